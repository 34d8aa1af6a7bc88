// The format tools' shared parts (format_comparison.h).

#include "format_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"

namespace gusuku::bench_common {

std::string readFolderAndOptions(int argc, char** argv, const char* usage,
                                 const std::function<bool(const std::string& option, const char* value)>& read_option) {
    std::string folder;
    for (int index = 1; index < argc; ++index) {
        const std::string argument = argv[index];
        const char* value = index + 1 < argc ? argv[index + 1] : nullptr;
        const bool is_option = argument.rfind("--", 0) == 0;
        if (is_option && value == nullptr) throw std::invalid_argument(argument + ": needs a value");
        if (is_option && read_option(argument, value)) ++index;
        else if (folder.empty() && !is_option) folder = argument;
        else throw std::invalid_argument("'" + argument + "': unknown argument");
    }
    if (folder.empty()) throw std::invalid_argument(usage);
    return folder;
}

glm::dvec3 parsePointOption(const std::string& option, const std::string& text) {
    glm::dvec3 point;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &point.x, &point.y, &point.z) != 3)
        throw std::invalid_argument(option + ": '" + text + "' is not E,N,U");
    return point;
}

void parseFrameSizeOption(const char* value, uint32_t& width, uint32_t& height) {
    if (std::sscanf(value, "%ux%u", &width, &height) != 2 || width < 16 || height < 16)
        throw std::invalid_argument(std::string("--size: '") + value + "' is not WxH of at least 16x16");
}

BuildingView southEastViewOf(const BakeSetData& bake_set) {
    glm::dvec3 low(INFINITY), high(-INFINITY);
    for (const glm::vec3& position : bake_set.building.positions) {
        low = glm::min(low, glm::dvec3(position));
        high = glm::max(high, glm::dvec3(position));
    }
    const glm::dvec3 centre = 0.5 * (low + high);
    const double radius = std::max(0.5 * glm::length(high - low), 1.0);
    return {centre + radius * glm::dvec3(1.8 * 0.6, -1.8 * 0.8, 0.6), centre};
}

double meanLightmapLuminance(const BakeSetImage& image) {
    double sum = 0.0, count = 0.0;
    for (size_t texel = 0; texel + 3 < image.rgba.size(); texel += 4)
        if (image.rgba[texel + 3] > 0.0f) {
            sum += luminanceRec709(glm::dvec3(image.rgba[texel], image.rgba[texel + 1], image.rgba[texel + 2]));
            count += 1.0;
        }
    return count > 0.0 ? sum / count : 0.0;
}

float sunlitGreyExposure(const BakeSetImage& lightmap, double sun_luminance) {
    return float(0.6 / (0.5 / M_PI * std::max(meanLightmapLuminance(lightmap) + sun_luminance, 1e-9)));
}

std::vector<uint8_t> changedRegion(const std::vector<uint8_t>& composite, const std::vector<uint8_t>& camera) {
    std::vector<uint8_t> region(composite.size() / 4, 0);
    for (size_t pixel = 0; pixel < region.size(); ++pixel)
        for (int channel = 0; channel < 3; ++channel)
            if (composite[pixel * 4 + channel] != camera[pixel * 4 + channel]) region[pixel] = 1;
    return region;
}

}  // namespace gusuku::bench_common

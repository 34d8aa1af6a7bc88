// Cloud cover from the camera frame (see weather_estimate.h).

#include "gusuku/weather_estimate.h"

#include <algorithm>
#include <cmath>

#include "gusuku/colour.h"
#include "gusuku/percentile.h"

namespace gusuku {
namespace {

float clearness(float value, float overcast_value, float clear_value) {
    return std::clamp((value - overcast_value) / (clear_value - overcast_value), 0.0f, 1.0f);
}

}  // namespace

CloudEstimate estimateCloudCover(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height) {
    if (rgba8.size() != size_t(width) * height * 4) return estimateCloudCover(nullptr, 0, 0);
    return estimateCloudCover(rgba8.data(), width, height);
}

CloudEstimate estimateCloudCover(const uint8_t* rgba8, uint32_t width, uint32_t height) {
    CloudEstimate estimate;
    estimate.cloud_cover = 1.0f;
    if (rgba8 == nullptr || width < 2 || height < 8) return estimate;

    std::vector<glm::vec3> linear(size_t(width) * height);
    std::vector<double> luminance(linear.size());
    for (size_t pixel = 0; pixel < linear.size(); ++pixel) {
        const uint8_t* bytes = rgba8 + 4 * pixel;
        linear[pixel] = srgbDecode(glm::vec3(bytes[0], bytes[1], bytes[2]) / 255.0f);
        luminance[pixel] = luminanceRec709(glm::dvec3(linear[pixel]));
    }
    if (*std::max_element(luminance.begin(), luminance.end()) <= 0.0) return estimate;

    // Shadows: the lower half's luminance spread, floored at 1/255 of linear so black pixels stay finite.
    const std::vector<double> lower(luminance.begin() + ptrdiff_t(size_t(height / 2) * width), luminance.end());
    constexpr double kFloor = 1.0 / 255.0;
    estimate.shadow_contrast =
        float(std::log(std::max(percentile(lower, 0.9), kFloor) / std::max(percentile(lower, 0.1), kFloor)));

    // Sky: the top rows' blueness, at the 75th percentile, so a sky that fills only part of them still counts.
    std::vector<double> blueness;
    for (size_t pixel = 0; pixel < size_t(std::max(1u, height / 8)) * width; ++pixel) {
        const glm::vec3& rgb = linear[pixel];
        if (rgb.b + rgb.r > 0.0f) blueness.push_back((rgb.b - rgb.r) / (rgb.b + rgb.r));
    }
    estimate.sky_blueness = blueness.empty() ? 0.0f : float(percentile(blueness, 0.75));

    const float clear = 0.5f * (clearness(estimate.shadow_contrast, kOvercastShadowContrast, kClearShadowContrast) +
                                clearness(estimate.sky_blueness, kOvercastSkyBlueness, kClearSkyBlueness));
    estimate.cloud_cover = 1.0f - clear;
    return estimate;
}

}  // namespace gusuku

// The sun's place in a sky map and the north it gives (gusuku/assets/sky_sun.h).
#include "gusuku/assets/sky_sun.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/maths/equirect.h"

namespace gusuku {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double luminanceAt(const ImageRGBA& sky, int x, int y) {
    const float* texel = sky.texel(x, y);
    double sum = 0.0;
    const double weights[3] = {0.2126, 0.7152, 0.0722};
    for (int c = 0; c < 3; ++c)
        if (std::isfinite(texel[c]) && texel[c] > 0.0f) sum += weights[c] * double(texel[c]);
    return sum;
}

// The texel centre's direction with north at u = 0 (the image's own frame: azimuth = 360 u).
glm::dvec3 imageDirection(const ImageRGBA& sky, int x, int y) {
    return equirectDirection((x + 0.5) / sky.width, (y + 0.5) / sky.height, 0.0);
}

}  // namespace

SkySunSighting findSkySun(const ImageRGBA& sky) {
    SkySunSighting sighting;
    if (sky.width <= 0 || sky.height <= 0 || sky.texels.size() != size_t(sky.width) * size_t(sky.height) * 4)
        return sighting;
    int peak_x = 0, peak_y = 0;
    double peak = 0.0;
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x)
            if (const double luminance = luminanceAt(sky, x, y); luminance > peak) {
                peak = luminance;
                peak_x = x;
                peak_y = y;
            }
    if (!(peak > 0.0)) return sighting;
    const glm::dvec3 peak_direction = imageDirection(sky, peak_x, peak_y);
    const double max_cos = std::cos(kSkySunMaxCoreRadiusDeg / kDegPerRad);
    // Flood fill from the peak; a texel beyond the radius ends the search (a cloud, not a disc), which also bounds
    // the work to the texels within 10 degrees of the peak.
    std::vector<uint8_t> visited(size_t(sky.width) * size_t(sky.height), 0);
    std::vector<std::pair<int, int>> stack = {{peak_x, peak_y}};
    visited[size_t(peak_y) * sky.width + peak_x] = 1;
    glm::dvec3 weighted_direction(0.0);
    std::vector<glm::dvec3> core;
    while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        const glm::dvec3 direction = imageDirection(sky, x, y);
        if (glm::dot(direction, peak_direction) < max_cos) return sighting;
        const double weight = luminanceAt(sky, x, y) * equirectTexelSolidAngle(y, sky.width, sky.height);
        weighted_direction += weight * direction;
        core.push_back(direction);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int ny = y + dy;
                if (ny < 0 || ny >= sky.height) continue;
                const int nx = (x + dx + sky.width) % sky.width;
                uint8_t& seen = visited[size_t(ny) * sky.width + nx];
                if (seen || luminanceAt(sky, nx, ny) < 0.5 * peak) continue;
                seen = 1;
                stack.push_back({nx, ny});
            }
    }
    const glm::dvec3 centre = glm::length(weighted_direction) > 0.0 ? glm::normalize(weighted_direction)
                                                                    : peak_direction;
    const glm::dvec2 uv = equirectCoordinates(centre, 0.0);
    sighting.found = true;
    sighting.image_azimuth_deg = std::fmod(360.0 * uv.x + 360.0, 360.0);
    sighting.elevation_deg = std::asin(std::clamp(centre.z, -1.0, 1.0)) * kDegPerRad;
    sighting.core_texels = int(core.size());
    for (const glm::dvec3& direction : core)
        sighting.core_radius_deg = std::max(
            sighting.core_radius_deg, std::acos(std::clamp(glm::dot(direction, centre), -1.0, 1.0)) * kDegPerRad);
    return sighting;
}

double northAzimuthInImageFromSun(double sun_image_azimuth_deg, double sun_azimuth_deg) {
    double north = std::fmod(sun_image_azimuth_deg - sun_azimuth_deg, 360.0);
    if (north < 0.0) north += 360.0;
    return north >= 360.0 ? 0.0 : north;
}

glm::dvec3 skySunDirectionEnu(const SkySunSighting& sighting, double north_azimuth_in_image_deg) {
    const double azimuth = (sighting.image_azimuth_deg - north_azimuth_in_image_deg) / kDegPerRad;
    const double elevation = sighting.elevation_deg / kDegPerRad;
    return {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
}

}  // namespace gusuku

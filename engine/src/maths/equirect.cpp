#include "gusuku/maths/equirect.h"

#include <cmath>
#include <numbers>

namespace gusuku {

namespace {
}

glm::dvec3 equirectDirection(double u, double v, double north_azimuth_in_image_deg) {
    const double azimuth = (360.0 * u - north_azimuth_in_image_deg) * std::numbers::pi / 180.0;
    const double elevation = (0.5 - v) * std::numbers::pi;
    const double c = std::cos(elevation);
    return {c * std::sin(azimuth), c * std::cos(azimuth), std::sin(elevation)};
}

glm::dvec2 equirectCoordinates(const glm::dvec3& direction_enu, double north_azimuth_in_image_deg) {
    const double z = std::fmax(-1.0, std::fmin(1.0, direction_enu.z));
    const double elevation = std::asin(z);
    const double azimuth_deg = std::atan2(direction_enu.x, direction_enu.y) * 180.0 / std::numbers::pi;
    double u = (azimuth_deg + north_azimuth_in_image_deg) / 360.0;
    u -= std::floor(u);
    const double v = 0.5 - elevation / std::numbers::pi;
    return {u, v};
}

double equirectTexelSolidAngle(int y, int width, int height) {
    const double theta = (double(y) + 0.5) / double(height) * std::numbers::pi;
    return (2.0 * std::numbers::pi / double(width)) * (std::numbers::pi / double(height)) * std::sin(theta);
}

}  // namespace gusuku

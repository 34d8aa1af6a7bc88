#include "gusuku/equirect.h"

#include <cmath>

namespace gusuku {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

glm::dvec3 equirectDirection(double u, double v, double north_azimuth_in_image_deg) {
    const double azimuth = (360.0 * u - north_azimuth_in_image_deg) * kPi / 180.0;
    const double elevation = (0.5 - v) * kPi;
    const double c = std::cos(elevation);
    return {c * std::sin(azimuth), c * std::cos(azimuth), std::sin(elevation)};
}

glm::dvec2 equirectCoordinates(const glm::dvec3& direction_enu, double north_azimuth_in_image_deg) {
    const double z = std::fmax(-1.0, std::fmin(1.0, direction_enu.z));
    const double elevation = std::asin(z);
    const double azimuth_deg = std::atan2(direction_enu.x, direction_enu.y) * 180.0 / kPi;
    double u = (azimuth_deg + north_azimuth_in_image_deg) / 360.0;
    u -= std::floor(u);
    const double v = 0.5 - elevation / kPi;
    return {u, v};
}

double equirectTexelSolidAngle(int y, int width, int height) {
    const double theta = (double(y) + 0.5) / double(height) * kPi;
    return (2.0 * kPi / double(width)) * (kPi / double(height)) * std::sin(theta);
}

}  // namespace gusuku

// The viewer's camera moves (see view_controls.h).

#include "view_controls.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace gusuku::view {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxElevationDeg = 85.0;
constexpr double kMinDistanceM = 0.5;
}  // namespace

void ViewState::orbit(double degrees) {
    const double radians = degrees * kPi / 180.0, c = std::cos(radians), s = std::sin(radians);
    const glm::dvec3 offset = position_enu - look_at_enu;
    position_enu = look_at_enu + glm::dvec3(c * offset.x - s * offset.y, s * offset.x + c * offset.y, offset.z);
}

void ViewState::pitch(double degrees) {
    const glm::dvec3 offset = position_enu - look_at_enu;
    const double distance = glm::length(offset), horizontal = std::hypot(offset.x, offset.y);
    const double elevation = std::atan2(offset.z, horizontal) * 180.0 / kPi;
    const double raised = std::clamp(elevation + degrees, -kMaxElevationDeg, kMaxElevationDeg) * kPi / 180.0;
    const glm::dvec2 across = horizontal > 1e-9 ? glm::dvec2(offset.x, offset.y) / horizontal : glm::dvec2(0, -1);
    position_enu = look_at_enu + glm::dvec3(across * (distance * std::cos(raised)), distance * std::sin(raised));
}

void ViewState::walk(double metres) {
    glm::dvec3 forward = look_at_enu - position_enu;
    forward.z = 0.0;
    if (glm::length(forward) < 1e-9) return;
    const glm::dvec3 step = glm::normalize(forward) * metres;
    position_enu += step;
    look_at_enu += step;
}

void ViewState::strafe(double metres) {
    const glm::dvec3 forward = look_at_enu - position_enu;
    glm::dvec3 right(forward.y, -forward.x, 0.0);
    if (glm::length(right) < 1e-9) return;
    const glm::dvec3 step = glm::normalize(right) * metres;
    position_enu += step;
    look_at_enu += step;
}

void ViewState::dolly(double fraction) {
    const glm::dvec3 offset = position_enu - look_at_enu;
    const double distance = glm::length(offset);
    const double wanted = std::max(distance * (1.0 - fraction), kMinDistanceM);
    position_enu = look_at_enu + offset * (wanted / distance);
}

}  // namespace gusuku::view

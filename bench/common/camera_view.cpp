// Camera placement for the tools (see camera_view.h).

#include "camera_view.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace gusuku::bench_common {

CameraPose lookAtPose(const glm::dvec3& position, const glm::dvec3& target) {
    const glm::dvec3 offset = target - position;
    if (!(glm::length(offset) > 1e-6)) throw std::invalid_argument("--look-at: the same point as --position");
    const glm::dvec3 forward = glm::normalize(offset);
    const glm::dvec3 world_up = std::abs(forward.z) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, world_up));
    const glm::dvec3 down = glm::cross(forward, right);
    CameraPose pose;
    pose.position_enu = position;
    pose.camera_to_enu = glm::dmat3(right, down, forward);
    return pose;
}

CameraIntrinsics intrinsicsForFov(uint32_t width, uint32_t height, double horizontal_fov_deg) {
    const double focal = 0.5 * double(width) / std::tan(0.5 * horizontal_fov_deg * std::numbers::pi / 180.0);
    return {focal, focal, 0.5 * width, 0.5 * height, width, height};
}

}  // namespace gusuku::bench_common

#pragma once
// A camera placed by eye for the tools (gusuku-render, gusuku-bench): a pose that looks from one ENU point at
// another, and pinhole intrinsics from a horizontal field of view, in gusuku/runtime.h's conventions.

#include <cstdint>

#include <glm/vec3.hpp>

#include "gusuku/runtime.h"

namespace gusuku::bench_common {

/// The pose of a camera at `position` looking at `target`, image up towards ENU +z (runtime.h's convention:
/// columns right, down, forward). std::invalid_argument when the two points coincide.
CameraPose lookAtPose(const glm::dvec3& position, const glm::dvec3& target);

/// Pinhole intrinsics of a width x height frame with this horizontal field of view, centred principal point.
CameraIntrinsics intrinsicsForFov(uint32_t width, uint32_t height, double horizontal_fov_deg);

}  // namespace gusuku::bench_common

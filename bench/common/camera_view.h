#pragma once
// A camera placed by eye for the tools (gusuku-render, gusuku-bench), from their --position and --look-at
// options; the maths is the runtime's own (CameraPose::lookingAt, CameraIntrinsics::fromFieldOfView).

#include <cstdint>

#include <glm/vec3.hpp>

#include "gusuku/runtime/runtime.h"

namespace gusuku::bench_common {

/// CameraPose::lookingAt, with the tools' message (naming --position and --look-at) when the points coincide.
CameraPose lookAtPose(const glm::dvec3& position, const glm::dvec3& target);

}  // namespace gusuku::bench_common

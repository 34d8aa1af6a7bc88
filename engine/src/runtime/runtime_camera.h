#pragma once
// The camera convention of runtime.h as matrices, and the checks of a frame's input. Private to gusuku_runtime.

#include <optional>
#include <string>

#include <glm/mat4x4.hpp>

#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// ENU -> Vulkan clip for the pinhole camera (runtime.h's convention): x_ndc = 2 u / width - 1, y_ndc = 2 v /
/// height - 1 (Vulkan's y points down like image rows), depth in [0, 1] between near_m and far_m.
glm::dmat4 cameraEnuToClip(const CameraIntrinsics& intrinsics, const CameraPose& pose, double near_m, double far_m);

/// "FIELD: PROBLEM" for a frame the runtime cannot render (size, NaN, a non-rotation, ...); nothing when valid.
std::optional<std::string> findFrameProblem(const FrameInput& frame, uint32_t width, uint32_t height);
/// The camera source and the semaphores of a frame for this runtime's options: one source, the one its camera
/// format takes, and at most kMaxFrameSemaphores of each kind, none null.
std::optional<std::string> findCameraProblem(const FrameInput& frame, const RuntimeOptions& options);
constexpr uint32_t kMaxFrameSemaphores = 8;

}  // namespace gusuku::runtime_detail

#pragma once
// What the runtime needs of the app's device (runtime.h, "Device requirements"), checked when it opens so a
// device that lacks something fails there, by name, not at the first frame. Private to gusuku_runtime.

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// Throws RuntimeError kDevice naming the first requirement the device does not meet: the queue family's graphics
/// and compute, each format's optimal-tiling features, the main pass's sample count and the frame size's limits
/// (image and framebuffer sides, the colour statistics' frame-sized storage buffer). (Vulkan 1.0 suffices; the
/// colour matches' 1.1 subgroups are optional: ColourStatisticsPass::deviceSupports.)
void checkDeviceRequirements(const GpuDevice& gpu, const RuntimeOptions& options);

}  // namespace gusuku::runtime_detail

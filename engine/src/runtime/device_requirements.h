#pragma once
// What the runtime needs of the app's device (runtime.h, "Device requirements"), checked when it opens so a
// device that lacks something fails there, by name, not at the first frame. Private to gusuku_runtime.

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// Throws RuntimeError kDevice naming the first requirement the device does not meet: the queue family's graphics
/// and compute, each format's optimal-tiling features, the main pass's sample count, the fixed parts' limits
/// (descriptor counts, push constants, vertex input, compute workgroups: device_requirements.cpp kFixedNeeds) and
/// the frame size's and the shadow map's limits (image, framebuffer and viewport sides, the camera pack's
/// workgroup count, the colour statistics' frame-sized storage buffer). (Vulkan 1.0 suffices; the
/// colour matches' 1.1 subgroups are optional: ColourStatisticsPass::deviceSupports.)
void checkDeviceRequirements(const GpuDevice& gpu, const RuntimeOptions& options);

/// Throws RuntimeError kDevice "bake set: FIELD: ..." when the bake set's images or mesh exceed the device's
/// limits: the lightmap side, the ground grid's sides and each texture's against maxImageDimension2D, the slots'
/// array layers against maxImageArrayLayers, the building's vertices against maxDrawIndexedIndexValue; each
/// message says what to bake differently.
void checkBakeSetLimits(const GpuDevice& gpu, const BakeSetData& bake_set);

}  // namespace gusuku::runtime_detail

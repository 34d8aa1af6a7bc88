#pragma once
// The runtime's frame as an ordered list of passes (docs/design.md 8). Every pass has CameraInput's lifecycle:
// it is made once in open() from the shared PassContext (and the few other passes it reads), owns its pipelines,
// descriptors and per-slot state, is prepared on the host for each frame by a call of its own (prepare(...),
// whose arguments say what it depends on), records into the frame's command buffer through the hooks below, and
// is destroyed with the runtime. The frame records the list's hooks phase by phase: every pass's recordBefore,
// then the main render pass with every pass's recordInMainPass, then every pass's recordAfter; a pass draws in
// the main pass only through its place in the list, never by comparing handles. Private to gusuku_runtime.

#include <cstdint>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

struct GpuScene;  // runtime_scene.h

/// What every pass is made from, owned by the runtime and outliving its passes.
struct PassContext {
    const GpuDevice& gpu;
    const RuntimeOptions& options;
    const GpuScene& scene;
};

/// One recording into a command buffer: the whole frame, or (profiled frame) one pass's share of it.
struct PassRecording {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint32_t slot = 0;                  ///< the frame slot being recorded
    const FrameInput* frame = nullptr;
    bool read_back = false;             ///< the composite is copied to the slot's host-visible buffer
    /// What this command buffer has bound at RUNTIME_FRAME_SET of the shading layout (FrameSet::bindOnce), as
    /// Vulkan's own command-buffer state: the set is bound once per command buffer, never again before the ground
    /// draw. On lavapipe (Mesa 22.3) each vkCmdBindDescriptorSets makes new gallium sampler views for the set's
    /// images, and when the next draw's vertex shader samples them (the ground's reads the ground geometry and
    /// irradiance) the driver keeps what it made until the device is destroyed: a rebind right before the ground
    /// draw grew resident memory by ~280 KB every frame (RuntimeMemory's test). Nothing that binds another layout's
    /// set 0 records between the building and the ground (the camera draw comes first in the main pass).
    VkDescriptorSet bound_frame_set = VK_NULL_HANDLE;
};

class FramePass {
public:
    virtual ~FramePass() = default;
    /// Outside any render pass, before the main pass (transfers, compute, passes of its own).
    virtual void recordBefore(PassRecording&) {}
    /// Inside the main pass (viewport set), in list order.
    virtual void recordInMainPass(PassRecording&) {}
    /// After the main pass has ended.
    virtual void recordAfter(PassRecording&) {}
};

}  // namespace gusuku::runtime_detail

#pragma once
// What the main pass draws into, shared by the passes inside it (docs/design.md 8): its render passes (one per
// MainPassVariant, compatible, so they share pipelines and framebuffers), the depth-stencil (or, msaa_samples > 1,
// the multisampled colour and depth), and per frame slot the composite (the app's compositeImage()) with its
// framebuffer. Not a pass itself: the frame begins and ends the main pass around the list's main-pass hooks.
// Private to gusuku_runtime.

#include <array>
#include <cstdint>
#include <vector>

#include "device_object.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_image.h"
#include "multisample_target.h"
#include "runtime_pipelines.h"

namespace gusuku::runtime_detail {

class MainTargets {
public:
    /// The composites start in TRANSFER_SRC_OPTIMAL, the layout compositeImage() promises.
    MainTargets(const PassContext& context, uint32_t slot_count);

    VkRenderPass renderPass(MainPassVariant variant) const { return render_passes_[size_t(variant)].get(); }
    VkSampleCountFlagBits samples() const { return samples_; }
    /// Begins `variant` of the main pass on the slot's framebuffer and sets the viewport. The variants that start
    /// the frame's main pass (kWhole, kFirst) do not load the composite: the camera-in draw writes every pixel of
    /// it first.
    void begin(VkCommandBuffer cmd, uint32_t slot, MainPassVariant variant) const;
    const GpuImage& composite(uint32_t slot) const { return slots_[slot].composite; }
    uint64_t memoryBytes() const;

private:
    struct Slot {
        GpuImage composite;      // the frame's colour target, RGBA8 sRGB
        Framebuffer framebuffer; // composite + depth, or the multisampled colour and depth + the composite
    };
    const PassContext context_;
    const VkSampleCountFlagBits samples_;
    GpuImage depth_;                      // msaa_samples 1
    MultisampleTarget msaa_colour_;       // msaa_samples > 1: what the main pass draws, resolved into the composite
    MultisampleTarget msaa_depth_;
    std::array<RenderPass, 4> render_passes_;  // MainPassVariant order
    std::vector<Slot> slots_;
};

}  // namespace gusuku::runtime_detail

#pragma once
// The camera frame into the runtime (docs/design.md 8 step 1; docs/runtime.md, "Camera formats"): whatever its
// format and wherever it lives, the camera is sampled in place by one draw at the start of the main pass
// (camera.frag), and, on frames with a colour match, by a packing kernel that gives the statistics their
// packed RGBA8 words (camera_pack.comp). Both read it through shaders/include/camera_sample.glsl.
//   - Host pixels go through a per-slot host-visible staging buffer into the runtime's own plane images (one
//     four-byte plane, or Y' and interleaved chroma planes): the one host copy an app that hands bytes asks for.
//   - The app's VkImage is read through a view the runtime keeps (a small cache, views made the first time an
//     image is met), in its own layout; TRANSFER_SRC_OPTIMAL is moved to SHADER_READ_ONLY_OPTIMAL and back.
//   - The zero-copy camera (options.camera_ycbcr_image, camera_ycbcr.h): the app's two-plane Y'CbCr image through
//     an immutable sampler with a sampler Y'CbCr conversion; no plane images, no staging.
// Each frame slot has its own descriptor set, updated only when its source changes. On the zero-copy route each
// cached view has its own set instead, written once when the view is made: an app that cycles a ring of
// imported images (up to the cache's 8) costs no descriptor write and no Vulkan object once each has been met. The frame's first pass in the
// list (frame_pass.h): its draw is the main pass's first. Private to gusuku_runtime.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "camera_interface.h"
#include "camera_ycbcr.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// The VkFormats of a camera format's planes (plane 1 VK_FORMAT_UNDEFINED for a four-byte format).
struct CameraPlaneFormats {
    VkFormat plane0 = VK_FORMAT_UNDEFINED;
    VkFormat plane1 = VK_FORMAT_UNDEFINED;
};
CameraPlaneFormats cameraPlaneFormats(CameraFormat format);

class CameraInput final : public FramePass {
public:
    /// The set layout, sampler, per-slot sets and staging buffers, the runtime's plane images (left in
    /// SHADER_READ_ONLY_OPTIMAL) and, when `pack` (a colour match is possible), the packed buffer and its kernel.
    CameraInput(const GpuDevice& gpu, const RuntimeOptions& options, uint32_t slot_count, bool pack);
    ~CameraInput() override;
    CameraInput(const CameraInput&) = delete;
    CameraInput& operator=(const CameraInput&) = delete;

    /// The camera-in draw's pipeline, for a render pass compatible with the main pass, at its sample count.
    void createDrawPipeline(VkRenderPass render_pass, VkSampleCountFlagBits samples);

    /// Host side of a frame in `slot`, whose previous frame has completed: host pixels into the slot's staging
    /// buffer, or the app image's view found or made; the slot's set pointed at the source when it changed.
    /// With the view cache full, the least recently used view is let go first: the caller must have waited for
    /// every frame in flight when needsEviction(frame) said so. Throws RuntimeError kInvalidFrame for a bad
    /// camera_image_format, kDevice when a view cannot be made. pack_grid: the colour match's sample grid this
    /// frame (ColourMatchPass::packGrid), or null.
    void prepare(uint32_t slot, const FrameInput& frame, const ColourStatisticsGrid* pack_grid);
    bool needsEviction(const FrameInput& frame) const;

    /// Before the frame's passes, outside a render pass: the staged pixels into the plane images, the app
    /// image's layout for sampling, and (pack_grid not null) the packed words of that sample grid's pixels for the
    /// statistics (the colour match's grid this frame: only what they read), each with its barriers.
    void recordBeforePasses(VkCommandBuffer cmd, uint32_t slot, const FrameInput& frame,
                            const ColourStatisticsGrid* pack_grid);
    /// The camera-in draw, first in the main pass (viewport set by the caller).
    void recordDraw(VkCommandBuffer cmd, uint32_t slot) const;
    /// After the frame's passes: the app image back to TRANSFER_SRC_OPTIMAL when it came so.
    void recordAfterPasses(VkCommandBuffer cmd, const FrameInput& frame) const;

    // The frame's hooks (frame_pass.h), in the slot and with the pack grid prepare() was given.
    void recordBefore(PassRecording& recording) override {
        recordBeforePasses(recording.cmd, recording.slot, *recording.frame, pack_grid_);
    }
    void recordInMainPass(PassRecording& recording) override { recordDraw(recording.cmd, recording.slot); }
    void recordAfter(PassRecording& recording) override { recordAfterPasses(recording.cmd, *recording.frame); }

    /// The packed camera (frame_width * frame_height RGBA8 words), written by recordBeforePasses at the pixels of
    /// its pack_grid (the others hold older frames' words or nothing).
    const GpuBuffer& packedBuffer() const { return packed_buffer_; }

    /// Lets go of an app image's view (the caller waited for the frames that read it); false when unknown.
    bool forget(VkImage image);
    uint64_t memoryBytes() const;

private:
    struct CachedView {
        VkImage image = VK_NULL_HANDLE;
        VkFormat format = VK_FORMAT_UNDEFINED;
        VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // sampled in (part of the key on the zero-copy route)
        VkImageView view = VK_NULL_HANDLE;
        uint64_t last_used = 0;
    };
    struct SlotSource {
        VkImageView plane0 = VK_NULL_HANDLE;  // what the slot's set points at now
        VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
        uint32_t view_decodes_srgb = 0;
    };
    static constexpr size_t kViewCacheSize = 8;

    void createPlanes(uint32_t slot_count);
    void createDescriptors(uint32_t slot_count);
    void createZeroCopyDescriptors();
    void createPackPipeline();
    bool holds(const CachedView& entry, const FrameInput& frame) const;
    size_t viewFor(const FrameInput& frame);  // the entry's index
    void stageHostPixels(uint32_t slot, const FrameInput& frame);
    void pointSlotAt(uint32_t slot, VkImageView plane0, VkImageView plane1, VkImageLayout layout);
    void recordUpload(VkCommandBuffer cmd, uint32_t slot) const;
    void recordPack(VkCommandBuffer cmd, uint32_t slot, const ColourStatisticsGrid& grid) const;
    void releaseView(CachedView& entry);
    void destroy() noexcept;

    const GpuDevice& gpu_;
    uint32_t width_, height_;
    CameraFormat format_;
    YcbcrModel ycbcr_model_;
    YcbcrRange ycbcr_range_;
    CameraPlaneFormats plane_formats_;
    GpuImage plane0_, plane1_;              // the runtime's own planes, for host pixels
    std::vector<GpuBuffer> staging_;        // per slot, host-visible: both planes back to back
    std::vector<SlotSource> slot_sources_;  // per slot
    std::vector<VkDescriptorSet> slot_sets_;
    std::array<CachedView, kViewCacheSize> views_{};
    std::vector<VkDescriptorSet> bound_sets_;  // per slot: the set its draw and pack bind this frame
    // The zero-copy route (null otherwise): the conversion and sampler, and one set per cached view.
    std::unique_ptr<YcbcrCameraSampler> ycbcr_;
    std::array<VkDescriptorSet, kViewCacheSize> view_sets_{};
    uint64_t use_counter_ = 0;
    const ColourStatisticsGrid* pack_grid_ = nullptr;  // this frame's (prepare)

    VkSampler sampler_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout packed_set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet packed_set_ = VK_NULL_HANDLE;
    VkPipelineLayout draw_layout_ = VK_NULL_HANDLE;
    VkPipeline draw_pipeline_ = VK_NULL_HANDLE;
    VkPipelineLayout pack_layout_ = VK_NULL_HANDLE;
    VkPipeline pack_pipeline_ = VK_NULL_HANDLE;
    GpuBuffer packed_buffer_;
    // The specialisation constants of camera_interface.h, for both stages.
    std::array<uint32_t, CAMERA_CONSTANT_COUNT> specialisation_values_{};
    std::array<VkSpecializationMapEntry, CAMERA_CONSTANT_COUNT> specialisation_entries_{};
    VkSpecializationInfo specialisation_{};
};

}  // namespace gusuku::runtime_detail

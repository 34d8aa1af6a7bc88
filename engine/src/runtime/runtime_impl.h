#pragma once
// gusuku_runtime's Runtime (runtime.h; docs/design.md 8), declared once for the files that implement it by job:
//   runtime.cpp             the option checks, open() and the headless wrapper
//   runtime_resources.cpp   the targets, descriptors, command buffer and fence made in open(), and their release
//   runtime_frame_pipelines.cpp  the frame's graphics pipelines
//   runtime_frame.cpp       the frame on the CPU: frame_preparation.h's pure functions, kept and uploaded
//   runtime_passes.cpp      the frame on the GPU, pass by pass (recorders only)
//   runtime_submission.cpp  frame slots, submission with the app's semaphores, read-back and the profiled frame
//   camera_input.cpp        the camera sampled in place, in its own format (camera_input.h)
// Everything is created in open(); a frame takes the next of frames_in_flight slots (waiting on its fence only
// when the GPU still works on it), records into its pre-allocated command buffer, submits it and returns;
// only the host-bytes path waits, to read the composite back. A frame allocates nothing. Private to
// gusuku_runtime.

#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera_input.h"
#include "colour_statistics_pass.h"
#include "frame_preparation.h"
#include "gusuku/maths/frame_lighting.h"
#include "gusuku/maths/shadow_fit.h"
#include "gusuku/runtime/runtime.h"
#include "multisample_target.h"
#include "runtime_depth_push.h"
#include "runtime_interface.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {

struct GraphicsPipelineDescription;  // runtime_pipelines.h

/// Throws RuntimeError(kInvalidFrame) for options out of their documented ranges (runtime.h).
void checkRuntimeOptions(const RuntimeOptions& options);

/// What one frame in flight owns (RuntimeOptions::frames_in_flight of them).
struct FrameSlot {
    GpuImage composite;                           // the frame's colour target, the app's compositeImage()
    VkFramebuffer framebuffer = VK_NULL_HANDLE;   // composite + the shared depth, or (msaa_samples > 1) the
                                                  // shared multisampled colour and depth + the composite
    GpuBuffer readback;                           // host-visible RGBA8, the host-bytes path only
    GpuBuffer ground_indices;                     // host-visible: the ground quads chosen, 6 indices each
    GpuBuffer ground_candidates;                  // host-visible vertex stream: per cell, the shadow may fall here
    uint64_t ground_generation = 0;               // which selection the two hold
    VkCommandBuffer command_buffer = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    bool in_flight = false;                       // submitted and its fence not yet waited for
};

class RuntimeImpl final : public Runtime {
public:
    RuntimeImpl(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options);
    ~RuntimeImpl() override;

    FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) override;
    FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) override;
    VkImage compositeImage() const override { return slots_[last_slot_].composite.handle(); }
    void waitIdle() override;
    void forgetCameraImage(VkImage image) override;
    void resetColourStatistics() override {
        if (statistics_) statistics_->reset();
        frames_to_next_measurement_ = 0;  // the next frame with a match measures the camera
    }
    void invalidateShadowMaps() override { building_shadow_valid_ = site_shadow_valid_ = false; }
    uint64_t deviceMemoryBytes() const override;
    LightmapFormat lightmapFormat() const override { return options_.lightmap_format; }
    uint32_t astcTextureCount() const override { return scene_.astc_texture_count; }

private:
    // runtime_resources.cpp and runtime_frame_pipelines.cpp
    void createGroundSelectionArrays();
    void createTargets();
    void createMainTargets();
    void createDescriptors();
    void createPipelines();
    void createCommands();
    void destroy() noexcept;

    VkSampleCountFlagBits mainPassSamples() const { return VkSampleCountFlagBits(options_.msaa_samples); }

    // runtime_frame.cpp
    void checkFrame(const FrameInput& frame) const;  // RuntimeError kInvalidFrame naming the field
    FrameInfo prepareFrame(const FrameInput& frame);
    void updateShadowState(const glm::dvec3& shadow_sun);
    void updateGroundSelection(bool wanted, bool include_baked_changes, const glm::dvec3& shadow_sun);
    void uploadGroundSelection(FrameSlot& slot);
    void prepareColourMatch(const FrameInput& frame, const FrameLighting& lighting, const SlotBlend& blend);

    // runtime_passes.cpp
    void recordFrameStart(VkCommandBuffer cmd, const FrameInput& frame);
    void recordStatistics(VkCommandBuffer cmd, const FrameInput& frame);
    void recordShadows(VkCommandBuffer cmd);
    void recordMaskedShadows(VkCommandBuffer cmd);
    void recordOccluder(VkCommandBuffer cmd);
    void recordBuilding(VkCommandBuffer cmd);
    void recordGround(VkCommandBuffer cmd);
    void recordReadback(VkCommandBuffer cmd);
    void beginMainPass(VkCommandBuffer cmd, VkRenderPass render_pass);

    // runtime_submission.cpp
    // Records `record` into the current slot's command buffer and submits it (with the frame's semaphores when
    // given); `wait` then blocks on the slot's fence. A template, not a std::function, so a frame allocates
    // nothing even where a standard library would box the lambda.
    template <typename Record> void submit(const Record& record, const FrameSync* sync, bool wait) {
        beginCommands();
        record(slots_[slot_].command_buffer);
        submitCommands(sync);
        if (wait) waitForSlot(slots_[slot_]);
    }
    void acquireSlot(const FrameInput& frame);
    void beginCommands();
    void submitCommands(const FrameSync* sync);
    void waitForSlot(FrameSlot& slot);
    void finishOutput(uint8_t* output_rgba8);

    // A copy, not a reference: GpuDevice is a value (gpu_device.h) and an app may pass a temporary
    // (Runtime::open(GpuDevice::describe(...), ...)). Every buffer, image and pass below points at this member,
    // which is declared first so it outlives them.
    const GpuDevice gpu_;
    RuntimeOptions options_;
    BakeSetManifest manifest_;
    std::vector<LabStatistics> slot_colour_statistics_;  // per slot (zero when the manifest has none)
    GpuScene scene_;

    // Per-frame resources, all made in open(). What each frame in flight needs of its own (the app may read a
    // composite while the next frame renders; the host writes the staging and ground buffers) is in a slot;
    // what only the GPU writes and reads within a frame is shared, ordered by barriers across frames.
    std::vector<FrameSlot> slots_;
    uint32_t slot_ = 0;       // the slot being recorded
    uint32_t last_slot_ = 0;  // the slot of the last frame submitted
    VkFormat main_depth_format_ = VK_FORMAT_UNDEFINED;  // depth-stencil (mainDepthStencilFormat)
    GpuImage depth_target_;              // msaa_samples 1
    MultisampleTarget msaa_colour_;      // msaa_samples > 1: what the main pass draws, resolved into the composite
    MultisampleTarget msaa_depth_;
    GpuImage building_shadow_;
    GpuImage site_shadow_;
    GpuBuffer uniform_buffer_;   // device-local FrameUniforms, written in each frame's command buffer
    std::unique_ptr<CameraInput> camera_;
    std::unique_ptr<ColourStatisticsPass> statistics_;  // null on a device without subgroup arithmetic
    GpuBuffer colour_state_without_match_;              // then the frame set's colour state: zeros, match off
    const GpuBuffer& colourStateBuffer() const {
        return statistics_ ? statistics_->stateBuffer() : colour_state_without_match_;
    }

    VkRenderPass main_passes_[4] = {};  // MainPassVariant order
    VkRenderPass shadow_pass_ = VK_NULL_HANDLE;
    VkFramebuffer building_shadow_framebuffer_ = VK_NULL_HANDLE;
    VkFramebuffer site_shadow_framebuffer_ = VK_NULL_HANDLE;
    VkSampler linear_sampler_ = VK_NULL_HANDLE;
    VkSampler shadow_sampler_ = VK_NULL_HANDLE;
    VkSampler shadow_depth_sampler_ = VK_NULL_HANDLE;  // nearest, no compare: the building's map read as depths
    VkSampler texture_sampler_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout frame_set_layout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout material_set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet frame_set_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> material_sets_;
    VkPipelineLayout depth_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout shading_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout masked_depth_layout_ = VK_NULL_HANDLE;  // the material set alone, MaskedDepthPushConstants
    VkPipeline shadow_pipeline_ = VK_NULL_HANDLE;       // the building into a shadow map
    VkPipeline site_shadow_pipeline_ = VK_NULL_HANDLE;  // the occluder into a shadow map (its own vertex stride)
    VkPipeline occluder_pipeline_ = VK_NULL_HANDLE;
    VkPipeline building_pipeline_ = VK_NULL_HANDLE;
    // Alpha-masked materials (issue 21 item 3), made only when the bake set has one: the building with its
    // discard, and the building's shadow map with depth_masked.frag's alpha test.
    VkPipeline building_masked_pipeline_ = VK_NULL_HANDLE;
    VkPipeline masked_shadow_pipeline_ = VK_NULL_HANDLE;
    VkPipeline ground_pipeline_ = VK_NULL_HANDLE;          // quads the building's shadow may reach
    VkPipeline ground_baked_pipeline_ = VK_NULL_HANDLE;    // quads only its baked light changes: no building shadow
    VkPipeline ground_sunless_pipeline_ = VK_NULL_HANDLE;  // the same with no sun at all: no shadow-map reads
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    void createMaskedPipelines(const GraphicsPipelineDescription& building, const GraphicsPipelineDescription& shadow);

    // This frame's CPU-side state, filled by prepareFrame.
    shader_interface::FrameUniforms uniforms_{};
    shader_interface::DepthOnlyPushConstants shadow_push_{};  // both shadow maps: the sun's view of this frame's fit
    shader_interface::DepthOnlyPushConstants occluder_push_{};
    bool sun_shines_ = false;
    // The shadow maps hold the sun's direction rounded to options_.shadow_sun_step_deg; they are re-rendered
    // only when that rounded direction changes (the building and the site are static).
    glm::dvec3 shadow_sun_direction_{0.0};
    ShadowFit shadow_fit_;
    bool building_shadow_valid_ = false;
    bool site_shadow_valid_ = false;
    bool render_building_shadow_ = false;
    bool render_site_shadow_ = false;
    // The ground quads drawn this frame (selectGroundQuads in ground_quads.h), and the reused host arrays that
    // choose them. What the ground quads were last chosen for (they are chosen again only when it changes).
    struct GroundSelectionKey {
        bool wanted = false;
        bool include_baked_changes = false;
        bool sun_shines = false;
        glm::dvec3 sun{0.0};
        bool operator==(const GroundSelectionKey&) const = default;
    };
    std::optional<GroundSelectionKey> ground_selection_key_;
    uint32_t ground_index_count_ = 0;         // all quads drawn, times 6
    uint32_t ground_shadow_index_count_ = 0;  // the first of them, which the building's shadow may reach
    std::vector<uint8_t> ground_cell_marked_;
    std::vector<float> ground_shadow_candidate_;  // per cell: 1 where the building's shadow may fall
    uint64_t ground_generation_ = 0;              // counts the selections; each slot uploads the newest
    std::vector<uint32_t> ground_quad_indices_;
    bool draw_ground_ = false;
    bool frame_set_bound_ = false;  // the frame set is bound in the command buffer being recorded
    bool site_shadows_ = false;
    LabStatistics frame_source_statistics_{};
    ColourMatchMode frame_colour_mode_ = ColourMatchMode::kOff;  // resolved (never kAuto)
    bool frame_measures_colour_ = false;  // this frame packs the camera and runs the statistics
    uint32_t frames_to_next_measurement_ = 0;  // kColourStatisticsInterval's countdown
    GroundMatchView frame_ground_view_;  // mode kGround: this frame's camera and light
};

}  // namespace gusuku::runtime_detail

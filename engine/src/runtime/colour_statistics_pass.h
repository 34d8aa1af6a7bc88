#pragma once
// The runtime's colour statistics pass (docs/design.md 8, pass 7): records, into the frame's command buffer, the two
// compute dispatches that measure the camera frame's Lab statistics and smooth them into the ColourMatchState
// that the next frame's building pass reads (through shaders/include/colour_match.glsl). Choices and the CPU
// reference: gusuku/maths/colour_match.h; GPU layout: shaders/include/colour_match_interface.h.
//
// Everything is allocated at construction (the state buffer, the partials buffer, two pipelines); recording
// allocates nothing. Not thread-safe. Every per-frame input is written in the command buffer (vkCmdUpdateBuffer)
// and ordered by barriers, so several frames may be in flight on one queue.

#include <cstdint>
#include <memory>

#include <vulkan/vulkan.h>

#include "colour_match_interface.h"
#include "sun_evidence_interface.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {

class ColourStatisticsPass {
public:
    /// Builds the pipelines and buffers for frames of frame_width x frame_height sampled every stride-th pixel,
    /// smoothing with the time constant smoothing_frames (RuntimeOptions). Throws RuntimeError kInvalidFrame for
    /// a stride of 0 or larger than a side, kDevice when the device lacks subgroup arithmetic in compute
    /// shaders (Vulkan 1.1's VkPhysicalDeviceSubgroupProperties) or a Vulkan call fails. gpu must outlive this.
    /// ground: the bake set's ground for mode kGround (groundMatchSceneFrom), or null when it has no albedo
    /// (recordGround then may not be called); its buffers are uploaded here.
    ColourStatisticsPass(const GpuDevice& gpu, uint32_t frame_width, uint32_t frame_height, uint32_t stride,
                         float smoothing_frames, const GroundMatchScene* ground = nullptr);
    ColourStatisticsPass(const ColourStatisticsPass&) = delete;
    /// Whether the device has what the pass needs: a Vulkan 1.1 instance (gpu.instance_api_version) for the
    /// query, and subgroup arithmetic in compute shaders. Without it the runtime opens with no colour match.
    static bool deviceSupports(const GpuDevice& gpu);
    ColourStatisticsPass& operator=(const ColourStatisticsPass&) = delete;

    /// Records a vkCmdUpdateBuffer of the state's host part (source statistics, mode, gain limit) and a barrier
    /// that makes it visible to the fragment and compute shaders after it. Outside a render pass. Throws
    /// RuntimeError kInvalidBakeSet for non-finite statistics or a negative sigma.
    void recordSourceUpdate(VkCommandBuffer cmd, const LabStatistics& source, ColourMatchMode mode,
                            float gain_limit);

    /// Records the statistics of camera_buffer (frame_width * frame_height packed RGBA8 words, R in the low
    /// byte, sRGB, row 0 at the top) and the state's update, outside a render pass. Barriers recorded:
    /// before, the caller's transfer, compute and host writes of camera_buffer and earlier shader reads of the
    /// state (fragment included when the queue has graphics) against these dispatches; between the two
    /// dispatches; after, the state's write against later fragment and compute reads, transfers and host reads
    /// (after the submission's fence). Re-binds the descriptor sets only when camera_buffer changes, which the
    /// caller may do only while no recorded command buffer of this pass is waiting to execute. After reset(),
    /// the next record() starts the smoothing over.
    void record(VkCommandBuffer cmd, const GpuBuffer& camera_buffer);

    /// Mode kGround's statistics (colour_statistics_ground.comp and its reduce) of camera_buffer for this view,
    /// with the barriers and camera-buffer rules of record(). Writes the view into its buffer in the command
    /// buffer, after the earlier frames' kernels have read theirs.
    /// Only when hasGround().
    void recordGround(VkCommandBuffer cmd, const GpuBuffer& camera_buffer, const GroundMatchView& view);
    bool hasGround() const { return ground_statistics_pipeline_ != nullptr; }
    /// The ground kernel's sample grid (groundMatchStride of the frame and the statistics stride).
    const ColourStatisticsGrid& groundGrid() const { return sample_grid_ground_; }
    /// Mode kGround's cells and E_without on the GPU (GROUND_MATCH_CELL_BINDING, GROUND_MATCH_IRRADIANCE_BINDING),
    /// which the sun-evidence pass reads too. Only when hasGround().
    const GpuBuffer& groundCellBuffer() const { return ground_cell_buffer_; }
    const GpuBuffer& groundIrradianceBuffer() const { return ground_irradiance_buffer_; }
    /// The ground kernel's view of a frame (what recordGround writes into its buffer). Only when hasGround().
    shader_interface::GroundMatchFrame groundFrameFor(const GroundMatchView& view) const;
    /// The sun-evidence estimator (sun_evidence_pass.h) shares the ground kernel's march and camera read: after
    /// enableSunEvidence() (once, before recording; allocates sunEvidenceBuffer()'s samples), the next recordGround
    /// after each requestSunEvidence(frame) also writes the estimator's samples there. Only when hasGround().
    void enableSunEvidence();
    void requestSunEvidence(const shader_interface::SunEvidenceGroundFrame& frame);
    /// SunEvidenceGroundFrame, then SunEvidenceSampleGpu per sample of groundGrid() (sun_evidence_interface.h).
    const GpuBuffer& sunEvidenceBuffer() const { return ground_sun_evidence_buffer_; }

    /// The next record() or recordGround() forgets the smoothed statistics and gain (a cut in the camera feed).
    void reset() { reset_pending_ = true; }

    /// The state buffer (one ColourMatchState), for the building pass's descriptor set.
    const GpuBuffer& stateBuffer() const { return state_buffer_; }
    /// The state as the GPU left it; only once the submission that wrote it has completed.
    shader_interface::ColourMatchState readState() const;

    const ColourStatisticsGrid& grid() const { return grid_; }
    uint32_t minValidSamples() const { return min_valid_samples_; }
    float smoothingWeight() const { return smoothing_weight_; }

private:
    const GpuDevice& gpu_;
    uint32_t frame_width_, frame_height_;
    ColourStatisticsGrid grid_;
    uint32_t workgroups_x_ = 0, workgroups_y_ = 0;
    uint32_t partials_per_workgroup_ = 0;
    uint32_t min_valid_samples_ = 0;
    float smoothing_weight_ = 1.0f;
    bool queue_has_graphics_ = false;
    bool reset_pending_ = false;
    VkBuffer bound_camera_buffer_ = VK_NULL_HANDLE;
    GpuBuffer state_buffer_;
    GpuBuffer partial_buffer_;
    ComputePipeline statistics_pipeline_;
    ComputePipeline reduce_pipeline_;
    // Mode kGround (all null / empty without a ground albedo).
    ColourStatisticsGrid sample_grid_ground_;  // the ground kernel's samples (groundMatchStride)
    uint32_t ground_workgroups_x_ = 0, ground_workgroups_y_ = 0;
    uint32_t ground_min_samples_ = 0;
    float ground_start_height_m_ = 0.0f;
    GroundGrid ground_grid_;
    uint32_t ground_slot_count_ = 0;
    VkBuffer ground_bound_camera_buffer_ = VK_NULL_HANDLE;
    GpuBuffer ground_cell_buffer_;
    GpuBuffer ground_irradiance_buffer_;
    GpuBuffer ground_frame_buffer_;  // host-visible GroundMatchFrame
    GpuBuffer ground_partial_buffer_;
    GpuBuffer ground_sun_evidence_buffer_;  // the frame alone until enableSunEvidence(), then the samples too
    shader_interface::SunEvidenceGroundFrame sun_evidence_frame_{};  // measure 1: requested for the next recordGround
    std::unique_ptr<ComputePipeline> ground_statistics_pipeline_;
    std::unique_ptr<ComputePipeline> ground_reduce_pipeline_;
};

}  // namespace gusuku

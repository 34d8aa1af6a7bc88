#pragma once
// The sun read from the site's shadows in the camera frame (issue 41 items 1 and 2; gusuku/maths/sun_evidence.h holds
// the model, the choices and the CPU reference): on each frame that the ground colour match measures (its camera
// pack then holds the ground grid's pixels), after the main pass (so the site's shadow map is this frame's), two
// dispatches (on one such frame in kSunEvidenceMeasurementInterval): sun_evidence.comp classifies each ground sample as lit or site-shadowed and writes its ratio against
// the bake's prediction without the sun, and sun_evidence_reduce.comp takes the trimmed means about the medians into the frame slot's
// SunEvidenceResult in a host-visible buffer. The host reads a slot's result once the slot's fence says its frame has
// finished (latest()): no wait the frame would not make, nothing allocated per frame. A FramePass (frame_pass.h).
// Private to gusuku_runtime.

#include <cstdint>
#include <optional>
#include <vector>

#include "colour_match_pass.h"
#include "device_object.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/maths/sun_evidence.h"
#include "gusuku/runtime/runtime_sun_evidence.h"
#include "runtime_interface.h"
#include "shadow_pass.h"
#include "sun_evidence_interface.h"

namespace gusuku::runtime_detail {

class SunEvidencePass final : public FramePass {
public:
    /// statistics: the colour match's statistics pass, with ground (hasGround()); its cells, E_without and sample grid
    /// are read, not copied. packed_camera: the camera pack's buffer. shadows: the site's map is sampled.
    SunEvidencePass(const PassContext& context, const ColourStatisticsPass& statistics, const GpuBuffer& packed_camera,
                    const ShadowPass& shadows, uint32_t frames_in_flight);

    /// Host side, after the slot's fence: measure (the colour match measures the ground this frame and the sun is
    /// up); view: the frame's camera and blend with the clear-sky E_sun (sun_scale 1) and sun_shines set; uniforms:
    /// the site map's projection and bias; utc: the frame's instant, kept with its result.
    void prepare(uint32_t slot, bool measure, const GroundMatchView& view,
                 const shader_interface::FrameUniforms& uniforms, double utc_unix_seconds);
    void recordAfter(PassRecording& recording) override;
    /// The next frame the colour match measures measures the sun too (a cut in the camera feed: resetColourStatistics).
    void reset() { measurements_to_skip_ = 0; }

    /// The newest result among the slots whose frames have finished (finished(slot): the submission's fence status),
    /// or nothing before the first.
    template <typename Finished>
    std::optional<RuntimeSunEvidence> latest(const Finished& finished) {
        for (uint32_t slot = 0; slot < slots_.size(); ++slot)
            if (slots_[slot].pending && finished(slot)) harvest(slot);
        return latest_;
    }
    /// The samples of the last measurement (tests: SunEvidenceSampleGpu per sample of the ground grid).
    const GpuBuffer& sampleBuffer() const { return sample_buffer_; }
    const ColourStatisticsGrid& grid() const { return grid_; }
    uint64_t memoryBytes() const { return sample_buffer_.size() + frame_buffer_.size() + result_buffer_.size(); }

private:
    struct Slot {
        bool pending = false;  // a measurement was recorded into this slot's frame and not yet read
        uint64_t frame_index = 0;
        double utc_unix_seconds = 0.0;
    };
    void createSamplePipeline(const ColourStatisticsPass& statistics, const GpuBuffer& packed_camera,
                              const ShadowPass& shadows);
    void harvest(uint32_t slot);

    const PassContext context_;
    const ColourStatisticsPass& statistics_;
    ColourStatisticsGrid grid_;
    uint32_t workgroups_x_ = 0, workgroups_y_ = 0;
    GpuBuffer sample_buffer_;  // device-local SunEvidenceSampleGpu per sample
    GpuBuffer frame_buffer_;   // device-local GroundMatchFrame, written in the command buffer
    GpuBuffer result_buffer_;  // host-visible SunEvidenceResult per frame slot
    Sampler site_sampler_;     // bilinear depth compare, lit outside the map
    DescriptorSetLayout set_layout_;
    DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
    PipelineLayout layout_;
    Pipeline pipeline_;
    ComputePipeline reduce_;
    std::vector<Slot> slots_;
    float ground_top_m_ = 0.0f;  // the highest ground cell: the step check's walk ends above it
    // This frame (prepare).
    bool measure_ = false;
    uint32_t slot_ = 0;
    shader_interface::GroundMatchFrame frame_{};
    shader_interface::SunEvidencePushConstants push_{};
    uint64_t frames_ = 0;  // frames prepared: the serial of the next measurement
    uint32_t measurements_to_skip_ = 0;  // the colour match's measurements before the next of this pass
    std::optional<RuntimeSunEvidence> latest_;
};

}  // namespace gusuku::runtime_detail

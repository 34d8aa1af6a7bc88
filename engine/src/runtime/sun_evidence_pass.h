#pragma once
// The sun read from the site's shadows in the camera frame (issue 41 items 1 and 2; gusuku/maths/sun_evidence.h holds
// the model, the choices and the CPU reference), on one of the ground colour match's measurements in
// kSunEvidenceMeasurementInterval. The ground match's own kernel (colour_statistics_ground.comp) classifies each of
// its samples for the estimator as it measures (one ray march and one camera read for both; this pass requests it
// in prepare); after the main pass, when the frame's site map is drawn, one dispatch of sun_evidence_reduce.comp
// settles the samples the site map decides and takes the trimmed means about the medians into the frame slot's
// SunEvidenceResult in a host-visible buffer. The host reads a slot's result once the slot's fence says its frame
// has finished (latest()): no wait the frame would not make, nothing allocated per frame. A FramePass (frame_pass.h).
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
    /// statistics: the colour match's statistics pass, with ground (hasGround()); its kernel classifies the samples
    /// (enableSunEvidence, requestSunEvidence). shadows: the site's map is sampled.
    SunEvidencePass(const PassContext& context, ColourStatisticsPass& statistics, const ShadowPass& shadows,
                    uint32_t frames_in_flight);

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
    /// The samples of the last measurement (SunEvidenceGroundFrame, then SunEvidenceSampleGpu per sample of grid()).
    const GpuBuffer& sampleBuffer() const { return statistics_.sunEvidenceBuffer(); }
    const ColourStatisticsGrid& grid() const { return grid_; }
    uint64_t memoryBytes() const { return sampleBuffer().size() + result_buffer_.size(); }

private:
    struct Slot {
        bool pending = false;  // a measurement was recorded into this slot's frame and not yet read
        uint64_t frame_index = 0;
        double utc_unix_seconds = 0.0;
    };
    void createReducePipeline(const ShadowPass& shadows);
    void harvest(uint32_t slot);

    const PassContext context_;
    ColourStatisticsPass& statistics_;
    ColourStatisticsGrid grid_;
    GpuBuffer result_buffer_;  // host-visible SunEvidenceResult per frame slot
    Sampler site_sampler_;     // bilinear depth compare, lit outside the map
    DescriptorSetLayout set_layout_;
    DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
    PipelineLayout layout_;
    Pipeline pipeline_;  // sun_evidence_reduce.comp
    std::vector<Slot> slots_;
    float ground_top_m_ = 0.0f;  // the highest ground cell: the step check's walk ends above it
    // This frame (prepare).
    bool measure_ = false;
    uint32_t slot_ = 0;
    uint64_t frames_ = 0;  // frames prepared: the serial of the next measurement
    uint32_t measurements_to_skip_ = 0;  // the colour match's measurements before the next of this pass
    std::optional<RuntimeSunEvidence> latest_;
};

}  // namespace gusuku::runtime_detail

#pragma once
// The colour match (docs/design.md 8, pass 7; docs/runtime.md): each frame resolves the mode the app asked for
// and the baked appearance's statistics it matches from, and on one frame in kColourStatisticsInterval (the first
// of a mode, the first after a reset) measures the camera with ColourStatisticsPass, whose smoothed state the
// building reads through the frame set. A device without subgroup arithmetic gets no statistics pass and a state
// of zeros (match off), and refuses frames that ask for a match. A FramePass (frame_pass.h). Private to
// gusuku_runtime.

#include <cstdint>
#include <memory>
#include <vector>

#include "colour_statistics_pass.h"
#include "frame_pass.h"
#include "frame_preparation.h"

namespace gusuku::runtime_detail {

class ColourMatchPass final : public FramePass {
public:
    /// ground: mode kGround's ground (null without ground albedo); packed_camera: the camera pack's buffer
    /// (CameraInput::packedBuffer), which the statistics read.
    ColourMatchPass(const PassContext& context, const BakeSetManifest& manifest, const GroundMatchScene* ground,
                    const GpuBuffer& packed_camera);

    /// Host side: this frame's mode (kAuto resolved: kGround where the bake set and the device allow it, else
    /// kOff, so a default never makes a frame fail), source and, mode kGround, view; whether it measures. Throws
    /// RuntimeError kInvalidFrame for a mode this device or bake set cannot run.
    void prepare(const FrameInput& frame, const FrameLighting& lighting, const SlotBlend& blend, bool sun_shines);
    /// The camera pixels this frame's statistics read (the camera packs only those), or null on a frame that does
    /// not measure.
    const ColourStatisticsGrid* packGrid() const;
    void recordBefore(PassRecording& recording) override;

    /// The next measurement starts the smoothing over, and the next frame with a match measures.
    void reset();
    /// The state the building reads (one ColourMatchState).
    const GpuBuffer& stateBuffer() const { return statistics_ ? statistics_->stateBuffer() : state_without_match_; }
    /// The statistics pass (null on a device without subgroup arithmetic), and whether this frame measures the ground:
    /// then the camera pack holds the ground grid's pixels, which the sun-evidence pass reads too.
    const ColourStatisticsPass* statistics() const { return statistics_.get(); }
    ColourStatisticsPass* statistics() { return statistics_.get(); }
    bool measuresGround() const { return measures_ && mode_ == ColourMatchMode::kGround; }

private:
    const PassContext context_;
    const GpuBuffer& packed_camera_;
    std::unique_ptr<ColourStatisticsPass> statistics_;  // null on a device without subgroup arithmetic
    GpuBuffer state_without_match_;                     // then the state: zeros, match off
    std::vector<LabStatistics> slot_statistics_;        // per manifest slot (zero when it has none)
    LabStatistics source_statistics_{};
    ColourMatchMode mode_ = ColourMatchMode::kOff;      // resolved (never kAuto)
    bool measures_ = false;                             // this frame packs the camera and runs the statistics
    uint32_t frames_to_next_measurement_ = 0;           // kColourStatisticsInterval's countdown
    GroundMatchView ground_view_;                       // mode kGround: this frame's camera and light
};

}  // namespace gusuku::runtime_detail

// The colour match (colour_match_pass.h).

#include "colour_match_pass.h"

namespace gusuku::runtime_detail {

namespace {

std::vector<LabStatistics> slotColourStatistics(const BakeSetManifest& manifest) {
    std::vector<LabStatistics> per_slot;
    for (const BakeSetSlot& slot : manifest.slots) {
        LabStatistics statistics;
        if (slot.colour_statistics) {
            statistics.mean = glm::vec3(slot.colour_statistics->lab_mean);
            statistics.standard_deviation = glm::vec3(slot.colour_statistics->lab_sigma);
        }
        per_slot.push_back(statistics);
    }
    return per_slot;
}

}  // namespace

ColourMatchPass::ColourMatchPass(const PassContext& context, const BakeSetManifest& manifest,
                                 const GroundMatchScene* ground, const GpuBuffer& packed_camera)
    : context_(context), packed_camera_(packed_camera), slot_statistics_(slotColourStatistics(manifest)) {
    const RuntimeOptions& options = context.options;
    // The colour matches need subgroup arithmetic (Vulkan 1.1); the default frame (match off) does not, so a
    // device without it opens with no statistics pass and refuses frames that ask for a match.
    if (ColourStatisticsPass::deviceSupports(context.gpu)) {
        statistics_ = std::make_unique<ColourStatisticsPass>(context.gpu, options.frame_width, options.frame_height,
                                                             options.statistics_stride,
                                                             // T frames = T / interval measurements
                                                             options.statistics_smoothing_frames /
                                                                 float(kColourStatisticsInterval),
                                                             ground);
        return;
    }
    state_without_match_ = GpuBuffer(context.gpu, sizeof(shader_interface::ColourMatchState),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal);
    const shader_interface::ColourMatchState match_off{};  // zeros: mode off, the identity transfer
    state_without_match_.upload(&match_off, sizeof match_off);
}

void ColourMatchPass::prepare(const FrameInput& frame, const FrameLighting& lighting, const SlotBlend& blend,
                              bool sun_shines) {
    ColourMatchMode requested = frame.colour_match;
    if (requested == ColourMatchMode::kAuto)
        requested = statistics_ && statistics_->hasGround() ? ColourMatchMode::kGround : ColourMatchMode::kOff;
    if (requested != ColourMatchMode::kOff && !statistics_)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "frame: colour_match: needs subgroup arithmetic in compute shaders (a Vulkan 1.1 instance "
                           "and device), which this device lacks: use colour_match off");
    if (requested == ColourMatchMode::kGround && !statistics_->hasGround())
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "frame: colour_match: ground needs the bake set's ground_grid.albedo, which this bake set "
                           "lacks (bake it again)");
    const ColourSource source =
        colourSourceFor(requested, frame.mode == RenderMode::kDirectOnly, blend, slot_statistics_);
    if (source.mode == ColourMatchMode::kGround) ground_view_ = groundMatchViewFor(frame, lighting, sun_shines, blend);
    if (source.statistics) source_statistics_ = *source.statistics;
    if (source.mode != mode_) frames_to_next_measurement_ = 0;
    mode_ = source.mode;
    measures_ = source.mode != ColourMatchMode::kOff && frames_to_next_measurement_ == 0;
    if (measures_) frames_to_next_measurement_ = kColourStatisticsInterval - 1;
    else if (frames_to_next_measurement_ > 0) --frames_to_next_measurement_;
}

// The pack writes only the pixels this frame's statistics read (the ground grid, or the Lab modes' grid), and
// only on the frames that measure.
const ColourStatisticsGrid* ColourMatchPass::packGrid() const {
    if (!statistics_ || !measures_) return nullptr;
    return mode_ == ColourMatchMode::kGround ? &statistics_->groundGrid() : &statistics_->grid();
}

void ColourMatchPass::recordBefore(PassRecording& recording) {
    if (!statistics_) return;  // no colour match on this device (prepare refused any other mode)
    const VkCommandBuffer cmd = recording.cmd;
    // Every frame: the mode and the source follow the frame; the smoothed camera state stays between measurements.
    statistics_->recordSourceUpdate(cmd, source_statistics_, mode_, context_.options.colour_gain_limit);
    if (!measures_) return;
    if (mode_ == ColourMatchMode::kGround) statistics_->recordGround(cmd, packed_camera_, ground_view_);
    else if (mode_ != ColourMatchMode::kOff) statistics_->record(cmd, packed_camera_);
}

void ColourMatchPass::reset() {
    if (statistics_) statistics_->reset();
    frames_to_next_measurement_ = 0;  // the next frame with a match measures the camera
}

}  // namespace gusuku::runtime_detail

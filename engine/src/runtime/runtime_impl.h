#pragma once
// gusuku_runtime's Runtime (runtime.h; docs/design.md 8): the frame as an ordered list of passes (frame_pass.h),
// each owning its pipelines, descriptors and per-slot state. RuntimeImpl makes them in open(), prepares them on the
// host in the order their inputs need, and records the list. Its files, by job:
//   runtime.cpp             the option checks, open() (the passes made) and the headless wrapper
//   runtime_frame.cpp       the frame on the CPU: frame_preparation.h's pure functions, handed to each pass's prepare
//   runtime_submission.cpp  the list recorded: the whole frame, or pass by pass for the profiled frame
//   runtime_resources.cpp   what the runtime weighs in device memory
// The passes, in list order: frame_set (the uniforms), camera_input (the camera sampled in place, its draw first
// in the main pass), colour_match_pass (the statistics), shadow_pass, occluder_pass, building_pass,
// ground_pass (the ground ratio), sun_evidence_pass (the sun read from the site's shadows in the camera frame),
// frame_submission (slots, fences, the read-back); what they share: material_sets,
// main_targets. A frame allocates nothing. Private to gusuku_runtime.

#include <array>
#include <memory>

#include "building_pass.h"
#include "camera_input.h"
#include "colour_match_pass.h"
#include "frame_pass.h"
#include "frame_set.h"
#include "frame_submission.h"
#include "ground_pass.h"
#include "gusuku/runtime/runtime.h"
#include "main_targets.h"
#include "material_sets.h"
#include "occluder_pass.h"
#include "runtime_scene.h"
#include "shadow_pass.h"
#include "sun_evidence_pass.h"

namespace gusuku::runtime_detail {

/// Throws RuntimeError(kInvalidFrame) for options out of their documented ranges (runtime.h).
void checkRuntimeOptions(const RuntimeOptions& options);

/// A pass in the frame's list, and the PassTimings figure each of its hooks counts toward in the profiled frame
/// (null: the pass has no such hook). The profiled frame submits each run of hooks with one figure on its own.
struct ListedPass {
    FramePass* pass = nullptr;
    double PassTimings::*before = nullptr;
    double PassTimings::*in_main_pass = nullptr;
    double PassTimings::*after = nullptr;
};

/// What latestSunEvidence (gusuku/runtime/runtime_sun_evidence.h) asks of a runtime: RuntimeImpl and the headless
/// wrapper that holds one.
class SunEvidenceSource {
public:
    virtual std::optional<RuntimeSunEvidence> latestSunEvidence() = 0;

protected:
    ~SunEvidenceSource() = default;
};

class RuntimeImpl final : public Runtime, public SunEvidenceSource {
public:
    RuntimeImpl(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options);
    ~RuntimeImpl() override;

    FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) override;
    FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) override;
    VkImage compositeImage() const override { return targets_->composite(submission_->lastSlot()).handle(); }
    void waitIdle() override;
    void forgetCameraImage(VkImage image) override;
    void resetColourStatistics() override {
        colour_->reset();
        if (sun_evidence_) sun_evidence_->reset();
    }
    void invalidateShadowMaps() override { shadows_->invalidate(); }
    uint64_t deviceMemoryBytes() const override;
    LightmapFormat lightmapFormat() const override { return options_.lightmap_format; }
    uint32_t astcTextureCount() const override { return scene_.astc_texture_count; }
    std::optional<RuntimeSunEvidence> latestSunEvidence() override;
    /// Measuring frames skip the sun evidence while off (the cost test times the frame with and without it).
    void setSunEvidenceEnabled(bool enabled) { sun_evidence_enabled_ = enabled; }

private:
    static constexpr size_t kPassCount = 9;
    static constexpr int kPhaseCount = 3;  // before, in the main pass, after
    PassContext passContext() const { return {gpu_, options_, scene_}; }
    void makePasses(const BakeSetData& bake_set);

    // runtime_frame.cpp
    void checkFrame(const FrameInput& frame) const;  // RuntimeError kInvalidFrame naming the field
    FrameInfo prepareFrame(const FrameInput& frame);
    void prepareSunEvidence(const FrameInput& frame, const SlotBlend& blend, bool measure);

    // runtime_submission.cpp
    void acquireSlot(const FrameInput& frame);
    double PassTimings::*hookTiming(size_t step) const;
    void recordSteps(PassRecording& recording, size_t first, size_t end, MainPassVariant variant, bool all_hooks);
    // Records `record` into the slot's command buffer and submits it (with the frame's semaphores when given);
    // `wait` then blocks on the slot's fence. A template, not a std::function, so a frame allocates nothing even
    // where a standard library would box the lambda.
    template <typename Record>
    void submit(const FrameInput& frame, bool read_back, const Record& record, const FrameSync* sync, bool wait) {
        PassRecording recording{submission_->begin(), submission_->slot(), &frame, read_back};
        record(recording);
        submission_->submit(sync);
        if (wait) submission_->wait();
    }

    // A copy, not a reference: GpuDevice is a value (gpu_device.h) and an app may pass a temporary
    // (Runtime::open(GpuDevice::describe(...), ...)). Every pass points at this member, declared first so it
    // outlives them; the passes after it are declared in the order they are made (each outlives those that read it).
    const GpuDevice gpu_;
    RuntimeOptions options_;
    BakeSetManifest manifest_;
    GpuScene scene_;
    std::unique_ptr<MainTargets> targets_;
    std::unique_ptr<FrameSubmission> submission_;
    std::unique_ptr<MaterialSets> materials_;
    std::unique_ptr<ShadowPass> shadows_;
    std::unique_ptr<CameraInput> camera_;
    std::unique_ptr<ColourMatchPass> colour_;
    std::unique_ptr<FrameSet> frame_set_;
    std::unique_ptr<OccluderPass> occluder_;
    std::unique_ptr<BuildingPass> building_;
    std::unique_ptr<GroundPass> ground_;
    std::unique_ptr<SunEvidencePass> sun_evidence_;  // null without ground albedo, occluder or subgroup arithmetic
    FramePass no_sun_evidence_;                      // its place in the list then: no hooks
    bool sun_evidence_enabled_ = true;
    std::array<ListedPass, kPassCount> passes_{};  // the frame, in order
};

}  // namespace gusuku::runtime_detail

#pragma once
// The runtime's reading of the sun from the real site's own shadows in the camera frame (issue 41 items 1 and 2;
// the model and its CPU reference: gusuku/maths/sun_evidence.h; docs/platform-light.md, "The sun from the frame").
//
// The runtime measures it on the GPU within the frame, on the frames its ground colour match measures the camera
// (ColourMatch::kGround, or kAuto on a bake set with ground albedo: one frame in kColourStatisticsInterval), on one
// of those in kSunEvidenceMeasurementInterval, when the
// sun is above the horizon and the bake set has a site occluder (whose shadow map gives the boundary). It reads the
// result back once that frame's fence has signalled, never waiting for it: the newest result lags the frame by up
// to frames_in_flight frames (none on the host-bytes path, which waits for its frame anyway).
//
// The loop an app runs each frame (C: gusuku_runtime_sun_evidence, then gusuku_sun_filter_update):
//     runtime->renderFrame(frame, ...);
//     std::optional<RuntimeSunEvidence> reading = latestSunEvidence(*runtime);
//     const SunEvidence* evidence = reading ? &reading->estimate.evidence : nullptr;
//     const SunVisibilityState& state = filter.update(now, regime, evidence);
//     next_frame.weather.sun_scale = state.sun_visibility * state.sun_strength;
// An app whose exposure is the camera's metered one feeds sunEvidenceForFilter(reading->estimate, true).evidence
// instead (gusuku/maths/sun_cue_choice.h), which also weighs the metered ground where no boundary is in view.
// The same reading may come back for several frames (it changes when a newer measurement finishes; frame_index
// says which); feeding it to the filter each frame is right, as the filter weighs time, not calls.

#include <cstdint>
#include <optional>

#include "gusuku/maths/sun_evidence.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {

/// The runtime measures the sun on one of the colour match's measurements in this many (one frame in
/// kColourStatisticsInterval x this: 12, a reading every 0.4 s at 30 frames a second), and on the first after
/// resetColourStatistics: its cost is about 4 ms of lavapipe's CPU a measurement at 640x360, about 0.35 ms a frame so
/// spread (docs/platform-light.md, "Cost"). SunVisibilityFilter holds its state between the readings (its 0.5 s hold
/// and 1.5 s fade are longer than the gap).
inline constexpr uint32_t kSunEvidenceMeasurementInterval = 3;

struct RuntimeSunEvidence {
    /// evidence (for SunVisibilityFilter::update), the cue that decided (kNone or kMeteredGround: no boundary in
    /// view, confidence 0; sunEvidenceForFilter weighs the metered ground)
    /// and the sample counts and medians behind it.
    SunEvidenceEstimate estimate;
    uint64_t frame_index = 0;       ///< the frame measured: 1 for the runtime's first renderFrame, and so on
    double utc_unix_seconds = 0.0;  ///< that frame's FrameInput::utc_unix_seconds
};

/// The newest finished measurement of this runtime, or nothing before the first (or for a runtime that cannot
/// measure: no ground albedo, no site occluder, a device without subgroup arithmetic, colour match off). Never
/// waits on the GPU; allocates nothing. Not thread-safe against renderFrame on the same runtime.
std::optional<RuntimeSunEvidence> latestSunEvidence(Runtime& runtime);

}  // namespace gusuku

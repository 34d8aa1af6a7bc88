#pragma once
// Which of the frame's cues decides the sun's state (issue 41 item 1): the evidence an app feeds
// SunVisibilityFilter::update from the runtime's reading (latestSunEvidence; C: gusuku_runtime_sun_evidence), in
// the order the cues are trusted:
//   1. the site's shadow boundary (SunEvidenceCue::kSiteShadowBoundary): lit against site-shadowed ground of the same
//      frame, whose ratio cancels the camera's gain: taken as the runtime gives it;
//   2. the metered ground (kMeteredGround: no boundary in view): the lit ground against the bake's prediction at the
//      app's exposure. It holds only when FrameInput::exposure is the camera's own metered exposure (EV100 from its
//      ISO, shutter and aperture, gusuku/maths/exposure.h), not a guess or a relative platform estimate, so it
//      counts only when the app says so, with its confidence scaled by kMeteredGroundConfidence: an exposure is
//      known to a third of a stop at best, where the boundary's ratio needs none;
//   3. none: confidence 0, and the filter's prior (the weather service's SkyRegime) decides
//      (SunVisibilityState::cue says whether the frame or the prior decided).
// Pure and allocation-free.

#include "gusuku/maths/sun_evidence.h"
#include "gusuku/maths/sun_visibility.h"

namespace gusuku {

/// The metered ground's confidence against the boundary's for the same samples and spread: half, as the gain it
/// assumes (the app's exposure, the camera's response) is known to a third of a stop at best, where the boundary's
/// ratio cancels it. At the filter's evidence weight 2 a full metered reading (p 0.99) still outweighs a report's
/// prior (0.1 or 0.9), as a frame should.
inline constexpr float kMeteredGroundConfidence = 0.5f;

/// The evidence to feed the filter, and the cue it comes from (kNone: confidence 0, the prior decides).
struct SunCueChoice {
    SunEvidence evidence;
    SunEvidenceCue cue = SunEvidenceCue::kNone;
};

/// The cue that decides the frame: the boundary's reading as it is; the metered ground's when exposure_is_metered,
/// its confidence kMeteredGroundConfidence x min(1, lit / kSunEvidenceFullSamples) x clamp(1 - standard error /
/// kSunEvidenceOutStrength, 0, 1) (the boundary's rule on the lit side alone); else none.
SunCueChoice sunEvidenceForFilter(const SunEvidenceEstimate& estimate, bool exposure_is_metered);

/// A cue's name for tables and logs: "none", "site shadow boundary", "metered ground"; "unknown" past the enum.
const char* sunEvidenceCueName(SunEvidenceCue cue);

}  // namespace gusuku

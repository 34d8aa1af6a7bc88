#include "gusuku/maths/sun_cue_choice.h"

#include <algorithm>
#include <cmath>

namespace gusuku {

SunCueChoice sunEvidenceForFilter(const SunEvidenceEstimate& estimate, bool exposure_is_metered) {
    SunCueChoice choice;
    if (estimate.cue == SunEvidenceCue::kSiteShadowBoundary) {
        choice.evidence = estimate.evidence;
        choice.cue = estimate.cue;
        return choice;
    }
    if (estimate.cue != SunEvidenceCue::kMeteredGround || !exposure_is_metered ||
        !std::isfinite(estimate.strength_standard_error))
        return choice;  // none: the prior decides
    const double samples = std::min(1.0, double(estimate.lit_samples) / double(kSunEvidenceFullSamples));
    const double tightness = std::clamp(1.0 - estimate.strength_standard_error / kSunEvidenceOutStrength, 0.0, 1.0);
    choice.evidence = estimate.evidence;
    choice.evidence.confidence = float(kMeteredGroundConfidence * samples * tightness);
    choice.cue = choice.evidence.confidence > 0.0f ? SunEvidenceCue::kMeteredGround : SunEvidenceCue::kNone;
    if (choice.cue == SunEvidenceCue::kNone) choice.evidence = SunEvidence{};
    return choice;
}

const char* sunEvidenceCueName(SunEvidenceCue cue) {
    switch (cue) {
        case SunEvidenceCue::kNone: return "none";
        case SunEvidenceCue::kSiteShadowBoundary: return "site shadow boundary";
        case SunEvidenceCue::kMeteredGround: return "metered ground";
    }
    return "unknown";
}

}  // namespace gusuku

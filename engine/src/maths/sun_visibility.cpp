// The sun's state from the weather report's regime and the frame's evidence (see sun_visibility.h).

#include "gusuku/maths/sun_visibility.h"

#include <algorithm>
#include <cmath>

namespace gusuku {
namespace {

// Probabilities are held away from 0 and 1 so that their log-odds stay finite.
constexpr float kProbabilityFloor = 0.01f;
constexpr float kMaxMeasuredSunStrength = 1.5f;

float logOdds(float probability) {
    const float p = std::clamp(probability, kProbabilityFloor, 1.0f - kProbabilityFloor);
    return std::log(p / (1.0f - p));
}

float probabilityOf(float log_odds) { return 1.0f / (1.0f + std::exp(-log_odds)); }

bool finiteIn01(float value) { return std::isfinite(value) && value >= 0.0f && value <= 1.0f; }

}  // namespace

SkyRegime skyRegimeFromCover(float cloud_cover, float cover_base_feet) {
    if (!std::isfinite(cloud_cover)) return SkyRegime::kUnknown;
    const float oktas = std::clamp(cloud_cover, 0.0f, 1.0f) * 8.0f;
    if (oktas <= 2.0f) return SkyRegime::kClear;
    if (oktas < 7.0f) return SkyRegime::kBroken;
    const bool high = std::isfinite(cover_base_feet) && cover_base_feet >= kHighCloudBaseFeet;
    return high ? SkyRegime::kHighThinOvercast : SkyRegime::kOvercast;
}

float sunOutPrior(SkyRegime regime) {
    switch (regime) {
        case SkyRegime::kClear: return 0.9f;
        case SkyRegime::kBroken: return 0.5f;
        case SkyRegime::kOvercast: return 0.1f;
        case SkyRegime::kHighThinOvercast: return 0.8f;
        case SkyRegime::kUnknown: break;
    }
    // No report: lean towards a sun that is out, the case in which a missing shadow looks most wrong; a weak lean,
    // so that any confident frame cue overrules it.
    return 0.6f;
}

float sunStrengthPrior(SkyRegime regime) {
    return regime == SkyRegime::kHighThinOvercast ? kHighThinOvercastSunStrength : 1.0f;
}

SunVisibilityFilter::SunVisibilityFilter(const SunVisibilityOptions& options) : options_(options) {}

void SunVisibilityFilter::reset() {
    started_ = false;
    opposite_since_ = -1.0;
    state_.changes = 0;
}

const SunVisibilityState& SunVisibilityFilter::update(double time_seconds, SkyRegime regime,
                                                      const SunEvidence* evidence) {
    const bool first = !started_;
    const double elapsed = first || !std::isfinite(time_seconds) ? 0.0 : std::max(time_seconds - last_time_, 0.0);
    if (std::isfinite(time_seconds) && (first || time_seconds > last_time_)) last_time_ = time_seconds;
    started_ = true;

    // The posterior: the regime's log-odds plus the frame's, weighted by its confidence. Evidence that is not a
    // probability (NaN, out of range) counts as none.
    const float prior_log_odds = logOdds(sunOutPrior(regime));
    const bool usable = evidence && finiteIn01(evidence->sun_out_probability) && finiteIn01(evidence->confidence);
    const float confidence = usable ? evidence->confidence : 0.0f;
    const float evidence_log_odds =
        confidence > 0.0f ? options_.evidence_weight * confidence * logOdds(evidence->sun_out_probability) : 0.0f;
    state_.posterior = probabilityOf(prior_log_odds + evidence_log_odds);
    // The frame decided when its term outweighs the prior's.
    state_.cue = std::fabs(evidence_log_odds) > std::fabs(prior_log_odds) ? SunStateCue::kFrame
                                                                           : SunStateCue::kRegimePrior;

    if (first) {
        // No history: the state is what this frame says, at full visibility or none, without a ramp.
        state_.sun_out = state_.posterior >= 0.5f;
        state_.sun_visibility = state_.sun_out ? 1.0f : 0.0f;
        state_.sun_strength = sunStrengthPrior(regime);
        opposite_since_ = -1.0;
    } else {
        // Hysteresis: the posterior must pass the threshold on the other side and stay past it for hold_seconds.
        const bool opposite = state_.sun_out ? state_.posterior < options_.hidden_threshold
                                             : state_.posterior > options_.out_threshold;
        if (!opposite) {
            opposite_since_ = -1.0;
        } else if (opposite_since_ < 0.0) {
            opposite_since_ = last_time_;  // crossed at this frame
        }
        if (opposite && last_time_ - opposite_since_ >= options_.hold_seconds) {
            state_.sun_out = !state_.sun_out;
            ++state_.changes;
            opposite_since_ = -1.0;
        }
        // The ramp towards the decided state.
        const float target = state_.sun_out ? 1.0f : 0.0f;
        const float step = options_.transition_seconds > 0.0 ? float(elapsed / options_.transition_seconds) : 1.0f;
        if (state_.sun_visibility < target) state_.sun_visibility = std::min(state_.sun_visibility + step, target);
        else state_.sun_visibility = std::max(state_.sun_visibility - step, target);
    }

    // The sun's strength while out: the frame's measurement, smoothed, when it gives one; else the regime's.
    const bool measured = usable && confidence > 0.0f && std::isfinite(evidence->sun_strength) &&
                          evidence->sun_strength > 0.0f;
    // A reading far above the clear sky's is an error (a reflection, a wrong albedo pairing): capped so that one
    // such frame cannot flood the building with sun.
    const float strength_target =
        measured ? std::min(evidence->sun_strength, kMaxMeasuredSunStrength) : sunStrengthPrior(regime);
    if (first) {
        state_.sun_strength = strength_target;
    } else if (options_.strength_time_constant_seconds > 0.0) {
        const float blend = float(1.0 - std::exp(-elapsed / options_.strength_time_constant_seconds));
        state_.sun_strength += (strength_target - state_.sun_strength) * blend;
    } else {
        state_.sun_strength = strength_target;
    }
    return state_;
}

}  // namespace gusuku

#pragma once
// Whether the sun is out at this instant, kept apart from how overcast the sky is (issue 41 item 3).
//
// One cloud cover did both jobs before: it blended the sunny and overcast slots and scaled the real-time sun by
// (1 - cover), so a METAR "BKN" (6 oktas) drew a quarter-strength sun and a quarter-dark shadow at every instant.
// Under broken cloud the real sun is either out (a full, hard shadow in the camera image) or behind a cloud (no
// shadow at all), and high thin overcast (cirrostratus) often casts clear shadows though its cover is 8 oktas.
// So the light is split:
//   - the sky's state (sky_overcast, 0..1) blends the baked slots: it changes slowly and a weather service's cover
//     tells it well enough;
//   - the sun's visibility (0 or 1, with a ramp of transition_seconds between) switches the real-time sun and its
//     shadow, and sun_strength scales E_sun when it is out (thin cloud, haze: shadows softer than the bake's).
// The service's report sets the prior (SkyRegime: what the sun usually is in such a sky); the camera frame's own
// evidence (SunEvidence: lit against shadowed surfaces, issue 41 item 1) decides the instant when it is confident.
// A hysteresis (two thresholds and a hold time) makes one passing cloud give one change, not a flicker.
//
// Pure and allocation-free: the runtime may call update() every frame.

#include <cstdint>

namespace gusuku {

/// What a weather report says of the sky, as a prior on the sun (weatherRegimeFrom* in gusuku/weather).
enum class SkyRegime : uint8_t {
    kUnknown = 0,           ///< no report: the frame alone decides, the sun assumed out until it says otherwise
    kClear = 1,             ///< up to 2 oktas: the sun is out
    kBroken = 2,            ///< 3-6 oktas: out or hidden, nothing to prefer
    kOvercast = 3,          ///< 7-8 oktas of low or middle cloud: hidden
    kHighThinOvercast = 4,  ///< 7-8 oktas based at or above kHighCloudBaseFeet: a veiled sun that still casts shadows
};

/// Cloud bases at or above this height (feet above ground, as METAR gives them) are high cloud: cirrus and
/// cirrostratus, thin ice veils through which the sun usually casts shadows. The WMO's cloud atlas puts the high
/// étage at 5-13 km in temperate regions; 16,500 ft is 5.0 km.
inline constexpr float kHighCloudBaseFeet = 16500.0f;

/// The regime of a cover (0..1, oktas / 8) and the base of the cloud layer that gave it (feet above ground; a
/// negative or NaN base: not known, taken as low).
SkyRegime skyRegimeFromCover(float cloud_cover, float cover_base_feet);

/// The probability of the sun being out that a regime alone gives.
float sunOutPrior(SkyRegime regime);
/// E_sun's scale when the sun is out under this regime and the frame says nothing of its strength: 1, or for a
/// high veil kHighThinOvercastSunStrength.
float sunStrengthPrior(SkyRegime regime);
/// A sun through a high veil: an assumed 0.6 of the clear-sky E_sun. A veil's optical depth varies too widely for
/// one value to be right; this only keeps a shadow softer than a clear day's until the frame measures the strength
/// (SunEvidence::sun_strength), which then replaces it.
inline constexpr float kHighThinOvercastSunStrength = 0.6f;

/// One frame's reading of the sun from the camera image.
struct SunEvidence {
    float sun_out_probability = 0.5f;  ///< [0, 1]
    float confidence = 0.0f;           ///< [0, 1]: 0 no cue in view (the prior decides), 1 a clear shadow boundary
    /// When the sun is out: its measured E_sun against the bake's clear-sky E_sun (lit / shadowed ratio of the same
    /// surface, issue 41 item 2); NaN or <= 0: not measured.
    float sun_strength = -1.0f;
};

/// What decided the sun's state in the last update.
enum class SunStateCue : uint8_t {
    kRegimePrior = 0,  ///< no confident frame cue: the weather report's regime (or kUnknown's default)
    kFrame = 1,        ///< the camera frame's evidence
};

struct SunVisibilityOptions {
    /// How long the sun takes to fade in or out once the state changes: a cloud's edge crosses the half-degree
    /// sun in a second or two at typical cloud speeds (10 m/s at 1.5 km: 0.5 degrees in about 1.3 s).
    double transition_seconds = 1.5;
    float out_threshold = 0.7f;     ///< posterior probability above which a hidden sun comes out
    float hidden_threshold = 0.3f;  ///< below which an out sun goes in
    /// The posterior must stay past the opposite threshold this long before the state changes, so that a few
    /// frames of misleading evidence (a pedestrian's shadow, a flicker of exposure) change nothing.
    double hold_seconds = 0.5;
    /// Weight of the frame's log-odds against the prior's: 2 lets one confident frame cue (p 0.95) overrule an
    /// overcast report's prior (0.1), as the issue asks: the report gives the regime, the frame the instant.
    float evidence_weight = 2.0f;
    /// Time constant of the measured sun strength's smoothing (seconds).
    double strength_time_constant_seconds = 2.0;
};

/// What the frame's light takes.
struct SunVisibilityState {
    bool sun_out = true;              ///< the decided state
    float sun_visibility = 1.0f;      ///< [0, 1]: 0 or 1 but during a transition; scales E_sun and the sun's shadow
    float sun_strength = 1.0f;        ///< E_sun's scale while out (before sun_visibility)
    float posterior = 0.5f;           ///< this update's probability of the sun being out
    SunStateCue cue = SunStateCue::kRegimePrior;
    uint32_t changes = 0;             ///< state changes since the filter was made (for tests and overlays)
};

class SunVisibilityFilter {
public:
    explicit SunVisibilityFilter(const SunVisibilityOptions& options = {});

    /// One frame at time_seconds (any monotonic clock; a time that goes back is taken as no time passing).
    /// evidence may be null (no estimator this frame). Returns the state after this frame.
    const SunVisibilityState& update(double time_seconds, SkyRegime regime, const SunEvidence* evidence);

    /// Forgets the history: the next update decides from its own posterior at once, without a ramp (a new
    /// session, or the app resuming after a long pause).
    void reset();

    const SunVisibilityState& state() const { return state_; }

private:
    SunVisibilityOptions options_;
    SunVisibilityState state_;
    bool started_ = false;
    double last_time_ = 0.0;
    double opposite_since_ = -1.0;  ///< when the posterior crossed the opposite threshold; < 0 not crossed
};

}  // namespace gusuku

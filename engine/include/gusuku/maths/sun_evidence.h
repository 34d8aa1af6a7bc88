#pragma once
// Whether the sun is out, and how strong, read from the real site's own shadows in the camera frame (issue 41 items 1
// and 2; the cue of Madsen & Nielsen 2008 and Bertolini & Madsen 2020: lit against shadowed surfaces in the video).
// This header is the CPU reference of what the runtime's GPU estimator does (the ground colour match's kernel,
// shaders/runtime/colour_statistics_ground.comp with shaders/include/sun_evidence_ground.glsl, classifies the samples;
// shaders/runtime/sun_evidence_reduce.comp, recorded by the runtime's private SunEvidencePass, reduces them);
// tests/test_sun_evidence.cpp pins it on analytic cases and tests/test_runtime_sun_evidence.cpp holds the GPU to it.
//
// The model. The camera samples of the ground colour match (colour_match.h: each sampled pixel's ray followed onto
// the ground grid's height field) land on cells whose albedo rho and baked irradiance without the sun, E_without
// (sky and bounce, the site's own occlusion of the sky included), the bake set holds. Per sample
//     ratio = Y(observed) / Y(exposure rho / pi E_without)            (Rec.709 luminance, linear)
// is g for a cell the site shadows (or whose face turns from the sun), and g (1 + s q) for a lit one, where g is the
// camera's unknown gain (exposure error, white balance, tone curve to first order: it cancels), q = Y(rho E_sun
// cos) / Y(rho E_without) is the bake's clear-sky sun-to-sky share of that cell, and s is the sun's strength now
// against the bake's: 1 a clear sun, 0 a sun behind a cloud, a third under thin cloud. The site shadow is predicted
// from the runtime's site-shadow map (the occluder seen from the sun: the geometry the ground ratio uses), so the
// shadow boundary is known, not detected.
//
// So s is measured, not assumed:
//   1. g: the shadowed samples' log2 ratio, its trimmed mean about the median (the samples within
//      kSunEvidenceWindowBins bins of the median's): a robust level of the shade, which a few lit pixels of a
//      pedestrian or a wall standing in front cannot pull;
//   2. s: the same trimmed mean over the lit samples with q >= kSunEvidenceMinSunShare of s_i = (ratio_i / g - 1) /
//      q_i, each sample normalised by its own cell's albedo and share (so cells of unlike albedo or slope compare
//      like with like);
//   3. the sun's state: p = logistic((s - kSunEvidenceOutStrength) / w), w the larger of kSunEvidenceMinWidth and
//      the median's standard error (1.2533 sigma / sqrt(n), sigma from the interquartile range of the s_i / 1.349);
//   4. confidence: 0 with fewer than kSunEvidenceMinSamples on either side (no boundary in view: the cue is "none"
//      and the prior decides), else min(1, n_min / kSunEvidenceFullSamples) x clamp(1 - se / kSunEvidenceOutStrength,
//      0, 1): more samples on both sides and a tighter estimate give more.
// What s means: the sun-to-sky ratio now over the bake's (E_sun / E_without). A thin cloud that dims the sun to a
// third and leaves the sky gives 1/3; one that also brightens the sky by k gives 1/(3k): the ratio is what the frame
// shows, and what the runtime's sun must take once the colour match's gain has absorbed the sky's brightness.
//
// Medians by histogram, as the GPU can afford them (the median's bin is the first whose cumulative count reaches
// half the total; a mean within the window then refines it past the bin's width, which a narrow population of
// like pixels would otherwise leave as its error): kSunEvidenceBins bins (log2 ratio over
// [kSunEvidenceLowestLog2Ratio, + kSunEvidenceLog2RatioSpan), s over [kSunEvidenceLowestStrength, +
// kSunEvidenceStrengthSpan); outside: the end bins), and a quantile interpolated linearly within its bin (the bin's
// samples taken as spread evenly). Samples: a lit or shadowed one needs its site visibility (the map's bilinear
// compare) at most kSunEvidenceShadowedVisibility or at least kSunEvidenceLitVisibility: penumbra texels, whose side
// the map cannot tell, are left out. Clipped camera pixels (isClippedCameraPixel) and cells without light are left
// out, as in the colour match.
//
// A sample whose ray meets the side of a step before it comes down onto its cell (sunEvidenceRayReachesCell) is left
// out: the pixel shows a wall, not that cell's ground.
//
// No boundary in view (fewer than kSunEvidenceMinSamples shadowed samples, at least that many lit): the lit samples
// are read against the exposure the app passed instead of the shade, g taken as 1 (step 1 skipped), which holds
// only where FrameInput::exposure is the camera's own metered exposure (its ISO, shutter and aperture, EV100;
// gusuku/maths/exposure.h): the cue is kMeteredGround, with the probability and strength of steps 2-3 but
// confidence 0 in `evidence`, so that an app whose exposure is a guess keeps its prior; sunEvidenceForFilter
// (sun_cue_choice.h) gives it weight for an app that says its exposure is metered. Not here yet: walls of the
// photogrammetry mesh (only the ground grid's cells are sampled) and the sky near the sun (the bake set holds no sky
// radiance for the runtime to compare with).
//
// Pure and allocation-free but for the per-sample helpers' vectors (tests and tools).

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/maths/colour_match.h"
#include "gusuku/maths/const_span.h"
#include "gusuku/maths/sun_visibility.h"

namespace gusuku {

inline constexpr uint32_t kSunEvidenceBins = 64;
inline constexpr double kSunEvidenceLowestLog2Ratio = -6.0;
inline constexpr double kSunEvidenceLog2RatioSpan = 12.0;  ///< 0.1875 stop a bin
inline constexpr double kSunEvidenceLowestStrength = -0.5;
inline constexpr double kSunEvidenceStrengthSpan = 3.2;  ///< 0.05 a bin
/// The trimmed means keep the samples within this many bins of the median's: +-0.375 stop of shade, +-0.1 of s.
inline constexpr uint32_t kSunEvidenceWindowBins = 2;
/// A lit sample whose clear sun adds less than this share to its sky light tells little of the sun: left out.
inline constexpr double kSunEvidenceMinSunShare = 0.25;
inline constexpr double kSunEvidenceShadowedVisibility = 0.02;
inline constexpr double kSunEvidenceLitVisibility = 0.98;
inline constexpr uint32_t kSunEvidenceMinSamples = 32;
inline constexpr uint32_t kSunEvidenceFullSamples = 256;
/// The strength at which the sun counts as out with probability 0.5: a hidden sun leaves s near 0 (a bright
/// circumsolar sky still gives a little), a sun through thin cloud a third or more.
inline constexpr double kSunEvidenceOutStrength = 0.15;
inline constexpr double kSunEvidenceMinWidth = 0.03;
/// The camera's response (issue 41 item 2: a contrasty phone's tone curve read a clear sun at s 1.58): over the
/// ground's range the display luminance is taken as a power of the light, Y = k (g Y_true)^gamma, so a sample's log2
/// ratio r = log2 Y - x (x = log2 of the prediction without the sun) runs as c + (gamma - 1) x on the shade, and as
/// c + (gamma - 1) x + gamma log2(1 + s q) on the lit side. On each side the samples are split at their mean x
/// (darker and lighter albedos, less and more sky light); each half's r is its trimmed mean about its median (as
/// the shade's level, step 1), with the mean x of the samples it kept, and the slope between the halves is
/// gamma - 1 (on the lit side as long as the halves see like sun shares q): medians, so that pixels of a fixed
/// brightness that are not the cell (a wall in front of it, a person), which run at slope -1, cannot pull it. A
/// side counts where both halves keep kSunEvidenceMinSamples / 2 and their x lie kSunEvidenceMinResponseSpreadLog2
/// apart; the sides' slopes are pooled by samples x spread squared; the power is clamped to
/// [kSunEvidenceMinResponseGamma, kSunEvidenceMaxResponseGamma], and 1 where no side counts (ground of one albedo
/// under one sky light cannot tell a tone curve). Every ratio is then linearised, r' = (r + x) / gamma - x, before
/// steps 1-4 below.
inline constexpr double kSunEvidenceMinResponseSpreadLog2 = 0.4;
inline constexpr double kSunEvidenceMinResponseGamma = 0.5;
inline constexpr double kSunEvidenceMaxResponseGamma = 2.0;
/// A sample's ray must come down onto its cell's top without passing below the height field on the way: a ray that
/// enters a cell's column (its own or one before it) more than this far below the column's top shows the side of a
/// step (a wall, a terrace's edge), whose albedo and light are not the cell's. The height field marks such a step
/// only by its cells' heights, so the colour match's march can settle on a cell beside a wall that the pixel shows;
/// read as ground, a shaded wall face under a clear sun read as the shade's level and hid the sun (issue 41). 0.1 m
/// keeps ground sloping up to 0.4 (22 degrees) towards the camera, whose columns step by slope x cell / 2 at most.
inline constexpr double kSunEvidenceStepToleranceM = 0.1;
/// The cell edges the check walks back from the hit towards the camera (64 cells on a diagonal): a step further
/// away than that is taken as none.
inline constexpr uint32_t kSunEvidenceMaxCrossings = 128;

/// What decided a frame's evidence.
enum class SunEvidenceCue : uint8_t {
    kNone = 0,                ///< no cue in view: confidence 0, the prior (weather report) decides
    kSiteShadowBoundary = 1,  ///< lit against site-shadowed ground in the camera frame
    /// No boundary: the lit ground against the bake's prediction at the app's exposure (g taken as 1); confidence 0
    /// in `evidence` (see above and sunEvidenceForFilter)
    kMeteredGround = 2,
};

/// One camera sample as the estimator reads it (what the ground kernel's sun_evidence_ground.glsl writes per sample).
enum class SunEvidenceSampleKind : uint8_t { kNone = 0, kShadowed = 1, kLit = 2 };
struct SunEvidenceSample {
    SunEvidenceSampleKind kind = SunEvidenceSampleKind::kNone;
    float log2_ratio = 0.0f;  ///< log2(Y observed / Y predicted without the sun)
    float sun_share = 0.0f;   ///< q: Y(rho E_sun cos) / Y(rho E_without), the bake's clear sun
    float log2_predicted = 0.0f;  ///< x: log2 Y predicted without the sun (exposure included), for the response
};

/// One frame's reading (the reduce's output).
struct SunEvidenceEstimate {
    SunEvidence evidence;  ///< probability, confidence and strength for SunVisibilityFilter::update
    SunEvidenceCue cue = SunEvidenceCue::kNone;
    uint32_t shadowed_samples = 0;  ///< in the shadowed median
    uint32_t lit_samples = 0;       ///< in the strength median (q >= kSunEvidenceMinSunShare)
    float shade_log2_ratio = 0.0f;  ///< log2 g: the shadowed samples' trimmed mean (0 when too few: kMeteredGround)
    float strength = 0.0f;          ///< s, the trimmed mean (0 when too few); evidence.sun_strength is s where the
                                    ///< sun is out (p >= 0.5), else -1
    float strength_standard_error = 0.0f;
    float response_gamma = 1.0f;  ///< the camera response's power fitted on the shade (1: none fitted)
};

/// The bin of a value in a histogram of kSunEvidenceBins over [lowest, lowest + span), the ends taking what lies
/// outside (NaN: bin 0).
uint32_t sunEvidenceBin(double value, double lowest, double span);

/// The q-quantile (0..1) of a histogram's counts, interpolated within its bin; lowest when empty.
double sunEvidenceQuantile(ConstSpan<uint32_t> counts, double quantile, double lowest, double span);

/// The response's power, then steps 1-4 above, over the samples.
SunEvidenceEstimate estimateSunEvidence(ConstSpan<SunEvidenceSample> samples);

/// A sample's site visibility at a ground point (1 lit, 0 shadowed by the site, between: penumbra), ENU metres.
using SiteVisibility = std::function<double(const glm::dvec3& point_enu)>;

/// Whether the ray origin + t direction (direction.z < 0), which comes down to `cell`'s height inside that cell,
/// reaches it from above: walking back towards the origin over the cell edges it crosses (at most
/// kSunEvidenceMaxCrossings), at each the ray is no more than kSunEvidenceStepToleranceM below either neighbouring
/// cell's height (cells without ground never block). False: the pixel shows the side of a step, not the cell. The
/// walk ends once the ray is within the tolerance of ground_top_m, the highest ground cell's height
/// (sunEvidenceGroundTop): nothing further back can block it.
bool sunEvidenceRayReachesCell(const GroundMatchScene& scene, const glm::dvec3& origin, const glm::dvec3& direction,
                               size_t cell, double ground_top_m);

/// The highest height of a cell with ground (-infinity without any).
double sunEvidenceGroundTop(const GroundMatchScene& scene);

/// The per-sample records of a frame (reference of the ground kernel's classification, sun_evidence_ground.glsl): the
/// colour match's sample grid at stride, each ray onto the ground (groundMatchCellOfPixel), the cell's prediction
/// without the sun (view's slots and exposure), and the clear-sky E_sun `clear_sun_irradiance_rgb` (bake set units,
/// before any sun_scale) along view.sun_direction_enu for q. The site's visibility is looked up at the cell's centre
/// (its height). A sun below the horizon makes every sample kNone. Allocates the result.
std::vector<SunEvidenceSample> sunEvidenceSamples(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
                                                  uint32_t stride, const GroundMatchScene& scene,
                                                  const GroundMatchView& view,
                                                  const glm::dvec3& clear_sun_irradiance_rgb,
                                                  const SiteVisibility& site_visibility);

}  // namespace gusuku

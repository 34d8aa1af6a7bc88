#pragma once
// Adaptive sampling: spend a bake's samples where its error is. A lightmap's error (relative RMS over its
// texels, what `gusuku-bake converge` and the comparison with Cycles measure) is dominated by few texels: on
// the sample site and on the shared shrine a small share of the noisiest texels holds most of the squared error
// after any number of uniform samples. For a fixed number of samples in all, the sum of the texels' variances
// sigma_t^2 / n_t is smallest when each texel gets n_t proportional to its own sample standard deviation sigma_t
// (Lagrange); uniform sampling wastes (mean sigma^2) / (mean sigma)^2 of the rays.
//
// The bake traces a pilot (a quarter of the samples, at least 16 a texel, every texel alike), estimates each
// texel's sigma from its sums of luminance and squared luminance, and plans the rest per texel; the extra samples
// are one more point set (copies of the noisy texels' points) for the existing tracer and checkpoints. The plan
// follows from the pilot's sums alone, so a resumed bake plans the same set.
//
// Two departures from n_t proportional to sigma_t, chosen with `converge` (issue 11.1, error^2 x rays): a pilot
// of a quarter instead of half (many of the shrine's texels, under its eaves and inside, are dim, hold little of
// the squared error and have the longest paths, so a large pilot spends rays there), and n_t proportional to
// sigma_t^0.6 instead of sigma_t. The allocation n ~ sigma is optimal for exact sigmas and independent samples,
// but a 16-sample pilot's sigma is itself noisy (a rare bright path in the pilot makes a texel look far noisier
// than it is, and draw that many more samples), and the scrambled Sobol draws' error falls faster than
// 1/sqrt(n), which moves the optimum below sigma^1 even for exact sigmas. Both flatten the plan.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec4.hpp>

#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

/// Below this many samples per texel a bake (and a converge study point) samples every texel alike: a pilot of
/// fewer than 16 samples says too little about a texel's noise: with smaller pilots adaptive sampling lost to
/// uniform sampling on the sample site (converge, error^2 x rays, after the variance-guided filter), from pilots
/// of 16 on it is level or better.
inline constexpr uint32_t kMinAdaptiveSamples = 32;

/// The fewest pilot samples a texel gets (the pilot at kMinAdaptiveSamples): fewer judged the noise too poorly.
inline constexpr uint32_t kMinAdaptivePilotSamples = 16;

/// Texel t is planned toward n_t proportional to sigma_t^kAdaptiveNoiseExponent (see the top of this file for
/// why not 1), chosen with `converge`'s study points against a converged reference (its noise taken out) on
/// the shrine's and the sample's overcast and sunny_1200 slots: with a pilot of a quarter it beat the plan
/// before (a pilot of half, exponent 1) on all four, and neighbouring exponents were no better on both sites.
inline constexpr double kAdaptiveNoiseExponent = 0.6;

/// A texel's pilot for `samples_per_texel` samples: a quarter of them, at least kMinAdaptivePilotSamples, at
/// most half: on the shrine's overcast slot a quarter gave less error^2 x rays than a half, an eighth or three
/// eighths. Only meaningful from kMinAdaptiveSamples on.
uint32_t adaptivePilotSamples(uint32_t samples_per_texel);

/// The pilot per trace point of a texel's footprint (points_per_texel points sharing its samples):
/// adaptivePilotSamples(samples_per_point * points_per_texel) / points_per_texel, at least 1.
uint32_t adaptivePilotSamplesPerPoint(uint32_t samples_per_point, size_t points_per_texel);

/// Samples of one copy of a texel's point in the extra set: small, so the extras' granularity stays fine, but
/// a stratified handful (the first points of a scrambled Sobol sequence) rather than one sample each.
inline constexpr uint32_t kAdaptiveSamplesPerCopy = 4;

struct AdaptivePlanOptions {
    /// Extra samples come in multiples of this: a footprint's slots per texel times the samples of one copy
    /// (adaptiveExtraPoints), so each slot gets whole copies.
    uint32_t granularity = 1;
    /// No texel gets more than this many times the mean budget in all: a sigma estimated from a pilot that met
    /// one rare bright path is itself noisy, and must not draw the whole budget.
    double max_budget_multiple = 8.0;
    /// n_t proportional to sigma_t to this power (kAdaptiveNoiseExponent; 1: the minimum summed variance for
    /// exact sigmas and independent samples).
    double noise_exponent = kAdaptiveNoiseExponent;
};

/// Plans the samples after a pilot: every texel already has `pilot_samples`; the texels together get about
/// (budget_samples - pilot_samples) * texel_count more, texel t toward n_t = lambda * sigma_t^noise_exponent
/// (n_t >= pilot, at most max_budget_multiple * budget_samples), lambda set so the total is the budget. Returns each texel's
/// extra samples, rounded to the nearest multiple of the granularity. Texels with sigma 0 (or not finite) get
/// nothing. Deterministic. All zero when budget <= pilot or no sigma is positive.
std::vector<uint32_t> planAdaptiveSamples(const std::vector<float>& texel_sample_sigma, uint32_t pilot_samples,
                                          uint32_t budget_samples, const AdaptivePlanOptions& options = {});

/// The extra samples as one more point set for the tracer: each texel's trace points (its footprint's slots)
/// repeated, each copy traced with samples_per_copy samples that continue its point's own random stream
/// (QueryPointGpu's stream and first sample), so a texel's samples stay one scrambled Sobol sequence (measured:
/// copies with streams of their own stratify so much worse that adaptive sampling lost to uniform), while the
/// copies fill the tracer's SIMD lanes however few texels are noisy. owners[c]: the set's point copy c adds to.
struct AdaptiveExtras {
    std::vector<QueryPointGpu> points;
    std::vector<uint32_t> owners;
    uint32_t samples_per_copy = 0;
};

/// Copies for extra_per_texel (planAdaptiveSamples with granularity points_per_texel * samples_per_copy): for
/// texel t, extra_t / (points_per_texel * samples_per_copy) copies of each of its points_per_texel consecutive
/// points of `points`; copy k of point p draws samples pilot_samples_per_point + k * samples_per_copy on of
/// p's stream. Throws std::invalid_argument when sizes do not match or a count is not such a multiple.
AdaptiveExtras adaptiveExtraPoints(const std::vector<QueryPointGpu>& points, const std::vector<uint32_t>& extra_per_texel,
                                   size_t points_per_texel, uint32_t samples_per_copy, uint32_t pilot_samples_per_point);

/// One trace point's running sums: sum of estimates (xyz irradiance, w back-face score), sum of squared
/// luminance, and how many samples they hold.
struct PointSums {
    glm::vec4 sum{0.0f};
    float luminance_square_sum = 0.0f;
    uint32_t samples = 0;
};

/// The sums a point would show after `nominal_samples` samples with the same mean (xyz and w) and the same
/// variance of its mean luminance (Bessel-corrected), so that everything downstream, which divides by one
/// sample count for the whole set, reads each point's own mean and noise. Unchanged when samples equals
/// nominal_samples; a point with no samples stays zero.
PointSums normaliseToSampleCount(const PointSums& point, uint32_t nominal_samples);

/// A point set's running sums as the tracer reads them back (PointAccumulator), and how many samples each point
/// holds (all alike after a uniform trace).
struct SetSums {
    std::vector<glm::vec4> sums;
    std::vector<float> luminance_square_sums;
    std::vector<uint32_t> samples;
};

/// Adds traced sums of the copies [first_copy, first_copy + extra_sums.size()) (adaptiveExtraPoints' order,
/// samples_per_copy samples each) onto their owners: the extras may be traced in batches (a device limits how
/// many points one set may hold). Throws std::invalid_argument when the sizes do not match.
void addAdaptiveExtraSums(SetSums& set, const AdaptiveExtras& extras, size_t first_copy,
                          const std::vector<glm::vec4>& extra_sums, const std::vector<float>& extra_square_sums);

/// normaliseToSampleCount on every point of the set: afterwards every point reads as nominal_samples samples.
void normaliseSetSums(SetSums& set, uint32_t nominal_samples);

/// Traces one batch of copies (their points, samples_per_copy = kAdaptiveSamplesPerCopy samples each) and fills
/// its sums and squared-luminance sums; false when it was stopped (a bake's Ctrl-C).
using AdaptiveBatchTracer = std::function<bool(size_t batch, const std::vector<QueryPointGpu>& copies,
                                               std::vector<glm::vec4>& sums, std::vector<float>& square_sums)>;

/// Everything after the pilot, for the bake and `converge` alike: `set` holds the pilot's sums of `points`
/// (pilot_per_point samples each; points_per_texel consecutive points a texel), texel_variance_of_mean each
/// texel's variance of its mean luminance from them. Plans the extra samples toward samples_per_point a point
/// on average (planAdaptiveSamples, in whole copies of kAdaptiveSamplesPerCopy samples), hands the copies to
/// trace_batch in batches of at most max_batch_points (whole footprints), adds their sums and normalises the set
/// to samples_per_point. Returns false, the set half done, when a batch was stopped.
bool traceAdaptiveExtras(SetSums& set, const std::vector<QueryPointGpu>& points,
                         const std::vector<float>& texel_variance_of_mean, size_t points_per_texel,
                         uint32_t pilot_per_point, uint32_t samples_per_point, size_t max_batch_points,
                         const AdaptiveBatchTracer& trace_batch);

}  // namespace gusuku::bake

#pragma once
// Adaptive sampling: spend a bake's samples where its error is. A lightmap's error (relative RMS over its
// texels, what `gusuku-bake converge` and the comparison with Cycles measure) is dominated by few texels: on
// the sample site and on the shared shrine the noisiest 10 % of texels hold 59-70 % of the squared error after
// any number of uniform samples, and the noisiest 30 % hold 88-95 %. For a fixed number of samples in all, the
// sum of the texels' variances sigma_t^2 / n_t is smallest when each texel gets n_t proportional to its own
// sample standard deviation sigma_t (Lagrange); uniform sampling wastes (mean sigma^2) / (mean sigma)^2 of the
// rays, about 2x there.
//
// The bake traces a pilot (half the samples, every texel alike), estimates each texel's sigma from its sums of
// luminance and squared luminance, and plans the other half as a few classes of texels, each class given one
// number of extra samples, so that each class is one more point set for the existing tracer and checkpoints
// (a class's points and samples follow from the pilot's sums alone, so a resumed bake plans the same classes).

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace gusuku::bake {

/// The texels that get one number of extra samples.
struct AdaptiveClass {
    uint32_t extra_samples_per_texel = 0;  ///< a multiple of the planner's granularity, > 0
    std::vector<uint32_t> texels;          ///< indices into the planner's texel list, ascending
};

struct AdaptivePlanOptions {
    /// Extra samples come in multiples of this (the footprint's slots per texel: each slot gets the same).
    uint32_t granularity = 1;
    /// No texel gets more than this many times the mean budget in all: a sigma estimated from a pilot that met
    /// one rare bright path is itself noisy, and must not draw the whole budget.
    double max_budget_multiple = 8.0;
};

/// Plans the samples after a pilot: every texel already has `pilot_samples`; the texels together get about
/// (budget_samples - pilot_samples) * texel_count more, texel t toward n_t = lambda * sigma_t (n_t >= pilot, at
/// most max_budget_multiple * budget_samples), lambda set so the total is the budget. Each texel's extra
/// count is rounded to a class: granularity times a power of two, nearest in log2, zero below half of
/// the smallest class; classes come out sorted by extra samples, empty ones left out. Texels with sigma 0 (or
/// not finite) get nothing. Deterministic. Returns no classes when budget <= pilot or no sigma is positive.
std::vector<AdaptiveClass> planAdaptiveSamples(const std::vector<float>& texel_sample_sigma, uint32_t pilot_samples,
                                               uint32_t budget_samples, const AdaptivePlanOptions& options = {});

/// Total extra samples of a plan (the rays it adds, over the samples per ray).
uint64_t plannedExtraSamples(const std::vector<AdaptiveClass>& plan);

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

}  // namespace gusuku::bake

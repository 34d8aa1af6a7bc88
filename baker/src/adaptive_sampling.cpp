// Adaptive sampling's plan and bookkeeping (adaptive_sampling.h).

#include "gusuku_bake/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace gusuku::bake {

namespace {

// Rec.709 luminance weights, as bake_accumulate.comp squares them.
float luminanceOf(const glm::vec4& value) { return glm::dot(glm::vec3(value), glm::vec3(0.2126f, 0.7152f, 0.0722f)); }

bool usableSigma(float sigma) { return std::isfinite(sigma) && sigma > 0.0f; }

}  // namespace

std::vector<AdaptiveClass> planAdaptiveSamples(const std::vector<float>& texel_sample_sigma, uint32_t pilot_samples,
                                               uint32_t budget_samples, const AdaptivePlanOptions& options) {
    if (budget_samples <= pilot_samples || texel_sample_sigma.empty()) return {};
    const double pilot = double(pilot_samples);
    const double cap = std::max(pilot, options.max_budget_multiple * double(budget_samples));
    const double extra_total = double(budget_samples - pilot_samples) * double(texel_sample_sigma.size());
    double smallest_sigma = 0.0, room = 0.0;
    for (float sigma : texel_sample_sigma)
        if (usableSigma(sigma)) {
            smallest_sigma = smallest_sigma > 0.0 ? std::min(smallest_sigma, double(sigma)) : double(sigma);
            room += cap - pilot;
        }
    if (smallest_sigma <= 0.0) return {};

    // Extra samples of a texel for a given lambda: n_t = clamp(lambda sigma_t, pilot, cap), less the pilot.
    const auto extraFor = [&](double lambda, float sigma) {
        return usableSigma(sigma) ? std::clamp(lambda * double(sigma), pilot, cap) - pilot : 0.0;
    };
    const auto extraSum = [&](double lambda) {
        double total = 0.0;
        for (float sigma : texel_sample_sigma) total += extraFor(lambda, sigma);
        return total;
    };
    // The total grows with lambda, and at cap / smallest sigma every texel is at its cap: bisect for the
    // budget, or take that when even every texel at its cap spends less.
    double lambda = cap / smallest_sigma;
    if (room > extra_total) {
        double low = 0.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            const double middle = 0.5 * (low + lambda);
            (extraSum(middle) < extra_total ? low : lambda) = middle;
        }
    }

    const double granularity = double(std::max(options.granularity, 1u));
    std::map<uint32_t, std::vector<uint32_t>> classes;  // extra samples -> texels, in texel order
    for (size_t texel = 0; texel < texel_sample_sigma.size(); ++texel) {
        const double extra = extraFor(lambda, texel_sample_sigma[texel]);
        if (extra < 0.5 * granularity) continue;
        const double octave = std::max(0.0, std::round(std::log2(extra / granularity)));
        const uint32_t rounded = uint32_t(granularity * std::exp2(octave));
        classes[rounded].push_back(uint32_t(texel));
    }
    std::vector<AdaptiveClass> plan;
    for (auto& [extra, texels] : classes) plan.push_back({extra, std::move(texels)});
    return plan;
}

uint64_t plannedExtraSamples(const std::vector<AdaptiveClass>& plan) {
    uint64_t total = 0;
    for (const AdaptiveClass& one_class : plan) total += uint64_t(one_class.extra_samples_per_texel) * one_class.texels.size();
    return total;
}

PointSums normaliseToSampleCount(const PointSums& point, uint32_t nominal_samples) {
    if (point.samples == 0 || point.samples == nominal_samples) return point;
    const double n = double(point.samples), nominal = double(nominal_samples);
    const double mean_luminance = double(luminanceOf(point.sum)) / n;
    // Bessel-corrected sample variance of one sample's luminance; its mean's variance is that over n.
    const double sample_variance =
        point.samples > 1
            ? std::max(0.0, (double(point.luminance_square_sum) - n * mean_luminance * mean_luminance) / (n - 1.0))
            : 0.0;
    const double variance_of_mean = sample_variance / n;
    PointSums normalised;
    normalised.samples = nominal_samples;
    normalised.sum = point.sum * float(nominal / n);
    // Q' with (Q' - N m^2) / (N - 1) / N = the variance of the mean: what a reader dividing by N then finds.
    normalised.luminance_square_sum =
        float(nominal * mean_luminance * mean_luminance + variance_of_mean * nominal * (nominal - 1.0));
    return normalised;
}

}  // namespace gusuku::bake

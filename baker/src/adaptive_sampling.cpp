// Adaptive sampling's plan and bookkeeping (adaptive_sampling.h).

#include "gusuku_bake/adaptive_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace gusuku::bake {

namespace {

// Rec.709 luminance weights, as bake_accumulate.comp squares them.
float luminanceOf(const glm::vec4& value) { return glm::dot(glm::vec3(value), glm::vec3(0.2126f, 0.7152f, 0.0722f)); }

bool usableSigma(float sigma) { return std::isfinite(sigma) && sigma > 0.0f; }

}  // namespace

uint32_t adaptivePilotSamples(uint32_t samples_per_texel) {
    return std::min(std::max(samples_per_texel / 4, kMinAdaptivePilotSamples), samples_per_texel / 2);
}

uint32_t adaptivePilotSamplesPerPoint(uint32_t samples_per_point, size_t points_per_texel) {
    const uint32_t points = uint32_t(std::max<size_t>(points_per_texel, 1));
    return std::max(adaptivePilotSamples(samples_per_point * points) / points, 1u);
}

std::vector<uint32_t> planAdaptiveSamples(const std::vector<float>& texel_sample_sigma, uint32_t pilot_samples,
                                          uint32_t budget_samples, const AdaptivePlanOptions& options) {
    std::vector<uint32_t> extra_per_texel(texel_sample_sigma.size(), 0u);
    if (budget_samples <= pilot_samples || texel_sample_sigma.empty()) return extra_per_texel;
    // The plan's weight of each texel: sigma^exponent (adaptive_sampling.h says why not sigma itself).
    std::vector<float> weight(texel_sample_sigma.size(), 0.0f);
    for (size_t texel = 0; texel < weight.size(); ++texel)
        if (usableSigma(texel_sample_sigma[texel]))
            weight[texel] = float(std::pow(double(texel_sample_sigma[texel]), options.noise_exponent));
    const double pilot = double(pilot_samples);
    const double cap = std::max(pilot, options.max_budget_multiple * double(budget_samples));
    const double extra_total = double(budget_samples - pilot_samples) * double(weight.size());
    double smallest_weight = 0.0, room = 0.0;
    for (float w : weight)
        if (usableSigma(w)) {
            smallest_weight = smallest_weight > 0.0 ? std::min(smallest_weight, double(w)) : double(w);
            room += cap - pilot;
        }
    if (smallest_weight <= 0.0) return extra_per_texel;

    // Extra samples of a texel for a given lambda: n_t = clamp(lambda w_t, pilot, cap), less the pilot.
    const auto extraFor = [&](double lambda, float w) {
        return usableSigma(w) ? std::clamp(lambda * double(w), pilot, cap) - pilot : 0.0;
    };
    const auto extraSum = [&](double lambda) {
        double total = 0.0;
        for (float w : weight) total += extraFor(lambda, w);
        return total;
    };
    // The total grows with lambda, and at cap / smallest weight every texel is at its cap: bisect for the
    // budget, or take that when even every texel at its cap spends less.
    double lambda = cap / smallest_weight;
    if (room > extra_total) {
        double low = 0.0;
        for (int iteration = 0; iteration < 60; ++iteration) {
            const double middle = 0.5 * (low + lambda);
            (extraSum(middle) < extra_total ? low : lambda) = middle;
        }
    }
    const double granularity = double(std::max(options.granularity, 1u));
    for (size_t texel = 0; texel < weight.size(); ++texel)
        extra_per_texel[texel] =
            uint32_t(granularity * std::round(extraFor(lambda, weight[texel]) / granularity));
    return extra_per_texel;
}

AdaptiveExtras adaptiveExtraPoints(const std::vector<QueryPointGpu>& points, const std::vector<uint32_t>& extra_per_texel,
                                   size_t points_per_texel, uint32_t samples_per_copy, uint32_t pilot_samples_per_point) {
    if (points_per_texel == 0 || samples_per_copy == 0 || points.size() != extra_per_texel.size() * points_per_texel)
        throw std::invalid_argument("adaptiveExtraPoints: " + std::to_string(points.size()) + " points for " +
                                    std::to_string(extra_per_texel.size()) + " texels of " +
                                    std::to_string(points_per_texel));
    const uint64_t per_copy = uint64_t(points_per_texel) * samples_per_copy;
    AdaptiveExtras extras;
    extras.samples_per_copy = samples_per_copy;
    for (size_t texel = 0; texel < extra_per_texel.size(); ++texel) {
        if (extra_per_texel[texel] % per_copy != 0)
            throw std::invalid_argument("adaptiveExtraPoints: texel " + std::to_string(texel) + "'s " +
                                        std::to_string(extra_per_texel[texel]) +
                                        " extra samples are not a multiple of " + std::to_string(per_copy));
        const uint64_t copies = extra_per_texel[texel] / per_copy;
        for (uint64_t copy = 0; copy < copies; ++copy)
            for (size_t slot = 0; slot < points_per_texel; ++slot) {
                const size_t point = texel * points_per_texel + slot;
                QueryPointGpu copied = points[point];
                copied.normal.w = std::bit_cast<float>(uint32_t(point) + 1u);
                copied.face_normal.w =
                    std::bit_cast<float>(uint32_t(pilot_samples_per_point + copy * uint64_t(samples_per_copy)));
                extras.points.push_back(copied);
                extras.owners.push_back(uint32_t(point));
            }
    }
    return extras;
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

void addAdaptiveExtraSums(SetSums& set, const AdaptiveExtras& extras, size_t first_copy,
                          const std::vector<glm::vec4>& extra_sums, const std::vector<float>& extra_square_sums) {
    if (extra_square_sums.size() != extra_sums.size() || first_copy + extra_sums.size() > extras.owners.size())
        throw std::invalid_argument("addAdaptiveExtraSums: the copies' sums do not match the copies");
    if (set.luminance_square_sums.size() != set.sums.size() || set.samples.size() != set.sums.size())
        throw std::invalid_argument("addAdaptiveExtraSums: the set's sums, squares and counts differ in size");
    for (size_t copy = 0; copy < extra_sums.size(); ++copy) {
        const uint32_t owner = extras.owners[first_copy + copy];
        if (owner >= set.sums.size()) throw std::invalid_argument("addAdaptiveExtraSums: a copy's owner is past the set");
        set.sums[owner] += extra_sums[copy];
        set.luminance_square_sums[owner] += extra_square_sums[copy];
        set.samples[owner] += extras.samples_per_copy;
    }
}

void normaliseSetSums(SetSums& set, uint32_t nominal_samples) {
    for (size_t point = 0; point < set.sums.size(); ++point) {
        const PointSums normalised = normaliseToSampleCount(
            {set.sums[point], set.luminance_square_sums[point], set.samples[point]}, nominal_samples);
        set.sums[point] = normalised.sum;
        set.luminance_square_sums[point] = normalised.luminance_square_sum;
        set.samples[point] = normalised.samples;
    }
}

bool traceAdaptiveExtras(SetSums& set, const std::vector<QueryPointGpu>& points,
                         const std::vector<float>& texel_variance_of_mean, size_t points_per_texel,
                         uint32_t pilot_per_point, uint32_t samples_per_point, size_t max_batch_points,
                         const AdaptiveBatchTracer& trace_batch) {
    // One sample's sigma at each texel: its mean's variance times the samples the mean is over.
    const uint32_t pilot_per_texel = pilot_per_point * uint32_t(points_per_texel);
    std::vector<float> sigma(texel_variance_of_mean.size());
    for (size_t texel = 0; texel < sigma.size(); ++texel)
        sigma[texel] = std::sqrt(texel_variance_of_mean[texel] * float(pilot_per_texel));
    const std::vector<uint32_t> extra_per_texel =
        planAdaptiveSamples(sigma, pilot_per_texel, samples_per_point * uint32_t(points_per_texel),
                            {uint32_t(points_per_texel) * kAdaptiveSamplesPerCopy});
    const AdaptiveExtras extras =
        adaptiveExtraPoints(points, extra_per_texel, points_per_texel, kAdaptiveSamplesPerCopy, pilot_per_point);
    const size_t batch_points =
        std::max(points_per_texel, max_batch_points / points_per_texel * points_per_texel);
    std::vector<glm::vec4> batch_sums;
    std::vector<float> batch_square_sums;
    for (size_t first = 0, batch = 0; first < extras.points.size(); first += batch_points, ++batch) {
        const size_t last = std::min(extras.points.size(), first + batch_points);
        const std::vector<QueryPointGpu> copies(extras.points.begin() + ptrdiff_t(first),
                                                extras.points.begin() + ptrdiff_t(last));
        if (!trace_batch(batch, copies, batch_sums, batch_square_sums)) return false;
        addAdaptiveExtraSums(set, extras, first, batch_sums, batch_square_sums);
    }
    normaliseSetSums(set, samples_per_point);
    return true;
}

}  // namespace gusuku::bake

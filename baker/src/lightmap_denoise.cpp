#include "gusuku_bake/lightmap_denoise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

namespace {
// Edge-stop width in units of 1/sqrt(samples), for the filter without measured variance: of the multiples tried
// with `gusuku-bake converge` on the sample site (0.5, 1 and 2), 2 gave the lowest error at every sample count.
constexpr float kDenoiseNoiseMultiple = 2.0f;

// The stop with measured variance, |Y_p - Y_q| at which the weight is e^-1/2 in units of sqrt(var_p + var_q):
// 2 below 32 samples, 1.5 from there on. The measured variance is that of independent samples, and the scrambled
// Sobol draws' error falls faster than that (faster than samples^-0.5), so the measure overstates the noise more
// as samples grow and the stop narrows in its units. Chosen with `gusuku-bake converge` on the sample site and
// the shrine among 1, 1.5, 2 and 3: 2 at few samples, 1.5 from kManySamples on; 3 blurs more, 1 smooths too
// little at few samples.
constexpr float kLuminanceNoiseSigmasFew = 2.0f;
constexpr float kLuminanceNoiseSigmasMany = 1.5f;
constexpr uint32_t kManySamples = 32;
// Lightmaps of fine detail (lightmapRoughnessAgainstNoise at least kDetailRoughness), in their thin charts (at
// least kDetailMinChartEdgeFraction of the texels on the chart's edge: a rectangle under about 7-13 texels
// across), from kManySamples on: a position weight of one texel at 8 texels per metre and a stop of
// kDetailNoiseSigmasAt32 * (samples / 32)^-kDetailNoiseSigmasFall measured sigmas, at most
// kLuminanceNoiseSigmasFew. The measured variance overstates the true error more as samples grow, so the stop
// narrows with samples. Chosen by running variants (position widths, stops and their fall with samples; per-texel
// choices among the passes, non-local means, a first-order regression, a stop on a self-calibrated variance) on
// the lightmaps `gusuku-bake converge` filters on the shrine and the sample site against a converged study: the
// others gained less. Even a stop on the reference's own irradiance (an oracle) gains little on the shrine,
// whose light changes strongly between neighbouring texels of a flat face. On the sample site, whose light is
// smooth, these settings lose to the wide filter, which its roughness (below kDetailRoughness on its overcast
// slot) keeps; its sunny_1200 slot is rough too, and there the edge fraction keeps the wide filter on its broad
// charts (a rule by chart size, or a higher edge fraction, kept less of the shrine's gain).
constexpr float kDetailRoughness = 0.25f;
constexpr float kDetailMinChartEdgeFraction = 0.3f;
constexpr float kDetailPositionSigmaM = 0.125f;
constexpr float kDetailNoiseSigmasAt32 = 1.5f;
constexpr float kDetailNoiseSigmasFall = 0.35f;
// Passes with measured variance: the stop tightens by itself as each pass lowers the variance it carries, so the
// passes need not fall with samples. Past 3 they barely change the sample site's error; 5 reach 64 texels for
// denser lightmaps.
constexpr int kVarianceGuidedIterations = 5;

// B3-spline taps of the a-trous scheme.
constexpr float kTap[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};

// Each valid texel's variance averaged over its 3 x 3 neighbours that are valid and of its chart, weighted by
// the B3 taps (1/4, 1/2, 1/4 each way).
std::vector<float> smoothedVariance(const std::vector<float>& variance, const std::vector<glm::vec4>& rgba,
                                    const std::vector<DenoiseGuide>& guides, int resolution) {
    constexpr float kNear[3] = {0.25f, 0.5f, 0.25f};
    std::vector<float> smoothed = variance;
    for (int y = 0; y < resolution; ++y)
        for (int x = 0; x < resolution; ++x) {
            const size_t centre = size_t(y) * size_t(resolution) + size_t(x);
            if (rgba[centre].a <= 0.0f) continue;
            float sum = 0.0f, weight_sum = 0.0f;
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) {
                    const int qx = x + i - 1, qy = y + j - 1;
                    if (qx < 0 || qy < 0 || qx >= resolution || qy >= resolution) continue;
                    const size_t q = size_t(qy) * size_t(resolution) + size_t(qx);
                    if (rgba[q].a <= 0.0f || guides[q].chart != guides[centre].chart) continue;
                    sum += kNear[i] * kNear[j] * variance[q];
                    weight_sum += kNear[i] * kNear[j];
                }
            smoothed[centre] = sum / weight_sum;
        }
    return smoothed;
}

}  // namespace

DenoiseOptions denoiseOptionsForSamples(uint32_t samples, bool with_variance) {
    DenoiseOptions options;
    // The scrambled Sobol sampler's error falls about as samples^-0.7 on the sample site (not samples^-0.5),
    // so the edge-stop narrows at that rate, and fewer passes keep the filter's blur from outgrowing the noise.
    const float noise_scale = std::pow(float(std::max(samples, 1u)), -0.75f);
    options.relative_luminance_sigma = std::clamp(kDenoiseNoiseMultiple * noise_scale, 0.01f, 0.5f);
    options.iterations = samples <= 64 ? 3 : samples <= 512 ? 2 : 1;
    if (with_variance && samples >= 2) {
        options.iterations = kVarianceGuidedIterations;
        options.luminance_noise_sigmas = samples < kManySamples ? kLuminanceNoiseSigmasFew : kLuminanceNoiseSigmasMany;
        options.detail_roughness_threshold = samples >= kManySamples ? kDetailRoughness : 0.0f;
        options.detail_min_chart_edge_fraction = kDetailMinChartEdgeFraction;
        options.detail_position_sigma_m = kDetailPositionSigmaM;
        options.detail_luminance_noise_sigmas =
            std::min(kLuminanceNoiseSigmasFew,
                     kDetailNoiseSigmasAt32 * std::pow(float(samples) / float(kManySamples), -kDetailNoiseSigmasFall));
    }
    return options;
}

float lightmapRoughnessAgainstNoise(const std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides,
                                    int resolution, const std::vector<float>& luminance_variance) {
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    if (rgba.size() != texel_count || guides.size() != texel_count || luminance_variance.size() != texel_count)
        throw std::invalid_argument("lightmapRoughnessAgainstNoise: buffers do not hold resolution^2 texels");
    constexpr float kMinNormalCosine = 0.99f;             // 8.1 degrees
    constexpr double kChiSquareOneLowerQuartile = 0.1015;  // P(chi^2_1 < 0.1015) = 0.25
    constexpr size_t kMinQualifying = 16;
    const auto luminanceAt = [&](size_t i) { return double(luminanceRec709(glm::vec3(rgba[i]))); };
    std::vector<double> ratios;
    for (int y = 1; y + 1 < resolution; ++y)
        for (int x = 1; x + 1 < resolution; ++x) {
            const size_t centre = size_t(y) * size_t(resolution) + size_t(x);
            if (rgba[centre].a <= 0.0f || !(luminance_variance[centre] > 0.0f)) continue;
            const size_t neighbours[4] = {centre - 1, centre + 1, centre - size_t(resolution),
                                          centre + size_t(resolution)};
            double neighbour_sum = 0.0, neighbour_variance = 0.0;
            bool qualifies = true;
            for (const size_t q : neighbours) {
                if (rgba[q].a <= 0.0f || guides[q].chart != guides[centre].chart ||
                    glm::dot(guides[q].normal, guides[centre].normal) < kMinNormalCosine) {
                    qualifies = false;
                    break;
                }
                neighbour_sum += luminanceAt(q);
                neighbour_variance += luminance_variance[q];
            }
            if (!qualifies) continue;
            const double residual = luminanceAt(centre) - neighbour_sum / 4.0;
            ratios.push_back(residual * residual / (double(luminance_variance[centre]) + neighbour_variance / 16.0));
        }
    if (ratios.size() < kMinQualifying) return 1.0f;
    // The lower quartile rather than the mean or the median: edges and texel-wide features make the upper
    // part of the distribution, the noise and the smooth light its lower part.
    const auto quartile = ratios.begin() + long((ratios.size() - 1) / 4);
    std::nth_element(ratios.begin(), quartile, ratios.end());
    return float(*quartile / kChiSquareOneLowerQuartile);
}

void denoiseLightmap(std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides, int resolution,
                     const DenoiseOptions& options, const std::vector<float>& luminance_variance) {
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    if (rgba.size() != texel_count || guides.size() != texel_count)
        throw std::invalid_argument("denoiseLightmap: buffers do not hold resolution^2 texels");
    const bool measured = !luminance_variance.empty();
    if (measured && luminance_variance.size() != texel_count)
        throw std::invalid_argument("denoiseLightmap: luminance_variance does not hold resolution^2 texels");
    // Per texel: whether it takes the detail settings (a thin chart of a rough lightmap).
    std::vector<bool> detail(texel_count, false);
    if (measured && options.detail_roughness_threshold > 0.0f &&
        lightmapRoughnessAgainstNoise(rgba, guides, resolution, luminance_variance) >=
            options.detail_roughness_threshold) {
        struct ChartCounts {
            uint32_t texels = 0, on_edge = 0;
        };
        std::unordered_map<uint32_t, ChartCounts> charts;
        const auto inChart = [&](int x, int y, uint32_t chart) {
            if (x < 0 || y < 0 || x >= resolution || y >= resolution) return false;
            const size_t q = size_t(y) * size_t(resolution) + size_t(x);
            return rgba[q].a > 0.0f && guides[q].chart == chart;
        };
        for (int y = 0; y < resolution; ++y)
            for (int x = 0; x < resolution; ++x) {
                const size_t i = size_t(y) * size_t(resolution) + size_t(x);
                if (rgba[i].a <= 0.0f) continue;
                const uint32_t chart = guides[i].chart;
                ChartCounts& counts = charts[chart];
                ++counts.texels;
                if (!inChart(x - 1, y, chart) || !inChart(x + 1, y, chart) || !inChart(x, y - 1, chart) ||
                    !inChart(x, y + 1, chart))
                    ++counts.on_edge;
            }
        for (size_t i = 0; i < texel_count; ++i) {
            if (rgba[i].a <= 0.0f) continue;
            const ChartCounts& counts = charts[guides[i].chart];
            detail[i] = float(counts.on_edge) >= options.detail_min_chart_edge_fraction * float(counts.texels);
        }
    }
    const float inverse_position_variance = 1.0f / (2.0f * options.position_sigma_m * options.position_sigma_m);
    const float detail_inverse_position_variance =
        1.0f / (2.0f * options.detail_position_sigma_m * options.detail_position_sigma_m);
    const float detail_inverse_sigmas_squared =
        1.0f / (2.0f * options.detail_luminance_noise_sigmas * options.detail_luminance_noise_sigmas);
    const float inverse_relative_variance =
        1.0f / (2.0f * options.relative_luminance_sigma * options.relative_luminance_sigma);
    const float inverse_sigmas_squared =
        1.0f / (2.0f * options.luminance_noise_sigmas * options.luminance_noise_sigmas);
    std::vector<glm::vec4> source = rgba;
    std::vector<float> variance = luminance_variance, source_variance = luminance_variance;
    std::vector<float> luminance(texel_count), stop_variance;
    for (int iteration = 0; iteration < options.iterations; ++iteration) {
        const int step = 1 << iteration;
        for (size_t i = 0; i < texel_count; ++i) luminance[i] = luminanceRec709(glm::vec3(source[i]));
        if (measured) stop_variance = options.smooth_variance
                                          ? smoothedVariance(source_variance, source, guides, resolution)
                                          : source_variance;
        for (int y = 0; y < resolution; ++y)
            for (int x = 0; x < resolution; ++x) {
                const size_t centre = size_t(y) * size_t(resolution) + size_t(x);
                if (source[centre].a <= 0.0f) continue;
                const DenoiseGuide& guide = guides[centre];
                const float centre_luminance = luminance[centre];
                const float position_falloff =
                    detail[centre] ? detail_inverse_position_variance : inverse_position_variance;
                const float noise_falloff = detail[centre] ? detail_inverse_sigmas_squared : inverse_sigmas_squared;
                glm::vec3 weighted_sum(0.0f);
                float weight_sum = 0.0f, weighted_variance = 0.0f;
                for (int j = 0; j < 5; ++j) {
                    const int qy = y + (j - 2) * step;
                    if (qy < 0 || qy >= resolution) continue;
                    for (int i = 0; i < 5; ++i) {
                        const int qx = x + (i - 2) * step;
                        if (qx < 0 || qx >= resolution) continue;
                        const size_t q = size_t(qy) * size_t(resolution) + size_t(qx);
                        if (source[q].a <= 0.0f || guides[q].chart != guide.chart) continue;
                        const glm::vec3 offset = guides[q].position - guide.position;
                        const float position_weight = std::exp(-glm::dot(offset, offset) * position_falloff);
                        const float normal_weight =
                            std::pow(std::max(0.0f, glm::dot(guides[q].normal, guide.normal)), options.normal_power);
                        const float difference = luminance[q] - centre_luminance;
                        float colour_weight;
                        if (measured) {
                            // A floor of 1e-6 relative keeps texels whose samples all agreed (an open sky) apart
                            // from any neighbour that differs, without dividing by zero.
                            const float floor = 1e-6f * (luminance[q] + centre_luminance);
                            const float noise = stop_variance[centre] + stop_variance[q] + floor * floor;
                            colour_weight = noise > 0.0f ? std::exp(-difference * difference * noise_falloff / noise)
                                                         : (difference == 0.0f ? 1.0f : 0.0f);
                        } else {
                            const float relative = std::fabs(difference) /
                                                   std::max(luminance[q] + centre_luminance, 1e-12f);
                            colour_weight = std::exp(-relative * relative * inverse_relative_variance);
                        }
                        const float weight = kTap[i] * kTap[j] * position_weight * normal_weight * colour_weight;
                        weighted_sum += weight * glm::vec3(source[q]);
                        weight_sum += weight;
                        if (measured) weighted_variance += weight * weight * source_variance[q];
                    }
                }
                // The centre tap always contributes (weight 9/64), so weight_sum > 0.
                rgba[centre] = glm::vec4(weighted_sum / weight_sum, source[centre].a);
                if (measured) variance[centre] = weighted_variance / (weight_sum * weight_sum);
            }
        source = rgba;
        source_variance = variance;
    }
}

std::vector<float> texelLuminanceVarianceFromFootprint(const LightmapFootprint& footprint,
                                                       const std::vector<glm::vec4>& slot_sums,
                                                       const std::vector<float>& slot_luminance_square_sums,
                                                       uint32_t samples_per_slot, float max_invalid_fraction) {
    const size_t slots_per_texel = footprint.pointsPerTexel();
    if (slot_sums.size() != footprint.points.size() || slot_luminance_square_sums.size() != slot_sums.size() ||
        slots_per_texel == 0)
        throw InputError("lightmap", "footprint sums",
                         std::to_string(slot_sums.size()) + " sums and " +
                             std::to_string(slot_luminance_square_sums.size()) + " squares for " +
                             std::to_string(footprint.points.size()) + " footprint points");
    const size_t texel_count = footprint.points.size() / slots_per_texel;
    std::vector<float> variance(texel_count, 0.0f);
    if (samples_per_slot == 0) return variance;
    for (size_t i = 0; i < texel_count; ++i) {
        // The slots texelSumsFromFootprint keeps: the valid ones for a valid texel, else the invalid ones.
        const uint64_t kept = keptFootprintSlots(footprint, slot_sums, i, samples_per_slot, max_invalid_fraction);
        double weighted_variance = 0.0, weight_sum = 0.0;
        for (size_t k = 0; k < slots_per_texel; ++k) {
            if ((kept >> k & 1u) == 0) continue;
            const size_t slot = i * slots_per_texel + k;
            const double weight = footprint.points[slot].weight;
            weighted_variance +=
                weight * weight * luminanceVarianceOfMean(slot_sums[slot], slot_luminance_square_sums[slot],
                                                          samples_per_slot);
            weight_sum += weight;
        }
        if (weight_sum > 0.0) variance[i] = float(weighted_variance / (weight_sum * weight_sum));
    }
    return variance;
}

}  // namespace gusuku::bake

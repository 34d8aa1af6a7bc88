#include "gusuku_bake/lightmap_denoise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "gusuku/colour.h"
#include "gusuku/input_error.h"
#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

namespace {
// Edge-stop width in units of 1/sqrt(samples), for the filter without measured variance. Measured with
// `gusuku-bake converge` on the sample site (1-sample relative RMS 0.88) for multiples 0.5, 1 and 2: 2 gave the
// lowest error from 8 to 256 samples (5.0 % against 10.8 % raw at 64 samples).
constexpr float kDenoiseNoiseMultiple = 2.0f;

// The stop with measured variance, |Y_p - Y_q| at which the weight is e^-1/2 in units of sqrt(var_p + var_q):
// 2 below 32 samples, 1.5 from there on. The measured variance is that of independent samples, and the scrambled
// Sobol draws' error falls faster than that (samples^-0.7, not ^-0.5), so the measure overstates the noise more
// as samples grow and the stop narrows in its units. Measured with `gusuku-bake converge` (--max-samples 256
// --reference-samples 1024 on the sample site, 64 / 256 on the shrine) for 1, 1.5, 2 and 3: 2 was best or within
// 0.1 % absolute of the best up to 16 samples on the sample site's overcast and sunny_1200 slots; from 32 on, 1.5
// was better on sunny_1200 (1.85 against 1.96 % at 64) and the shrine (5.7 against 6.0 % at 64) and within
// 0.05 % on overcast; 3 was 10-25 % worse from 32 samples on (more blur), 1 worse at 16 and fewer (less smoothing).
constexpr float kLuminanceNoiseSigmasFew = 2.0f;
constexpr float kLuminanceNoiseSigmasMany = 1.5f;
constexpr uint32_t kManySamples = 32;
// Passes with measured variance: the stop tightens by itself as each pass lowers the variance it carries, so the
// passes need not fall with samples. Past 3 they change the sample site's error by under 0.01 % at 0.25 m
// position width; 5 reach 64 texels for denser lightmaps.
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
    }
    return options;
}

void denoiseLightmap(std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides, int resolution,
                     const DenoiseOptions& options, const std::vector<float>& luminance_variance) {
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    if (rgba.size() != texel_count || guides.size() != texel_count)
        throw std::invalid_argument("denoiseLightmap: buffers do not hold resolution^2 texels");
    const bool measured = !luminance_variance.empty();
    if (measured && luminance_variance.size() != texel_count)
        throw std::invalid_argument("denoiseLightmap: luminance_variance does not hold resolution^2 texels");
    const float inverse_position_variance = 1.0f / (2.0f * options.position_sigma_m * options.position_sigma_m);
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
                        const float position_weight = std::exp(-glm::dot(offset, offset) * inverse_position_variance);
                        const float normal_weight =
                            std::pow(std::max(0.0f, glm::dot(guides[q].normal, guide.normal)), options.normal_power);
                        const float difference = luminance[q] - centre_luminance;
                        float colour_weight;
                        if (measured) {
                            // A floor of 1e-6 relative keeps texels whose samples all agreed (an open sky) apart
                            // from any neighbour that differs, without dividing by zero.
                            const float floor = 1e-6f * (luminance[q] + centre_luminance);
                            const float noise = stop_variance[centre] + stop_variance[q] + floor * floor;
                            colour_weight = noise > 0.0f ? std::exp(-difference * difference * inverse_sigmas_squared / noise)
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

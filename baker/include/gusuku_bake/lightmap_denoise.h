#pragma once
// An edge-keeping filter for baked irradiance: an a-trous wavelet filter (Dammertz et al. 2010) in lightmap
// space whose weights stop at geometric edges (world position and normal of each texel), at chart boundaries
// (a texel never takes light from another chart, however close the two lie in the lightmap or in the world),
// and at changes of irradiance larger than the texels' own noise. That noise is measured: the bake sums each
// sample's squared luminance beside the sample, so every texel knows the variance of its mean, and the filter
// (as SVGF, Schied et al. 2017) stops where |Y_p - Y_q| is large against sqrt(var_p + var_q), carrying the
// variance through its passes (each pass's output is a weighted mean, its variance sum(w^2 var) / sum(w)^2).
// A well-converged texel then keeps its value however many samples the bake took, instead of the filter's blur
// (its bias) setting a floor under the error. Its effect on error per sample count is printed by
// `gusuku-bake converge`.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku_bake/lightmap_uv.h"

namespace gusuku::bake {

struct DenoiseGuide {
    glm::vec3 position{0.0f};  ///< texel's world position (ENU metres)
    glm::vec3 normal{0.0f};    ///< texel's unit shading normal
    uint32_t chart = 0;        ///< the texel's lightmap chart: texels of different charts never mix
};

struct DenoiseOptions {
    int iterations = 3;               ///< a-trous passes with step 1, 2, 4, ... texels
    float position_sigma_m = 0.25f;   ///< world distance at which the position weight falls to e^-1/2
    float normal_power = 64.0f;       ///< weight (n_p . n_q)^power
    /// Without measured variance: |Y_p - Y_q| / (Y_p + Y_q) at which the irradiance weight is e^-1/2.
    float relative_luminance_sigma = 0.5f;
    /// With measured variance: |Y_p - Y_q| / sqrt(var_p + var_q) at which the irradiance weight is e^-1/2.
    float luminance_noise_sigmas = 2.0f;
    /// With measured variance: the irradiance stop reads each texel's variance averaged over its 3 x 3
    /// neighbours of the same chart (as SVGF), since a variance from a few samples is itself noisy.
    bool smooth_variance = true;
    /// With measured variance, fine detail: when the lightmap's roughness against its measured noise
    /// (lightmapRoughnessAgainstNoise) is at least this, texels of thin charts (at least
    /// detail_min_chart_edge_fraction of their valid texels lack a valid 4-neighbour of the chart: beams,
    /// brackets, boards, where texel-wide detail lies) are filtered with the two detail_* settings instead of
    /// position_sigma_m and luminance_noise_sigmas. 0 never switches.
    float detail_roughness_threshold = 0.0f;
    float detail_min_chart_edge_fraction = 0.3f;
    float detail_position_sigma_m = 0.125f;
    float detail_luminance_noise_sigmas = 1.5f;
};

/// Options for a bake of `samples` samples per texel. With measured variance the irradiance stop follows each
/// texel's own noise; without it (the caller has no square sums, or a single sample) it narrows as the noise
/// of the sample site (samples^-0.75) and the passes fall with samples, as before the variance was measured.
/// With measured variance and from 32 samples on, the options also hold the settings for the thin charts of
/// lightmaps of fine detail (a roughness threshold, a narrower position weight and an irradiance stop that
/// narrows with samples), which denoiseLightmap applies where the data asks for them.
DenoiseOptions denoiseOptionsForSamples(uint32_t samples, bool with_variance = false);

/// How rough a lightmap is against its measured noise: over the texels whose four neighbours are valid, of
/// their chart and of their normal (within 8 degrees), the lower quartile of r^2 / (var_p + sum var_q / 16),
/// r = Y_p - mean of the four Y_q, over the lower quartile of chi-square with one degree of freedom (0.1015).
/// Noise alone of the measured variance gives 1; the bake's scrambled Sobol samples err 3 to 15 times less
/// (in square) than the variance of independent samples it measures, and smooth light adds little, so a smooth
/// lightmap gives 0.05-0.2; texel-wide detail (beams, contact edges) keeps it at 0.3 or more however many
/// samples. 1 when fewer than 16 texels qualify (a lightmap of slivers is all detail).
float lightmapRoughnessAgainstNoise(const std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides,
                                    int resolution, const std::vector<float>& luminance_variance);

/// Filters rgba (alpha > 0 marks a valid texel; invalid texels neither change nor contribute), in place.
/// guides holds resolution^2 entries (ignored where invalid). luminance_variance: resolution^2 variances of each
/// texel's mean luminance (luminanceVarianceOfMean), or empty for the relative stop. With measured variance and
/// options.detail_roughness_threshold > 0, in a lightmap whose lightmapRoughnessAgainstNoise reaches the
/// threshold the texels of thin charts are filtered with the detail_* settings. O(iterations * 25 * texels).
/// Throws std::invalid_argument when a buffer's size is not resolution^2.
void denoiseLightmap(std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides, int resolution,
                     const DenoiseOptions& options = {}, const std::vector<float>& luminance_variance = {});

/// The variance of each texel's mean luminance when its samples were spread over a footprint (lightmap_uv.h's
/// texelSumsFromFootprint folds the sums): sum over the slots it keeps of (w_s / W)^2 times the slot mean's
/// variance, with the same validity rule as texelSumsFromFootprint. Zero for a texel with no samples.
std::vector<float> texelLuminanceVarianceFromFootprint(const LightmapFootprint& footprint,
                                                       const std::vector<glm::vec4>& slot_sums,
                                                       const std::vector<float>& slot_luminance_square_sums,
                                                       uint32_t samples_per_slot, float max_invalid_fraction);

}  // namespace gusuku::bake

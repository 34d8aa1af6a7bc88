#pragma once
// An edge-keeping filter for baked irradiance: an a-trous wavelet filter (Dammertz et al. 2010) in lightmap
// space whose weights stop at geometric edges (world position and normal of each texel) and at large relative
// changes of irradiance (a shadow edge under the eaves), so it smooths Monte Carlo noise without bleeding light
// across corners or charts. Its effect on error per sample count is printed by `gusuku-bake converge`.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace gusuku::bake {

struct DenoiseGuide {
    glm::vec3 position{0.0f};  ///< texel's world position (ENU metres)
    glm::vec3 normal{0.0f};    ///< texel's unit shading normal
};

struct DenoiseOptions {
    int iterations = 3;               ///< a-trous passes with step 1, 2, 4, ... texels
    float position_sigma_m = 0.25f;   ///< world distance at which the position weight falls to e^-1/2
    float normal_power = 64.0f;       ///< weight (n_p . n_q)^power
    float relative_luminance_sigma = 0.5f;  ///< |Y_p - Y_q| / (Y_p + Y_q) at which the colour weight is e^-1/2
};

/// Options for a bake of `samples` samples per texel: the irradiance edge-stop narrows as the Monte Carlo noise
/// (1/sqrt(samples)) falls, so the filter smooths hard where noise dominates and leaves a well-converged bake
/// nearly untouched instead of adding blur (its bias) to it.
DenoiseOptions denoiseOptionsForSamples(uint32_t samples);

/// Filters rgba (alpha > 0 marks a valid texel; invalid texels neither change nor contribute), in place.
/// guides holds resolution^2 entries (ignored where invalid). O(iterations * 25 * texels).
void denoiseLightmap(std::vector<glm::vec4>& rgba, const std::vector<DenoiseGuide>& guides, int resolution,
                     const DenoiseOptions& options = {});

}  // namespace gusuku::bake

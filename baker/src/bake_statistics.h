#pragma once
// Colour statistics of the baked appearance, for the runtime's CIE Lab colour match (docs/design.md 4): the source
// side of the Reinhard transfer. The appearance of a lightmap texel is rho / pi * (E_ind + V E_sun max(0, n.s)),
// with V the sun's visibility traced on the CPU; mean and standard deviation are over valid texels in Lab.

#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake_geometry.h"
#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

struct LabStatistics {
    glm::vec3 mean{0.0f};
    glm::vec3 sigma{0.0f};
    size_t texel_count = 0;
};

/// Base colour (factor times texture, nearest texel) at a lightmap texel's position.
glm::vec3 albedoAtTexel(const TriangleMesh& mesh, const LightmapTexel& texel);

/// irradiance: per texel of geometry.texels (same order), alpha > 0 where valid.
LabStatistics bakedAppearanceStatistics(const BakeGeometry& geometry, const std::vector<glm::vec4>& irradiance,
                                        const SunLight& sun);

}  // namespace gusuku::bake

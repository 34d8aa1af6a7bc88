#pragma once
// A checker of two ground albedos in 1 m squares (a dark stone and a light sand), so that neighbouring ground cells
// differ: the ground colour match and the sun evidence must compare each camera sample with its own cell's albedo.
// Shared by test_colour_match_ground and test_runtime_sun_evidence.

#include <cmath>

#include <glm/vec3.hpp>

#include "gusuku/assets/bakeset_loader.h"

namespace gusuku::testing {

/// Writes the checker into bake_set's ground albedo; a bake set without one gets it (all ones, then the checker).
inline void paintCheckerGroundAlbedo(BakeSetData& bake_set) {
    const GroundGrid& grid = bake_set.manifest.ground_grid.grid;
    if (bake_set.ground_albedo.rgba.empty()) {
        bake_set.manifest.ground_grid.albedo = "ground_albedo.exr";
        bake_set.ground_albedo.width = grid.columns;
        bake_set.ground_albedo.height = grid.rows;
        bake_set.ground_albedo.rgba.assign(grid.cellCount() * 4, 1.0f);
    }
    for (int row = 0; row < grid.rows; ++row)
        for (int column = 0; column < grid.columns; ++column) {
            const glm::dvec2 centre = groundCellCentreEnu(grid, {column, row});
            const bool dark = (int(std::floor(centre.x)) + int(std::floor(centre.y))) % 2 != 0;
            const glm::vec3 albedo = dark ? glm::vec3(0.30f, 0.26f, 0.20f) : glm::vec3(0.55f, 0.50f, 0.42f);
            float* texel = &bake_set.ground_albedo.rgba[groundCellIndex(grid, {column, row}) * 4];
            texel[0] = albedo.r;
            texel[1] = albedo.g;
            texel[2] = albedo.b;
        }
}

}  // namespace gusuku::testing

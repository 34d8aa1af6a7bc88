#pragma once
// A bake set made in memory for runtime tests, with every term known in closed form, so a rendered pixel can be
// checked against an independent number rather than against itself:
//   - the site at Nakagusuku (26.2856 N, 127.8008 E, 160 m, UTC+9), bake date 2026-06-21;
//   - the building: an axis-aligned box [-1, 1] x [-1, 1] x [0, height] m (ENU), outward normals, one grey
//     material of albedo `albedo`, each face's lightmap coordinates inside one lightmap of `resolution`^2;
//   - every lightmap texel holds E_ind = `indirect_irradiance` (grey), alpha 1;
//   - a flat ground grid at z = 0 from (-grid_half_m, -grid_half_m), cells of cell_m, normal up, E_with =
//     E_without = `ground_irradiance` (the building changes no baked light, so only its shadow darkens);
//   - slots sunny_0900, sunny_1200, sunny_1500 (suns by SPA at those local times, E_sun = `sun_irradiance`
//     grey) and overcast; colour statistics of each slot set to the same grey appearance;
//   - optionally the ground as an occluder quad (so the occluder's depth sits exactly under the ground pass).

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::testing {

struct SyntheticBakeSetOptions {
    double building_height_m = 3.0;
    float albedo = 0.5f;
    float indirect_irradiance = 1.0f;
    float ground_irradiance = 2.0f;
    float sun_irradiance = 5.0f;
    int lightmap_resolution = 16;
    double grid_half_m = 12.0;
    double cell_m = 0.25;
    bool ground_occluder = true;
    /// A step in the ground: south of y = step_north_m the ground lies step_height_m lower (0: flat). The
    /// occluder follows it (two levels and the riser), so the sample's terrace steps have a closed-form twin.
    double step_height_m = 0.0;
    double step_north_m = -3.0;
    /// A grey ground albedo in every cell (ground_grid.albedo), so the ground colour match (ColourMatch::kGround)
    /// can run; 0: none, as in bake sets made before the field existed.
    float ground_albedo = 0.0f;
};

/// The ground's height (ENU z) at (x, y) for these options: 0, or -step_height_m south of the step.
double syntheticGroundHeight(const SyntheticBakeSetOptions& options, double y);

BakeSetData makeSyntheticBakeSet(const SyntheticBakeSetOptions& options = {});

/// Whether the synthetic box (the default options' 2 x 2 x 3 m) or its shadow may show in the pixel whose centre
/// ray is `ray_enu` from `camera_enu`: the ray passes within `box_margin_m` of the box, or the flat ground point it
/// meets looks back along the sun (unit, towards it) within 0.5 m of the box (the shadow with the PCF's margin).
/// Checked on the CPU by marching, for the tests that pin camera pixels outside this reach bit for bit.
bool mayShowTheBoxOrItsShadow(const glm::dvec3& camera_enu, const glm::dvec3& ray_enu, const glm::dvec3& sun_enu,
                              double box_margin_m);

/// UTC seconds of a local time (hours, minutes) on the synthetic set's bake date at its UTC+9 clock.
double syntheticLocalTime(int hours, int minutes);

}  // namespace gusuku::testing

#pragma once
// The ground grid of a bake set and the shadow-catcher ratio it exists for (docs/design.md 3, docs/bakeset.md):
// the baker writes the grid, the runtime reads it. One home for both, with a GLSL twin of every function in
// shaders/include/ground_ratio.glsl (same names), held to this header by tests/test_ground_ratio.cpp.
//
// Frame and units: the site's east-north-up frame, metres; only ENU x (east) and y (north) address the grid.
// The grid is top-down over the region the building can shade. Image convention (ground_*.exr):
//   - column 0 at the west edge, row 0 at the NORTH edge, so the images read as a map with north up;
//   - cell (column, row) covers x in [origin_x + column cell_m, origin_x + (column + 1) cell_m) and
//     y in [origin_y + (rows - row - 1) cell_m, origin_y + (rows - row) cell_m), so its centre is
//       x = origin_x + (column + 0.5) cell_m,   y = origin_y + (rows - row - 0.5) cell_m;
//   - texel index (the images' and the baker's cell order) = row * columns + column.
// Irradiance (E_with, E_without, E_sun) is in the bake set's units (sky radiance units times steradians), per
// linear Rec.709 channel. glm only: the runtime links this (gusuku_maths) without the I/O stack.

#include <cstddef>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace gusuku {

/// Where the grid lies. The manifest's ground_grid object holds these four (origin_enu_m, cell_m, columns,
/// rows); a default-constructed grid has no cells.
struct GroundGrid {
    glm::dvec2 origin_enu_m{0.0};  ///< south-west corner of the grid (west edge of column 0, south edge of the last row)
    double cell_m = 0.25;          ///< side of a square cell, metres, > 0
    int columns = 0;               ///< cells west to east
    int rows = 0;                  ///< cells north to south

    size_t cellCount() const { return size_t(columns > 0 ? columns : 0) * size_t(rows > 0 ? rows : 0); }
    bool operator==(const GroundGrid& other) const;  ///< every member equal
    bool operator!=(const GroundGrid& other) const { return !(*this == other); }
};

/// A cell by column (west to east) and row (north to south).
struct GroundCellAddress {
    int column = 0;
    int row = 0;
    bool operator==(const GroundCellAddress& other) const;  ///< every member equal
    bool operator!=(const GroundCellAddress& other) const { return !(*this == other); }
};

/// ENU (x, y) of the centre of cell (column, row). Any integers are accepted (cells outside the grid continue
/// its lattice), so callers range-check with groundCellInside when they must.
glm::dvec2 groundCellCentreEnu(const GroundGrid& grid, GroundCellAddress cell);

bool groundCellInside(const GroundGrid& grid, GroundCellAddress cell);

/// The cell whose square holds ENU (x, y) (half-open squares, as above); nothing when the point is outside the
/// grid or not finite. groundCellAt(groundCellCentreEnu(c)) == c for every cell c of the grid.
std::optional<GroundCellAddress> groundCellAt(const GroundGrid& grid, const glm::dvec2& enu_xy);

/// Texel index in the ground images: row * columns + column. The cell must be inside the grid.
size_t groundCellIndex(const GroundGrid& grid, GroundCellAddress cell);
/// Inverse of groundCellIndex for index < cellCount().
GroundCellAddress groundCellFromIndex(const GroundGrid& grid, size_t index);

/// Normalised texture coordinates of ENU (x, y) in the ground images, for a sampler with Vulkan's conventions
/// (texel (column, row) has its centre at ((column + 0.5) / columns, (row + 0.5) / rows)):
///   u = (x - origin_x) / (columns cell_m),   v = (origin_y + rows cell_m - y) / (rows cell_m).
/// A cell centre lands exactly on its texel centre; points outside the grid give u or v outside [0, 1].
glm::dvec2 groundGridUv(const GroundGrid& grid, const glm::dvec2& enu_xy);

// ------------------------------------------------------------------------------------------------------------
// The shadow-catcher ratio (differential rendering, Debevec 1998; docs/design.md 3)
// ------------------------------------------------------------------------------------------------------------
// The runtime never draws the ground: it scales the camera pixel of a ground point by
//   ratio = (E_with + V_bld E_sun) / (E_without + E_sun),   E_sun = V_scene I_sun max(0, n . s)
// per channel, with E_with / E_without the ground's baked sky-and-bounce irradiance with and without the
// building (ground_<slot>_with.exr / _without.exr), I_sun the sun's irradiance on a plane facing it (the slot's
// irradiance_rgb carried to the current sun), n the ground's unit normal (ground_geometry.exr), s the unit
// direction towards the sun (ENU), V_bld the building's shadow on the point (shadow map: 1 lit, 0 shadowed).
// V_scene is the real scene's own shadow (0 where the real site already shades the point, 1 elsewhere): a point
// the real sun does not reach gets no new sun term, so there the ratio is E_with / E_without and the building
// changes only its sky and bounce light. Where the building changes nothing (E_with = E_without, V_bld = 1) the
// ratio is exactly 1, so the photo passes through unchanged.
//
// Guard: a channel whose denominator E_without + E_sun is not > 0 (no light at all without the building, or
// NaN input) gets ratio 1: with nothing to scale from, the photo is left as it is.
// Cells with no ground under them (alpha 0 in the ground images) hold E_with = E_without = 0: the caller must
// pass the photo through there (ratio 1) itself; the ratio cannot tell such a cell from an unlit real point.
//
// float32, as on the GPU: the twin computes the same expressions in the same order.

/// E_sun at a ground point: scene_visibility * sun_irradiance_rgb * max(0, dot(normal, sun_direction_enu)).
glm::vec3 groundSunIrradiance(const glm::vec3& sun_irradiance_rgb, const glm::vec3& normal_enu,
                              const glm::vec3& sun_direction_enu, float scene_visibility);

/// The ratio above, per channel, with the zero-denominator guard. building_visibility is V_bld in [0, 1].
glm::vec3 groundShadowRatio(const glm::vec3& e_with, const glm::vec3& e_without, const glm::vec3& e_sun,
                            float building_visibility);

}  // namespace gusuku

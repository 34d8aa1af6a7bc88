#pragma once
// Which ground quads a frame draws (docs/design.md 8 step 6), on the CPU: those touching a cell whose baked
// light the building changes (proposed mode), or a cell whose ray towards the sun passes through the building's
// bounds grown by a margin (its shadow may fall there). The rest of the grid is not drawn at all: its camera
// pixels are never touched. A pure function over arrays made once at open, so a frame allocates nothing;
// tests/test_frame_preparation.cpp checks it against a brute-force search. Private to gusuku_runtime.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "gusuku/formats/ground_grid.h"

namespace gusuku::runtime_detail {

/// GpuScene::ground_cell_state's values (runtime_scene.h), per cell in texel order.
constexpr uint8_t kCellNoGround = 0;
constexpr uint8_t kCellGround = 1;
constexpr uint8_t kCellGroundChangedByBuilding = 2;  ///< the building changes its baked light in some slot

/// The building's bounds are grown by this many ground cells plus kShadowReachMarginM before the sun-ray test.
/// The test looks at cell centres only, yet the shadow is drawn between them: a quad is drawn when one of its
/// corner cells is marked, so the shadow's edge may lie up to a cell past the nearest marked centre; and the
/// drawn shadow reaches past the exact one by the PCF's footprint and by the shadow maps' rounded sun
/// (RuntimeOptions::shadow_sun_step_deg; the quads are chosen for that same rounded sun). Two cells cover both...
constexpr double kShadowReachMarginCells = 2.0;
/// ... plus this fixed reach in metres, which keeps the margin from vanishing on grids of fine cells.
constexpr double kShadowReachMarginM = 0.25;

/// The margin the building's bounds grow by for a grid of cell_m cells.
double groundShadowMarginM(double cell_m);

/// The ENU centre of cell (column, row) at the given height (row 0 is the grid's north edge).
glm::dvec3 groundCellCentre(const GroundGrid& grid, size_t column, size_t row, double height_m);

/// Whether the ray origin + t direction, t >= 0, meets the box [low, high] (slab test; a direction component of
/// 0 meets it only when the origin lies within that slab).
bool rayMeetsBox(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& low, const glm::dvec3& high);

/// The CPU's copy of the ground grid's cells (GpuScene::ground_cell_state and ground_cell_height).
struct GroundCells {
    GroundGrid grid;
    std::span<const uint8_t> state;  ///< kCell* per cell
    std::span<const float> height;   ///< ENU z per cell
    std::span<const glm::vec3> normal = {};  ///< ENU unit normal per cell (empty: not known)
};

/// What the frame draws of the quads written: the first shadow_index_count indices are the quads the building's
/// shadow may reach (drawn with the shadow-reading shader), the rest up to index_count the others.
struct GroundQuadSelection {
    uint32_t index_count = 0;         ///< all triangles drawn, times 3
    uint32_t shadow_index_count = 0;  ///< the first of them (the shadow quads' triangles), times 3
    uint32_t quads = 0;               ///< quads with at least one triangle drawn
};

/// Chooses the quads (see above). marked and shadow_candidate have one entry per cell; quad_indices room for
/// every quad ((columns - 1)(rows - 1), 6 indices each: two triangles between four neighbouring cell centres).
/// Writes marked (1: the cell makes its quads drawn), shadow_candidate (1.0: the building's shadow may fall on
/// the cell, the ground pass's per-vertex stream) and the chosen quads' indices: of each quad only the triangles
/// (a c b, b c d) with a marked corner. Nothing is drawn, and nothing
/// written, when quad_indices is empty or the cells do not match the grid. pass_through (empty, or one entry per
/// cell): 1 where the baked change leaves the ratio at exactly 1 in this frame's light (ground_sunlit.h), so the
/// baked change does not mark the cell.
GroundQuadSelection selectGroundQuads(const GroundCells& cells, const glm::dvec3& building_min,
                                      const glm::dvec3& building_max, bool include_baked_changes, bool sun_shines,
                                      const glm::dvec3& sun_direction, std::span<uint8_t> marked,
                                      std::span<float> shadow_candidate, std::span<uint32_t> quad_indices,
                                      std::span<const uint8_t> pass_through = {});

}  // namespace gusuku::runtime_detail

#pragma once
// The ground cells the building covers (docs/design.md 3, "The ground at the building's foot"): the runtime draws
// the ground ratio between cell centres (ground.vert: its vertices are the cell centres), so the fragments of a
// quad with one corner under the building take part of that corner's light. Under a 2 cm platform E_with is about
// 0 (the point is inside it), and the visible ground beside the platform read a ratio of 0.6 at its foot and a
// dark band half a cell (25 cm at 0.5 m cells) wide in the scene. A covered cell's centre is never seen (the
// building hides it); its ratio is only a corner of the quads beside it, so it carries its uncovered neighbours'.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "bake_geometry.h"

namespace gusuku::bake {

/// A cell is covered when the building lies over its ground within this height: no camera sees the ground's
/// light under a gap this low at a cell's scale (a 2 cm platform, a floor slab, a part sunk into the ground).
inline constexpr float kCoveredGapM = 0.10f;

/// Per ground cell (row-major, as ground_cells): 1 where the cell has ground and a building triangle lies straight
/// above its centre within kCoveredGapM (a ray from 1 mm above the ground, so a part whose bottom face lies on the
/// ground is met from inside).
std::vector<uint8_t> coveredGroundCells(const BakeGeometry& geometry);

/// `with_sums` (one per cell with ground, in ground_cells' order, as traced) with each covered cell's E_with
/// replaced by its E_without times the mean ratio E_with / E_without (per channel) of its nearest uncovered
/// neighbours, ring by ring (the 8 neighbours, then theirs), so that every covered cell next to open ground
/// carries that ground's ratio. A covered region with no uncovered cell keeps its traced values. The w channel
/// (the backface count) is kept.
std::vector<glm::vec4> withCoveredCellsFilled(const BakeGeometry& geometry, const std::vector<uint8_t>& covered,
                                              const std::vector<glm::vec4>& with_sums,
                                              const std::vector<glm::vec4>& without_sums);

}  // namespace gusuku::bake

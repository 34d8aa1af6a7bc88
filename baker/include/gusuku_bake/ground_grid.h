#pragma once
// The ground grid (docs/design.md 3): a top-down grid over the region the building can shade or light (its
// footprint plus the shadow reach at the lowest baked sun, plus a bounce margin), holding the real ground's
// height and normal (from the SfM mesh) and, per slot, the ground's sky-and-bounce irradiance with and without
// the building. The runtime turns those into the shadow-catcher ratio.
//
// The grid's addressing (cell <-> ENU position, image order) is shared with the runtime and lives in
// gusuku/formats/ground_grid.h (column 0 west, row 0 NORTH); this header chooses the region and samples the ground.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gusuku/formats/ground_grid.h"
#include "gusuku/maths/mesh.h"
#include "gusuku_bake/bvh.h"

namespace gusuku::bake {

/// The baker's ground region is the bake set's ground grid (origin, cell size, columns, rows).
using GroundRegion = gusuku::GroundGrid;

/// The region: the building's footprint grown by shadow_reach = height / tan(max(lowest_sun_elevation, 10 deg))
/// (the 10 degree floor keeps a low winter sun from asking for an unbounded grid) plus a bounce margin of half
/// the building's height (at least 1 m). lowest_sun_elevation_deg < 0 means no sun (overcast only): reach 0.
/// The cell size grows if needed so the grid has at most max_cells_per_side per side.
GroundRegion chooseGroundRegion(const Bounds3& building_bounds, double lowest_sun_elevation_deg, double cell_m,
                                int max_cells_per_side = 512);

struct GroundCell {
    bool valid = false;        ///< the SfM mesh lies under the cell centre
    float height_m = 0.0f;     ///< ENU z of the ground at the cell centre
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< unit, facing up
};

/// Heights and normals by casting a ray straight down through each cell centre from above everything, against
/// the triangles not flagged skip_flags (the building is skipped: the ground under it is still ground).
std::vector<GroundCell> sampleGround(const GroundRegion& region, const Bvh& bvh, const TriangleMesh& mesh,
                                     uint32_t skip_flags, float top_z);

/// ENU (x, y) of cell (column, row)'s centre: gusuku::groundCellCentreEnu.
inline glm::dvec2 groundCellCentre(const GroundRegion& region, int column, int row) {
    return groundCellCentreEnu(region, {column, row});
}

/// A flat square at z = 0 (albedo 0.2) covering `half_size_m` around the origin: the ground stand-in when a
/// site has no SfM mesh. Two triangles, facing up.
TriangleMesh makeFlatGround(double half_size_m, const glm::vec3& albedo = glm::vec3(0.2f));

}  // namespace gusuku::bake

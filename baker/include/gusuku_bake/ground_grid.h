#pragma once
// The ground grid (docs/design.md 3): a top-down grid over the region the building can shade or light (its
// footprint plus the shadow reach at the lowest baked sun, plus a bounce margin; the site mesh's own relief near it
// adds its own such region, so the site's shadows the runtime reads the sun from are inside too), holding the real ground's
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

/// The site mesh's own relief near the building: the bounds of its steep faces (walls, steps, terrace edges:
/// steeper than 60 degrees, at least kSiteReliefMinHeightM tall) whose centre lies within search_m of the
/// building's footprint; empty where there is none (a flat stand-in). Such relief casts shadows of its own that
/// the runtime reads the sun from (issue 41): the ground grid covers it and its shadow reach too, not only the
/// building's, or the camera's site shadow boundaries fall outside the grid.
inline constexpr double kSiteReliefMinHeightM = 0.2;
Bounds3 siteReliefBounds(const TriangleMesh& site_mesh, const Bounds3& building_bounds, double search_m);

/// How far from the building's footprint the site's relief counts: the ground a visitor near the building sees,
/// without growing the grid over a whole photogrammetry block.
inline constexpr double kSiteReliefSearchM = 20.0;

/// The bake's region: the building's (chooseGroundRegion) joined with the site's relief's near it (siteReliefBounds
/// within kSiteReliefSearchM, grown by the relief's own shadow reach), so the relief's own shadows at the lowest
/// baked sun are inside; the building's region alone where there is no relief.
GroundRegion chooseSiteGroundRegion(const Bounds3& building_bounds, const TriangleMesh& site_mesh,
                                    double lowest_sun_elevation_deg, double cell_m, int max_cells_per_side = 512);

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

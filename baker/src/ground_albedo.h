#pragma once
// The ground's albedo per ground-grid cell (docs/bakeset.md "Ground albedo"): what the runtime's ground colour
// match (gusuku/maths/colour_match.h, ColourMatch::kGround) needs to predict the camera's pixels of the real ground.

#include <vector>

#include <glm/vec4.hpp>

#include "bake_geometry.h"

namespace gusuku::bake {

/// The bake set's file of the ground albedo (manifest ground_grid.albedo).
inline constexpr const char* kGroundAlbedoFile = "ground_albedo.exr";

/// Per cell (texel order, gusuku/formats/ground_grid.h): RGB the linear base colour (material factor times its texture,
/// the texel nearest the hit's uv) of the site's triangles, averaged over 4 x 4 points spread evenly over the cell,
/// A 1; cells without ground (no SfM mesh under the centre, as ground_cells says) (0, 0, 0, 0). Each point's
/// triangle is found as sampleGround finds the centre's (a ray straight down from above the scene, the building's
/// triangles skipped).
std::vector<glm::vec4> sampleGroundAlbedo(const BakeGeometry& geometry);

}  // namespace gusuku::bake

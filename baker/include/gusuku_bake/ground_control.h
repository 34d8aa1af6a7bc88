#pragma once
// Ground control points for `gusuku-bake georef`: a small CSV file pairing points' positions in the
// photogrammetry mesh with their surveyed positions, read into the site's ENU metres (docs/site-json.md,
// "Georeferencing"). The file:
//
//   # comments and blank lines are skipped
//   name,mesh_x,mesh_y,mesh_z,latitude_deg,longitude_deg,height_m
//   gate_nw,12.31,-4.02,7.88,26.285712,127.800934,162.31
//
// or, for a projected grid (UTM on WGS84, the zone given apart), the header
//   name,mesh_x,mesh_y,mesh_z,easting_m,northing_m,height_m
// Heights are above the WGS84 ellipsoid in both forms.

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/assets/geodetic.h"
#include "gusuku/assets/utm_grid.h"

namespace gusuku::bake {

struct GroundControlPoint {
    std::string name;
    int line = 0;           ///< its line in the file, from 1
    glm::dvec3 mesh{0.0};   ///< in the mesh's own coordinates
    glm::dvec3 enu_m{0.0};  ///< surveyed, in the site's ENU frame
};

/// The header line of each form, as the file must write it (spaces around commas are allowed).
inline constexpr const char* kGeodeticControlHeader = "name,mesh_x,mesh_y,mesh_z,latitude_deg,longitude_deg,height_m";
inline constexpr const char* kGridControlHeader = "name,mesh_x,mesh_y,mesh_z,easting_m,northing_m,height_m";
/// A surveyed point farther than this from the ENU origin is refused: site.json's translation range, and far
/// beyond any site, so it means a wrong zone, origin or column order.
inline constexpr double kMaxControlDistanceM = 100000.0;

/// Reads `text`, the contents of the file at `path`, converting each surveyed position to ENU about `origin`
/// (GeographicLib LocalCartesian; grid positions first through UTMUPS in `zone`, required for the grid form).
/// Throws InputError(path, "line N", problem) for the first bad line: a wrong header, a missing or extra column,
/// a value that is not a decimal number (NaN, inf), out of range (a latitude of 200), an empty or repeated name.
std::vector<GroundControlPoint> readGroundControlPoints(const std::string& path, const std::string& text,
                                                       const GeodeticPoint& origin,
                                                       const std::optional<UtmZone>& zone);

}  // namespace gusuku::bake

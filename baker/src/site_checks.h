#pragma once
// Placement checks a bake cannot make for itself (issue 42 items 3, 4), run by `gusuku-bake check` and `preview`:
// the building's base against the site mesh's ground around it, the site mesh's up (its faces' normals), and the
// sky's sun against the computed sun (at the sky's taken_at, else anywhere on the bake's day). Each warning is
// one line "FILE: FIELD: PROBLEM: what to change", the field a JSON pointer into site.json.

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/assets/site.h"
#include "gusuku/maths/image_rgba.h"
#include "gusuku/maths/mesh.h"

namespace gusuku::bake_cli {

/// The building's base may stand this far above or below the site mesh's ground before check warns: a survey
/// mesh's ground is within a few centimetres, a plinth or a step a little more.
inline constexpr double kBaseGapToleranceM = 0.25;
/// The ground around the building is sampled on a ring this far outside its footprint's box (outside any ruin of
/// it the survey still shows, near enough that the slope adds little).
inline constexpr double kGroundRingOffsetM = 1.0;
/// The site mesh's mean face normal may lean this far from up before check calls its up axis wrong: a hillside
/// leans 10-20 degrees, a mesh on its side 90.
inline constexpr double kUpAxisToleranceDeg = 30.0;
/// Below this length of the area-weighted mean unit normal the faces' facing says nothing (mixed winding, a
/// closed object) and no up check is made.
inline constexpr double kUpAxisMinMeanNormal = 0.3;
/// The sky's sun may stand this far from the computed sun before check warns: a hand-held 360 camera tilts a
/// degree or two, a 1024-wide map's texels are 0.35 degrees.
inline constexpr double kSkySunToleranceDeg = 5.0;

/// The building's base against the ground, for check's warning and preview's picture.
struct BaseGap {
    double base_up_m = 0.0;    ///< the building's lowest vertex, ENU up
    double ground_up_m = 0.0;  ///< median height of the site mesh on the ring around the footprint
    int ground_points = 0;     ///< ring points that found the site mesh under (or over) them
    double gapM() const { return base_up_m - ground_up_m; }
};
/// Empty when the ring finds no site mesh (the building stands off the mesh; check says so otherwise).
std::optional<BaseGap> measureBaseGap(const TriangleMesh& building, const TriangleMesh& site_mesh);

/// The site mesh's area-weighted mean unit face normal, ENU (its length says how much the faces agree).
glm::dvec3 meanFaceNormal(const TriangleMesh& mesh);

/// The sky's sun seen in the map against the computed sun.
struct SkySunComparison {
    bool sun_found = false;
    double seen_azimuth_deg = 0.0, seen_elevation_deg = 0.0;  ///< with site.json's north
    bool at_taken_at = false;     ///< true: against the sun at taken_at; false: the nearest sun on bake.date
    double computed_azimuth_deg = 0.0, computed_elevation_deg = 0.0;
    double nearest_utc_seconds = 0.0;  ///< the instant of the computed sun compared
    double angle_deg = 0.0;            ///< between the two directions
    double north_from_sun_deg = 0.0;   ///< the north that puts the seen sun at the computed azimuth
};
SkySunComparison compareSkySun(const SiteConfig& config, const SkyConfig& sky, const ImageRGBA& radiance,
                               const std::optional<double>& taken_at_utc_seconds);

/// All the placement checks' warnings (and, in `notes`, what they found when it is fine), for check and preview.
/// `site_mesh` is null without an sfm_mesh; `sunny_radiance` is the sunny sky as read (sun not removed).
std::vector<std::string> placementWarnings(const SiteConfig& config, const TriangleMesh& building,
                                           const TriangleMesh* site_mesh, const ImageRGBA& sunny_radiance,
                                           std::vector<std::string>& notes);

}  // namespace gusuku::bake_cli

// Placement checks for check and preview (site_checks.h).
#include "site_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <glm/geometric.hpp>

#include "gusuku/assets/sky_sun.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku::bake_cli {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
// Ring points: about this many along the ring, never closer than 0.25 m (a small building still gets a few).
constexpr int kRingPoints = 64;
constexpr double kMinRingSpacingM = 0.25;
// The day's sun path, without taken_at, in steps of this many seconds (the sun moves 0.5 deg in 2 minutes).
constexpr double kSunPathStepS = 120.0;

std::string format(const char* pattern, double a) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, a);
    return text;
}

std::string utcOffsetText(int minutes) {
    char text[16];
    std::snprintf(text, sizeof text, "%c%02d:%02d", minutes < 0 ? '-' : '+', std::abs(minutes) / 60, std::abs(minutes) % 60);
    return text;
}

double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * kDegPerRad;
}

std::vector<glm::dvec2> ringAround(const Bounds3& footprint) {
    const glm::dvec2 low(footprint.min.x - kGroundRingOffsetM, footprint.min.y - kGroundRingOffsetM);
    const glm::dvec2 high(footprint.max.x + kGroundRingOffsetM, footprint.max.y + kGroundRingOffsetM);
    const glm::dvec2 size = high - low;
    const double perimeter = 2.0 * (size.x + size.y);
    const double spacing = std::max(kMinRingSpacingM, perimeter / kRingPoints);
    std::vector<glm::dvec2> points;
    for (double s = 0.5 * spacing; s < perimeter; s += spacing) {
        double t = s;
        if (t < size.x) points.push_back({low.x + t, low.y});
        else if ((t -= size.x) < size.y) points.push_back({high.x, low.y + t});
        else if ((t -= size.y) < size.x) points.push_back({high.x - t, high.y});
        else points.push_back({low.x, high.y - (t - size.x)});
    }
    return points;
}

// The (x, y) -> up of the triangle's plane at point p when p is inside its footprint (edges included).
std::optional<double> heightInTriangle(const glm::dvec2& p, const glm::dvec3& a, const glm::dvec3& b,
                                       const glm::dvec3& c) {
    const double d = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
    if (std::abs(d) < 1e-12) return std::nullopt;  // a vertical face has no single height
    const double wa = ((b.y - c.y) * (p.x - c.x) + (c.x - b.x) * (p.y - c.y)) / d;
    const double wb = ((c.y - a.y) * (p.x - c.x) + (a.x - c.x) * (p.y - c.y)) / d;
    const double wc = 1.0 - wa - wb;
    constexpr double kEdge = -1e-9;
    if (wa < kEdge || wb < kEdge || wc < kEdge) return std::nullopt;
    return wa * a.z + wb * b.z + wc * c.z;
}

std::string buildingHeightAdvice(const SiteConfig& config, double gap_m, std::string& field) {
    const BuildingConfig& building = config.building;
    if (building.position) {
        field = "/building/position/height_m";
        return "set height_m to " + format("%.2f", building.position->height_m - gap_m) + " (now " +
               format("%.2f", building.position->height_m) + ")";
    }
    field = "/building/enu_offset_m";
    const glm::dvec3 offset = building.enu_offset_m.value_or(glm::dvec3(0.0));
    return "set enu_offset_m's up (third number) to " + format("%.2f", offset.z - gap_m) + " (now " +
           format("%.2f", offset.z) + ")";
}

}  // namespace

std::optional<BaseGap> measureBaseGap(const TriangleMesh& building, const TriangleMesh& site_mesh) {
    const Bounds3 footprint = meshBounds(building);
    if (footprint.empty()) return std::nullopt;
    const std::vector<glm::dvec2> ring = ringAround(footprint);
    const double reach = kGroundRingOffsetM + 1e-3;
    // The lowest surface over each ring point: a tree or a wall over the ground stands above it.
    std::vector<double> lowest(ring.size(), HUGE_VAL);
    for (size_t t = 0; t + 2 < site_mesh.indices.size(); t += 3) {
        const glm::dvec3 a(site_mesh.positions[site_mesh.indices[t]]);
        const glm::dvec3 b(site_mesh.positions[site_mesh.indices[t + 1]]);
        const glm::dvec3 c(site_mesh.positions[site_mesh.indices[t + 2]]);
        const double min_x = std::min({a.x, b.x, c.x}), max_x = std::max({a.x, b.x, c.x});
        const double min_y = std::min({a.y, b.y, c.y}), max_y = std::max({a.y, b.y, c.y});
        if (max_x < footprint.min.x - reach || min_x > footprint.max.x + reach || max_y < footprint.min.y - reach ||
            min_y > footprint.max.y + reach)
            continue;
        for (size_t i = 0; i < ring.size(); ++i) {
            const glm::dvec2& p = ring[i];
            if (p.x < min_x || p.x > max_x || p.y < min_y || p.y > max_y) continue;
            if (const std::optional<double> up = heightInTriangle(p, a, b, c)) lowest[i] = std::min(lowest[i], *up);
        }
    }
    std::vector<double> heights;
    for (const double up : lowest)
        if (std::isfinite(up)) heights.push_back(up);
    if (heights.empty()) return std::nullopt;
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    BaseGap gap;
    gap.base_up_m = footprint.min.z;
    gap.ground_up_m = heights[heights.size() / 2];
    gap.ground_points = int(heights.size());
    return gap;
}

glm::dvec3 meanFaceNormal(const TriangleMesh& mesh) {
    glm::dvec3 weighted(0.0);
    double area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]);
        const glm::dvec3 cross = glm::cross(glm::dvec3(mesh.positions[mesh.indices[t + 1]]) - a,
                                            glm::dvec3(mesh.positions[mesh.indices[t + 2]]) - a);
        weighted += cross;  // |cross| is twice the area, the same factor for both sums
        area += glm::length(cross);
    }
    return area > 0.0 ? weighted / area : glm::dvec3(0.0);
}

SkySunComparison compareSkySun(const SiteConfig& config, const SkyConfig& sky, const ImageRGBA& radiance,
                               const std::optional<double>& taken_at_utc_seconds) {
    SkySunComparison comparison;
    const SkySunSighting seen = findSkySun(radiance);
    if (!seen.found) return comparison;
    comparison.sun_found = true;
    const glm::dvec3 seen_direction = skySunDirectionEnu(seen, sky.north_azimuth_in_image_deg);
    comparison.seen_elevation_deg = seen.elevation_deg;
    comparison.seen_azimuth_deg = std::fmod(seen.image_azimuth_deg - sky.north_azimuth_in_image_deg + 720.0, 360.0);
    const SunObserver observer = config.site.sunObserver();
    SunPosition nearest;
    if (taken_at_utc_seconds) {
        comparison.at_taken_at = true;
        comparison.nearest_utc_seconds = *taken_at_utc_seconds;
        nearest = computeSunPosition(observer, *taken_at_utc_seconds);
    } else {
        const double midnight = parseDateAtOffset(config.bake.date, config.site.utc_offset_minutes);
        double best = -2.0;
        for (double t = midnight; t < midnight + 86400.0; t += kSunPathStepS) {
            const SunPosition sun = computeSunPosition(observer, t);
            if (!sun.above_horizon) continue;
            if (const double cosine = glm::dot(sun.direction_enu, seen_direction); cosine > best) {
                best = cosine;
                nearest = sun;
                comparison.nearest_utc_seconds = t;
            }
        }
        if (best < -1.5) nearest = computeSunPosition(observer, midnight + 43200.0);
    }
    comparison.computed_azimuth_deg = nearest.azimuth_deg;
    comparison.computed_elevation_deg = nearest.apparent_elevation_deg;
    comparison.angle_deg = angleDeg(seen_direction, nearest.direction_enu);
    comparison.north_from_sun_deg = northAzimuthInImageFromSun(seen.image_azimuth_deg, nearest.azimuth_deg);
    return comparison;
}

namespace {

// The site mesh's faces against up; false (with a warning) when they lean beyond kUpAxisToleranceDeg.
bool checkUpAxis(const SiteConfig& config, const TriangleMesh& site_mesh, std::vector<std::string>& warnings,
                 std::vector<std::string>& notes) {
    const std::string& file = config.file;
    const glm::dvec3 mean_normal = meanFaceNormal(site_mesh);
    if (glm::length(mean_normal) < kUpAxisMinMeanNormal) return true;  // the faces disagree: nothing to tell
    const double lean_deg = angleDeg(mean_normal, {0, 0, 1});
    notes.push_back("site mesh's faces: mean normal " + format("%.2f", mean_normal.x) + ", " +
                    format("%.2f", mean_normal.y) + ", " + format("%.2f", mean_normal.z) + " (ENU), " +
                    format("%.0f", lean_deg) + " deg from up");
    if (lean_deg <= kUpAxisToleranceDeg) return true;
    // The fix: the rotation taking the faces' mean normal, snapped to the nearest ENU axis, onto up,
    // before the given rotation. Snapping keeps the fix to a quarter or half turn, as an axis mix-up is.
    glm::dvec3 axis(0.0);
    int largest = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(mean_normal[i]) > std::abs(mean_normal[largest])) largest = i;
    axis[largest] = mean_normal[largest] > 0 ? 1.0 : -1.0;
    // Quaternion of the rotation from `axis` to +z: about axis x z by the angle between them; a half
    // turn (axis -z) about east.
    double fix[4] = {1, 0, 0, 0};
    if (axis.z < -0.5) fix[0] = 0, fix[1] = 1;
    else if (axis.z < 0.5) {
        const glm::dvec3 about = glm::normalize(glm::cross(axis, glm::dvec3(0, 0, 1)));
        const double half = std::sqrt(0.5);
        fix[0] = half, fix[1] = half * about.x, fix[2] = half * about.y, fix[3] = half * about.z;
    }
    const std::array<double, 4>& q = config.sfm_mesh->rotation_wxyz;
    const double product[4] = {fix[0] * q[0] - fix[1] * q[1] - fix[2] * q[2] - fix[3] * q[3],
                               fix[0] * q[1] + fix[1] * q[0] + fix[2] * q[3] - fix[3] * q[2],
                               fix[0] * q[2] - fix[1] * q[3] + fix[2] * q[0] + fix[3] * q[1],
                               fix[0] * q[3] + fix[1] * q[2] - fix[2] * q[1] + fix[3] * q[0]};
    const char* names[3] = {"east", "north", "up"};
    const std::string towards = std::string(axis[largest] > 0 ? "" : "-") + names[largest];
    std::string wxyz;
    for (int i = 0; i < 4; ++i)
        wxyz += (i ? ", " : "") + format("%.4f", std::abs(product[i]) < 5e-5 ? 0.0 : product[i]);
    warnings.push_back(
        file + ": /sfm_mesh/rotation_wxyz: the site mesh's ground faces face " + towards + " (mean normal " +
        format("%.0f", lean_deg) + " deg from up, more than " + format("%.0f", kUpAxisToleranceDeg) +
        "): the mesh's up axis is not mapped to up (a Y-up or Z-down export)" +
        (axis.z < -0.5 ? ", or its faces are wound inwards" : "") + "; set rotation_wxyz to [" + wxyz +
        "] and check translation_enu_m again (or fit all three with gusuku-bake georef)");
    return false;
}

// The building's base against the site mesh's ground around it.
void checkBaseGap(const SiteConfig& config, const TriangleMesh& building, const TriangleMesh& site_mesh,
                  std::vector<std::string>& warnings, std::vector<std::string>& notes) {
    const std::string& file = config.file;
    if (const std::optional<BaseGap> gap = measureBaseGap(building, site_mesh)) {
        const double gap_m = gap->gapM();
        const std::string where = format("%.2f m ", std::abs(gap_m)) + (gap_m > 0 ? "above" : "below") +
                                  " the site mesh's ground around it (the median of " +
                                  std::to_string(gap->ground_points) + " points " +
                                  format("%g m", kGroundRingOffsetM) + " outside its footprint)";
        if (std::abs(gap_m) > kBaseGapToleranceM) {
            std::string field;
            const std::string advice = buildingHeightAdvice(config, gap_m, field);
            std::string why = gap_m > 0 ? "floats" : "is sunk";
            std::string geoid;
            if (std::abs(gap_m) > 5.0)
                geoid = "; a height above sea level given where the ellipsoid height was meant is off by the "
                        "geoid, tens of metres";
            warnings.push_back(file + ": " + field + ": the building " + why + ": its base stands " + where +
                               ", more than " + format("%g m", kBaseGapToleranceM) + "; " + advice +
                               ", or move the site mesh (sfm_mesh's translation_enu_m up) by " +
                               format("%+.2f m", gap_m) + " if the building's height is the surveyed one" + geoid);
        } else {
            notes.push_back("building's base: " + where);
        }
    } else {
        notes.push_back("building's base: no site mesh within " + format("%g m", kGroundRingOffsetM) +
                        " of its footprint to compare with");
    }
}

// The sunny sky's sun against the computed sun: at taken_at, else on bake.date.
void checkSkySun(const SiteConfig& config, const ImageRGBA& sunny_radiance, std::vector<std::string>& warnings,
                 std::vector<std::string>& notes) {
    const std::string& file = config.file;
    const SkyCaptureTime capture = readSkyCaptureTime(file, "sunny");
    if (capture.north_auto) {
        notes.push_back("sunny sky: north from the sun at taken_at " + capture.taken_at_text + ": " +
                        format("%.2f", config.sunny_sky.north_azimuth_in_image_deg) + " deg in the image");
    } else {
        const SkySunComparison sun = compareSkySun(config, config.sunny_sky, sunny_radiance,
                                                   capture.taken_at_utc_seconds);
        const std::string north_field = file + ": /skies/sunny/north_azimuth_in_image_deg: ";
        if (!sun.sun_found) {
            notes.push_back("sunny sky: no sun seen in it (no bright spot under " +
                            format("%g", kSkySunMaxCoreRadiusDeg) + " deg across); its north is not checked");
        } else {
            const std::string seen = "the sun in the sky (azimuth " + format("%.1f", sun.seen_azimuth_deg) +
                                     " deg with this north, elevation " + format("%.1f", sun.seen_elevation_deg) +
                                     " deg)";
            const std::string computed = "the computed sun at " +
                                         formatIso8601(sun.nearest_utc_seconds, config.site.utc_offset_minutes) +
                                         " (azimuth " + format("%.1f", sun.computed_azimuth_deg) + ", elevation " +
                                         format("%.1f", sun.computed_elevation_deg) + ")";
            const double elevation_gap = std::abs(sun.seen_elevation_deg - sun.computed_elevation_deg);
            if (sun.angle_deg <= kSkySunToleranceDeg) {
                notes.push_back("sunny sky: " + seen + " stands " + format("%.1f", sun.angle_deg) + " deg from " +
                                computed);
            } else if (sun.at_taken_at && elevation_gap > kSkySunToleranceDeg) {
                warnings.push_back(file + ": /skies/sunny/taken_at: " + seen + " stands " +
                                   format("%.1f", elevation_gap) + " deg higher or lower than " + computed +
                                   ": taken_at (or its UTC offset) is not when the photo was taken, or the photo is "
                                   "not level; correct taken_at");
            } else if (sun.at_taken_at) {
                warnings.push_back(north_field + seen + " stands " + format("%.1f", sun.angle_deg) + " deg from " +
                                   computed + ": set north_azimuth_in_image_deg to " +
                                   format("%.2f", sun.north_from_sun_deg) + " (now " +
                                   format("%.2f", config.sunny_sky.north_azimuth_in_image_deg) +
                                   "), or to \"auto\", which computes it from the sun");
            } else {
                warnings.push_back(north_field + seen + " stands " + format("%.1f", sun.angle_deg) +
                                   " deg from the nearest point of the sun's path on " + config.bake.date +
                                   ": the north is off (or the photo is from another season); give the sky's "
                                   "taken_at (when the photo was taken, e.g. \"" +
                                   formatIso8601(sun.nearest_utc_seconds, config.site.utc_offset_minutes)
                                       .substr(0, 16) +
                                   utcOffsetText(config.site.utc_offset_minutes) +
                                   "\") and set north_azimuth_in_image_deg to \"auto\" to take the north from the "
                                   "sun");
            }
        }
    }
}

}  // namespace

std::vector<std::string> placementWarnings(const SiteConfig& config, const TriangleMesh& building,
                                           const TriangleMesh* site_mesh, const ImageRGBA& sunny_radiance,
                                           std::vector<std::string>& notes) {
    std::vector<std::string> warnings;
    // A mesh on its side has no ground under the building: the base check would measure nonsense.
    if (site_mesh && site_mesh->triangleCount() > 0 && checkUpAxis(config, *site_mesh, warnings, notes))
        checkBaseGap(config, building, *site_mesh, warnings, notes);
    checkSkySun(config, sunny_radiance, warnings, notes);
    return warnings;
}

}  // namespace gusuku::bake_cli

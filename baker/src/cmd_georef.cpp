// gusuku-bake georef GCPS.csv: fits site.json's sfm_mesh transform (scale, rotation, translation into the site's
// ENU metres) from ground control points (gusuku_bake/ground_control.h, gusuku_bake/similarity_fit.h), prints each
// point's residual and the fields to paste, and with -o writes them. Exit codes follow commands.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/utm_grid.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku_bake/ground_control.h"
#include "gusuku_bake/similarity_fit.h"

namespace gusuku::bake_cli {

namespace {

// A worst residual above this refuses the fit: a few centimetres is a good survey against a good mesh; tens of
// centimetres mean a point was marked in the wrong place or a height is above sea level instead of the ellipsoid.
constexpr double kDefaultMaxResidualCm = 10.0;
// The largest GCP file read: thousands of points fit in a few hundred kilobytes.
constexpr uint64_t kMaxControlFileBytes = uint64_t(1) << 24;

CommandHelp georefHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake georef GCPS.csv (--site SITE.json | --origin LAT,LON,H) [options]";
    help.description =
        "Fits site.json's sfm_mesh scale, rotation_wxyz and translation_enu_m from ground control points: a CSV\n"
        "whose header is name,mesh_x,mesh_y,mesh_z,latitude_deg,longitude_deg,height_m (WGS84, heights above the\n"
        "ellipsoid) or name,mesh_x,mesh_y,mesh_z,easting_m,northing_m,height_m (UTM, with --utm-zone); lines\n"
        "starting with # are comments (docs/site-json.md, \"Georeferencing\"). At least 3 points, not on one line.\n"
        "Least squares by Horn's quaternion method; prints each point's residual in centimetres and the fields.";
    help.options = {
        {"--site", "", "SITE.json", "take the ENU origin from this site's latitude_deg, longitude_deg, height_m", ""},
        {"--origin", "", "LAT,LON,H", "or give the ENU origin: WGS84 degrees and metres above the ellipsoid", ""},
        {"--utm-zone", "", "ZONE", "the UTM zone of easting/northing columns, a number and N or S (52N)", ""},
        {"--max-residual-cm", "", "CM", "refuse the fit when a point's residual exceeds this, (0, 10000]",
         defaultNumber(kDefaultMaxResidualCm)},
        {"--output", "-o", "FILE", "also write the fields as a JSON object to FILE (atomically)", ""},
    };
    help.notes =
        "Refused (exit 1, nothing written): fewer than 3 points, points on one line, a mirrored mesh, a residual\n"
        "above --max-residual-cm. Exit status: 0 fitted, 1 bad input or refused fit, 2 bad usage.";
    return help;
}

struct GeorefRequest {
    std::string gcps_path, site_path, output_path;
    std::optional<GeodeticPoint> origin;
    std::optional<UtmZone> utm_zone;
    double max_residual_cm = kDefaultMaxResidualCm;
};

GeodeticPoint parseOrigin(CommandLine& line, const std::string& text) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
        parts.push_back(text.substr(start, comma - start));
    parts.push_back(text.substr(start));
    if (parts.size() != 3) line.failValue("--origin", quotedForMessage(text) + " is not LAT,LON,H (three numbers)");
    const SiteValueRange ranges[3] = {kSiteLatitudeRangeDeg, kSiteLongitudeRangeDeg, kSiteHeightRangeM};
    const char* names[3] = {"latitude", "longitude", "height"};
    double values[3];
    for (int k = 0; k < 3; ++k) {
        const std::optional<double> value = parseDecimal(parts[k]);
        if (!value || *value < ranges[k].minimum || *value > ranges[k].maximum)
            line.failValue("--origin", std::string(names[k]) + " " + quotedForMessage(parts[k]) + " is not a number in [" +
                                           defaultNumber(ranges[k].minimum) + ", " + defaultNumber(ranges[k].maximum) + "]");
        values[k] = *value;
    }
    return GeodeticPoint{values[0], values[1], values[2]};
}

void parseArguments(CommandLine& line, GeorefRequest& request) {
    request.site_path = line.text("--site").value_or("");
    const std::optional<std::string> origin = line.text("--origin");
    const std::optional<std::string> zone = line.text("--utm-zone");
    request.max_residual_cm = line.number("--max-residual-cm", 1e-6, 10000.0).value_or(kDefaultMaxResidualCm);
    request.output_path = line.text("--output", "-o").value_or("");
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() != 1) line.fail("needs one GCPS.csv (see --help)");
    request.gcps_path = positionals.front();
    if (request.site_path.empty() == !origin) line.fail("give exactly one of --site SITE.json and --origin LAT,LON,H");
    if (origin) request.origin = parseOrigin(line, *origin);
    if (zone) {
        request.utm_zone = parseUtmZone(*zone);
        if (!request.utm_zone)
            line.failValue("--utm-zone", quotedForMessage(*zone) + " is not a zone number 1-60 and N or S, e.g. 52N");
    }
}

std::string fieldsJson(const bake::SimilarityTransform& transform) {
    // Rounded to what matters (1e-9 of the quaternion, 0.1 mm; site.json normalises the quaternion on load) through
    // decimal text, so the JSON shows "0.707106781" rather than the binary neighbour of a scaled integer; + 0.0
    // turns -0 into 0.
    const auto rounded = [](double value, int decimals) {
        char text[48];
        std::snprintf(text, sizeof text, "%.*f", decimals, value);
        return std::stod(text) + 0.0;
    };
    char scale_text[32];  // ten significant digits: 1e-10 relative, far below any survey's accuracy
    std::snprintf(scale_text, sizeof scale_text, "%.10g", transform.scale);
    nlohmann::json rotation = nlohmann::json::array(), translation = nlohmann::json::array();
    for (const double component : transform.rotation_wxyz) rotation.push_back(rounded(component, 9));
    for (int axis = 0; axis < 3; ++axis) translation.push_back(rounded(transform.translation[axis], 4));
    // One field a line, as site.json's examples write them (nlohmann's indented dump puts each number on a line).
    return "{\n  \"scale\": " + nlohmann::json(std::stod(scale_text)).dump() + ",\n  \"rotation_wxyz\": " +
           rotation.dump() + ",\n  \"translation_enu_m\": " + translation.dump() + "\n}";
}

void printResiduals(const std::vector<bake::GroundControlPoint>& points, const bake::SimilarityFit& fit) {
    std::printf("%-16s %6s %12s %9s %9s %9s\n", "point", "line", "residual cm", "east cm", "north cm", "up cm");
    for (size_t k = 0; k < points.size(); ++k) {
        const glm::dvec3 error_m = fit.transform.apply(points[k].mesh) - points[k].enu_m;
        std::printf("%-16s %6d %12.2f %9.2f %9.2f %9.2f\n", points[k].name.c_str(), points[k].line,
                    fit.residuals_m[k] * 100.0, error_m.x * 100.0, error_m.y * 100.0, error_m.z * 100.0);
    }
    std::printf("RMS residual %.2f cm; worst %s, %.2f cm\n", fit.rms_residual_m * 100.0,
                points[fit.worst_point].name.c_str(), fit.residuals_m[fit.worst_point] * 100.0);
}

}  // namespace

int runGeorefCommand(const std::vector<std::string>& args) {
    GeorefRequest request;
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake georef", args, georefHelp(), false,
                                                             [&](CommandLine& line) { parseArguments(line, request); }))
        return *exit_code;
    const GeodeticPoint origin = request.origin ? *request.origin : loadSiteConfig(request.site_path).site.reference;
    const std::vector<bake::GroundControlPoint> points = bake::readGroundControlPoints(
        request.gcps_path, readWholeFile(request.gcps_path, kMaxControlFileBytes), origin, request.utm_zone);
    std::vector<glm::dvec3> mesh, enu;
    for (const bake::GroundControlPoint& point : points) {
        mesh.push_back(point.mesh);
        enu.push_back(point.enu_m);
    }
    bake::SimilarityFit fit;
    try {
        fit = bake::fitSimilarity(mesh, enu);
    } catch (const bake::DegeneratePoints& error) {
        throw InputError(request.gcps_path, "points", error.what());
    }
    std::printf("ENU origin %.8f, %.8f, %.3f m; %zu ground control points\n", origin.latitude_deg,
                origin.longitude_deg, origin.height_m, points.size());
    printResiduals(points, fit);
    const bake::GroundControlPoint& worst = points[fit.worst_point];
    if (fit.residuals_m[fit.worst_point] * 100.0 > request.max_residual_cm) {
        char problem[512];
        std::snprintf(problem, sizeof problem,
                      "the residual of %s (line %d) is %.2f cm, above --max-residual-cm %g: check that point's mesh "
                      "position and survey (a height above sea level instead of the ellipsoid?), or leave it out; "
                      "nothing written",
                      quotedForMessage(worst.name).c_str(), worst.line, fit.residuals_m[fit.worst_point] * 100.0,
                      request.max_residual_cm);
        throw InputError(request.gcps_path, "points", problem);
    }
    const std::string fields = fieldsJson(fit.transform) + "\n";
    std::printf("site.json's \"sfm_mesh\", beside its \"path\":\n%s", fields.c_str());
    if (!request.output_path.empty()) {
        writeBytesAtomically(request.output_path, fields.data(), fields.size());
        std::printf("written: %s\n", request.output_path.c_str());
    }
    return 0;
}

}  // namespace gusuku::bake_cli

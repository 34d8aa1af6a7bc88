// gusuku-bake preview SITE.json -o DIR: a look at the placement before a long bake (issue 42 item 3). Loads what
// the bake would (the building, the site mesh, the sunny sky, the slots' suns), runs check's placement checks
// (site_checks.h) and draws two pictures on the CPU in seconds: top.png, straight down with north up, the slots'
// sun directions in yellow and a north arrow; view.png, a visitor's eye 1.6 m above the ground, the sun at the
// back, under the sky photo as the bake places it. checks.txt holds the checks list that is also printed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cmd_preview_raster.h"
#include "commands.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "site_checks.h"

namespace gusuku::bake_cli {

namespace {

constexpr int kDefaultSize = 800;
constexpr int kMinSize = 64, kMaxSize = 4096;
// A visitor's eyes above the ground.
constexpr double kEyeHeightM = 1.6;
// The top view shows this many building radii around its centre, at least kMinTopHalfWidthM.
constexpr double kTopRadii = 3.0;
constexpr double kMinTopHalfWidthM = 10.0;
// The view's horizontal field of view.
constexpr double kViewFieldDeg = 60.0;

const glm::vec3 kBuildingTint{1.0f, 0.62f, 0.35f};  // warm, so the building stands out from the survey
const glm::vec3 kSiteMeshTint{0.9f, 0.9f, 0.9f};
const glm::vec3 kSunColour{1.0f, 0.85f, 0.0f};
const glm::vec3 kGridColour{0.25f, 0.3f, 0.25f};
const glm::vec3 kHeadingColour{0.2f, 0.9f, 1.0f};

CommandHelp previewHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake preview SITE_JSON -o DIR [options]";
    help.description =
        "A quick look before a long bake: loads what the bake would (building, site mesh, sunny sky, the slots'\n"
        "suns), runs check's placement checks (the building floating or sunk against the site mesh's ground, the\n"
        "site mesh's up, the sky's sun against the computed sun) and writes, in seconds on the CPU:\n"
        "  DIR/top.png    straight down, north up (the white arrow), the building orange with its model's -z\n"
        "                 (what heading_deg turns) in cyan, the sun's direction at each sunny slot in yellow, a 1 m\n"
        "                 grid at the ground's height\n"
        "  DIR/view.png   a visitor's eye 1.6 m above the ground with the first sunny slot's sun behind, under the\n"
        "                 sky photo placed with its north_azimuth_in_image_deg, each slot's sun a yellow cross\n"
        "                 where it is in view\n"
        "  DIR/checks.txt the checks list, also printed: each warning names the file, the field and what to change";
    help.options = {
        {"--output", "-o", "DIR", "the folder to write the pictures and checks.txt into (created if missing)", ""},
        {"--size", "", "N", "the pictures' width in pixels, " + std::to_string(kMinSize) + " to " +
                                std::to_string(kMaxSize) + " (view.png is 16:9)",
         std::to_string(kDefaultSize)},
    };
    help.notes = "Exit status: 0 written (warnings or not), 1 bad input, 2 bad usage.";
    return help;
}

struct PreviewScene {
    SiteConfig config;
    TriangleMesh building;
    std::optional<TriangleMesh> site_mesh;
    ImageRGBA sky;
    std::vector<std::pair<std::string, SunPosition>> suns;  ///< sunny slots
    std::vector<std::string> warnings, notes;
};

PreviewScene loadScene(const std::string& site_path) {
    PreviewScene scene;
    scene.config = loadSiteConfig(site_path);
    const SiteConfig& config = scene.config;
    GltfLoadOptions building_options;
    building_options.enu_from_model = config.building.enuFromModel(config.site.reference);
    scene.building = loadGltf(config.building.path, building_options, &scene.warnings);
    if (config.sfm_mesh) {
        GltfLoadOptions options;
        options.enu_from_model = config.sfm_mesh->enuFromModel();
        scene.site_mesh = loadSiteMesh(config.sfm_mesh->path, options, &scene.warnings);
    }
    scene.sky = readSkyRadiance(config.sunny_sky);
    for (const BakeSlot& slot : config.bake.slots)
        if (slot.sky == SlotSky::Sunny)
            scene.suns.push_back({slot.name, computeSunPosition(config.site.sunObserver(), slot.utc_seconds)});
    for (std::string& warning : placementWarnings(config, scene.building, scene.site_mesh ? &*scene.site_mesh : nullptr,
                                                  scene.sky, scene.notes))
        scene.warnings.push_back(std::move(warning));
    for (const auto& [name, sun] : scene.suns)
        if (!sun.above_horizon)
            scene.warnings.push_back(config.file + ": /bake/slots: slot \"" + name + "\": the sun is below the horizon "
                                     "then; move the slot's local_time into the day");
    return scene;
}

glm::dvec3 firstSun(const PreviewScene& scene) {
    for (const auto& [name, sun] : scene.suns)
        if (sun.above_horizon) return sun.direction_enu;
    return glm::normalize(glm::dvec3(0.3, -0.5, 0.8));  // no sunny slot: a light from the south-east, for shape
}

void drawGrid(PreviewCanvas& canvas, const PreviewCamera& camera, const glm::dvec3& centre, double half_width,
              double ground_up) {
    const double first_x = std::floor(centre.x - half_width), first_y = std::floor(centre.y - half_width);
    for (double s = 0.0; s <= 2.0 * half_width + 1.0; s += 1.0) {
        canvas.drawLine(camera, {first_x + s, first_y, ground_up}, {first_x + s, first_y + 2 * half_width + 1, ground_up},
                        kGridColour, 1);
        canvas.drawLine(camera, {first_x, first_y + s, ground_up}, {first_x + 2 * half_width + 1, first_y + s, ground_up},
                        kGridColour, 1);
    }
}

void writePng(const std::string& path, const PreviewCanvas& canvas) {
    const std::vector<uint8_t> bytes = canvas.rgba8();
    writeFileAtomicallyKeepingExtension(
        path, [&](const std::string& temporary) { writePngRgba8(temporary, canvas.width(), canvas.height(), bytes); });
}

int preview(const std::string& site_path, const std::string& output_dir, int size) {
    const PreviewScene scene = loadScene(site_path);
    const Bounds3 building_bounds = meshBounds(scene.building);
    if (building_bounds.empty())
        throw InputError(scene.config.building.path, "", "the building has no triangles to preview");
    const glm::dvec3 low(building_bounds.min), high(building_bounds.max);
    const glm::dvec3 centre = 0.5 * (low + high);
    const double radius = std::max(1.0, 0.5 * std::hypot(high.x - low.x, high.y - low.y));
    double ground_up = low.z;
    if (scene.site_mesh)
        if (const std::optional<BaseGap> gap = measureBaseGap(scene.building, *scene.site_mesh))
            ground_up = gap->ground_up_m;
    const glm::dvec3 sun = firstSun(scene);

    // Top: straight down, north up.
    const double half_width = std::max(kMinTopHalfWidthM, kTopRadii * radius);
    const PreviewCamera top_camera =
        PreviewCamera::topDown({centre.x, centre.y, high.z + 1000.0}, 0.5 * size / half_width);
    PreviewCanvas top(size, size, {0.08f, 0.08f, 0.1f});
    drawGrid(top, top_camera, centre, half_width, ground_up);
    if (scene.site_mesh) top.drawMesh(top_camera, *scene.site_mesh, kSiteMeshTint, sun);
    top.drawMesh(top_camera, scene.building, kBuildingTint, sun);
    for (const auto& [name, slot_sun] : scene.suns) {
        if (!slot_sun.above_horizon) continue;
        // From the building's centre towards the sun, longer the lower the sun (its shadows are longer).
        const glm::dvec3 horizontal = glm::normalize(glm::dvec3(slot_sun.direction_enu.x, slot_sun.direction_enu.y, 0));
        const double length = radius + (half_width - radius) * std::cos(slot_sun.apparent_elevation_deg * std::numbers::pi / 180);
        top.drawLine(top_camera, {centre.x, centre.y, high.z}, glm::dvec3(centre.x, centre.y, high.z) + length * horizontal,
                     kSunColour, 3);
    }
    // The model's north (-z), which heading_deg turns: for many models their back, so a glance tells a wrong one.
    const double heading_rad = scene.config.building.heading_deg * std::numbers::pi / 180.0;
    top.drawLine(top_camera, {centre.x, centre.y, high.z},
                 glm::dvec3(centre.x, centre.y, high.z) +
                     1.5 * radius * glm::dvec3(std::sin(heading_rad), std::cos(heading_rad), 0.0),
                 kHeadingColour, 3);
    // North arrow with an N, top left.
    const double arrow_x = 0.06 * size, arrow_top = 0.05 * size, arrow_bottom = 0.16 * size, head = 0.025 * size;
    const glm::vec3 white(1.0f);
    top.drawPixelLine(arrow_x, arrow_bottom, arrow_x, arrow_top, white, 3);
    top.drawPixelLine(arrow_x, arrow_top, arrow_x - head, arrow_top + head, white, 3);
    top.drawPixelLine(arrow_x, arrow_top, arrow_x + head, arrow_top + head, white, 3);
    const double n_left = arrow_x + 1.6 * head, n_right = n_left + 1.4 * head, n_top = arrow_top + 1.2 * head,
                 n_bottom = n_top + 2.0 * head;
    top.drawPixelLine(n_left, n_bottom, n_left, n_top, white, 2);
    top.drawPixelLine(n_left, n_top, n_right, n_bottom, white, 2);
    top.drawPixelLine(n_right, n_bottom, n_right, n_top, white, 2);

    // View: a visitor on the sunny side, looking at the building's middle.
    const int view_height = std::max(kMinSize * 9 / 16, size * 9 / 16);
    const double focal = 0.5 * size / std::tan(0.5 * kViewFieldDeg * std::numbers::pi / 180.0);
    glm::dvec3 away(sun.x, sun.y, 0.0);
    away = glm::length(away) > 1e-6 ? glm::normalize(away) : glm::dvec3(0, -1, 0);
    const double distance = std::max(3.0 * radius, radius + 0.6 * (high.z - ground_up) * focal / (0.5 * view_height));
    const glm::dvec3 eye = glm::dvec3(centre.x, centre.y, ground_up + kEyeHeightM) + distance * away;
    const PreviewCamera view_camera =
        PreviewCamera::lookingAt(eye, {centre.x, centre.y, 0.5 * (std::max(ground_up, low.z) + high.z)}, focal);
    PreviewCanvas view(size, view_height, {0.5f, 0.6f, 0.7f});
    drawGrid(view, view_camera, centre, std::max(kMinTopHalfWidthM, distance + radius), ground_up);
    if (scene.site_mesh) view.drawMesh(view_camera, *scene.site_mesh, kSiteMeshTint, sun);
    view.drawMesh(view_camera, scene.building, kBuildingTint, sun);
    view.drawSky(view_camera, scene.sky, scene.config.sunny_sky.north_azimuth_in_image_deg);
    // Each sunny slot's sun where it stands in this view (a cross; off the picture when behind the visitor).
    for (const auto& [name, slot_sun] : scene.suns) {
        if (!slot_sun.above_horizon) continue;
        constexpr double kMarkerDistanceM = 100.0, kMarkerArmM = 1.5;
        const glm::dvec3 at = eye + kMarkerDistanceM * slot_sun.direction_enu;
        view.drawLine(view_camera, at - kMarkerArmM * view_camera.right, at + kMarkerArmM * view_camera.right,
                      kSunColour, 3);
        view.drawLine(view_camera, at - kMarkerArmM * view_camera.up, at + kMarkerArmM * view_camera.up, kSunColour,
                      3);
    }

    std::string checks = "placement:\n";
    for (const std::string& note : scene.notes) checks += "  " + note + "\n";
    for (const auto& [name, slot_sun] : scene.suns) {
        char line[160];
        std::snprintf(line, sizeof line, "  slot %s: sun at azimuth %.1f deg, elevation %.1f deg\n", name.c_str(),
                      slot_sun.azimuth_deg, slot_sun.apparent_elevation_deg);
        checks += line;
    }
    checks += "warnings: " + std::to_string(scene.warnings.size()) + "\n";
    for (const std::string& warning : scene.warnings) checks += "  " + warning + "\n";

    namespace fs = std::filesystem;
    const fs::path folder(output_dir);
    std::error_code error;
    if (fs::exists(folder, error) && !fs::is_directory(folder, error))
        throw InputError(output_dir, "", "exists and is not a folder");
    writePng((folder / "top.png").string(), top);
    writePng((folder / "view.png").string(), view);
    writeBytesAtomically((folder / "checks.txt").string(), checks.data(), checks.size());
    std::fputs(checks.c_str(), stdout);
    std::printf("wrote %s, %s and %s\n", (folder / "top.png").string().c_str(), (folder / "view.png").string().c_str(),
                (folder / "checks.txt").string().c_str());
    return 0;
}

}  // namespace

int runPreviewCommand(const std::vector<std::string>& args) {
    std::string site_path, output_dir;
    int size = kDefaultSize;
    const auto parse = [&](CommandLine& line) {
        const std::optional<std::string> output = line.text("--output", "-o");
        if (const std::optional<int64_t> given = line.integer("--size", kMinSize, kMaxSize)) size = int(*given);
        const std::vector<std::string> sites = line.positionals();
        line.finish();
        if (sites.size() != 1) line.fail(sites.empty() ? "missing SITE_JSON (see --help)" : "expected one SITE_JSON");
        if (!output) line.fail("missing -o DIR, the folder for the pictures (see --help)");
        site_path = sites.front();
        output_dir = *output;
    };
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake preview", args, previewHelp(), true, parse))
        return *exit_code;
    // Bad input throws InputError, which main() prints as "gusuku-bake: error: FILE: FIELD: PROBLEM" (exit 1).
    return preview(site_path, output_dir, size);
}

}  // namespace gusuku::bake_cli

// gusuku-bake check site.json: validates the site file and loads everything it names (meshes, skies), so a
// bad input is found in seconds rather than an hour into a bake. Prints what a bake would use.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bake_geometry.h"
#include "bake_preflight.h"
#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/mesh.h"
#include "gusuku/assets/site.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/slot_lighting.h"
#include "site_checks.h"

namespace gusuku::bake_cli {

namespace {

CommandHelp checkHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake check SITE_JSON";
    help.description =
        "Validates SITE_JSON (format: docs/site-json.md), loads the building and SfM meshes and the sky maps it\n"
        "names, and prints a summary: the site, the slots with their site-clock and UTC times, triangle counts,\n"
        "ENU bounds, sky sizes and warnings. The placement checks warn, naming the field and the value to set,\n"
        "when the building floats or is sunk against the site mesh's ground, when the site mesh's up is not up,\n"
        "and when the sky's sun is off the computed sun (gusuku-bake preview draws the placement).\n"
        "Exit 0 when everything loads, 1 on bad input, 2 on bad usage.";
    return help;
}

std::string formatUtcOffset(int minutes) {
    char text[16];
    const int magnitude = std::abs(minutes);
    std::snprintf(text, sizeof(text), "%c%02d:%02d", minutes < 0 ? '-' : '+', magnitude / 60, magnitude % 60);
    return text;
}

std::string formatVec3(const glm::dvec3& v) {
    char text[96];
    std::snprintf(text, sizeof(text), "(%.3f, %.3f, %.3f)", v.x, v.y, v.z);
    return text;
}

std::string formatBounds(const Bounds3& bounds) {
    if (bounds.empty()) return "empty";
    return formatVec3(glm::dvec3(bounds.min)) + " .. " + formatVec3(glm::dvec3(bounds.max));
}

bool overlapHorizontally(const Bounds3& a, const Bounds3& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

void printMesh(const char* label, const std::string& path, const TriangleMesh& mesh) {
    std::printf("%s: %s\n", label, path.c_str());
    std::printf("  %zu triangles, %zu vertices, %zu materials, %zu textures%s\n", mesh.triangleCount(),
                mesh.vertexCount(), mesh.materials.size(), mesh.textures.size(),
                mesh.has_uv1 ? ", lightmap UVs (TEXCOORD_1)" : "");
    std::printf("  ENU bounds (m): %s\n", formatBounds(meshBounds(mesh)).c_str());
}

/// Clipped texels beyond this fraction of a photo sky are more than a sun's glare (checkSky's warning).
constexpr double kClippedSkyWarningFraction = 0.005;

ImageRGBA checkSky(const char* label, const SkyConfig& sky, std::vector<std::string>& warnings) {
    SkyPhotoSummary photos;
    ImageRGBA image = readSkyRadiance(sky, &photos);
    std::printf("%s sky: %s\n  %d x %d, north at %.2f deg in the image\n", label, sky.path.c_str(), image.width,
                image.height, sky.north_azimuth_in_image_deg);
    if (!photos.ev100.empty()) {
        std::printf("  8-bit photo%s at EV100", photos.ev100.size() > 1 ? "s (an exposure bracket)" : "");
        for (const double ev100 : photos.ev100) std::printf(" %.2f", ev100);
        std::printf("; %zu of %zu texels clipped in every photo (%.3f %%)\n", photos.clipped_texel_count,
                    photos.texel_count, 100.0 * double(photos.clipped_texel_count) / double(photos.texel_count));
        // A clipped sun covers some 1e-5 of an equirect map; beyond 0.5 % the clipped sky itself is lost light
        // (held only as the clip's lower bound), which also biases the clear-sky sun calibrated on it.
        if (double(photos.clipped_texel_count) > kClippedSkyWarningFraction * double(photos.texel_count))
            warnings.push_back(std::string(label) + " sky: " + std::to_string(photos.clipped_texel_count) +
                               " texels clipped in every photo, more than a sun's glare: its light there is a lower "
                               "bound; a darker exposure (or a bracket) would hold it");
    }
    if (image.width != 2 * image.height)
        warnings.push_back(std::string(label) + " sky is " + std::to_string(image.width) + " x " +
                           std::to_string(image.height) + ", not the 2:1 of an equirectangular map");
    return image;
}

int checkSite(const std::string& site_path) {
    const SiteConfig config = loadSiteConfig(site_path);
    std::vector<std::string> warnings;

    const SiteLocation& site = config.site;
    std::printf("site: %s\n", site.name.c_str());
    std::printf("  reference: latitude %.7f deg, longitude %.7f deg, height %.2f m (WGS84)\n",
                site.reference.latitude_deg, site.reference.longitude_deg, site.reference.height_m);
    std::printf("  clock: UTC%s\n", formatUtcOffset(site.utc_offset_minutes).c_str());
    if (site.pressure_mbar < 0.0)
        std::printf("  atmosphere: standard pressure at the site's height, %.1f C\n", site.temperature_c);
    else
        std::printf("  atmosphere: %.1f mbar, %.1f C\n", site.pressure_mbar, site.temperature_c);

    const BakeSettings& bake = config.bake;
    std::printf("bake: %s, %.3g texels/m, %d samples/texel, %d bounces, seed %u, ground cell %.3g m\n",
                bake.date.c_str(), bake.texels_per_metre, bake.samples_per_texel, bake.max_bounces, bake.seed,
                bake.ground_cell_m);
    std::printf("slots:\n");
    for (const BakeSlot& slot : bake.slots) {
        if (slot.sky == SlotSky::Sunny)
            std::printf("  %-16s sunny     %s  UTC %s\n", slot.name.c_str(),
                        formatIso8601(slot.utc_seconds, site.utc_offset_minutes).c_str(),
                        formatIso8601(slot.utc_seconds, 0).c_str());
        else
            std::printf("  %-16s overcast  (no sun)\n", slot.name.c_str());
    }
    if (!config.overcast_sky) warnings.push_back("no overcast sky: no overcast slot can be baked");

    const BuildingConfig& building = config.building;
    const glm::dmat4 building_transform = building.enuFromModel(site.reference);
    GltfLoadOptions building_options;
    building_options.enu_from_model = building_transform;
    const TriangleMesh building_mesh = loadGltf(building.path, building_options, &warnings);
    printMesh("building", building.path, building_mesh);
    const glm::dvec3 building_origin(building_transform[3]);
    std::printf("  origin at ENU %s m, heading %.2f deg, scale %g\n", formatVec3(building_origin).c_str(),
                building.heading_deg, building.scale);
    if (building_mesh.triangleCount() == 0) warnings.push_back("the building has no triangles");
    if (std::hypot(building_origin.x, building_origin.y) > 1000.0)
        warnings.push_back("the building stands more than 1 km from the site reference; check its position");

    std::optional<TriangleMesh> loaded_sfm_mesh;
    if (config.sfm_mesh) {
        GltfLoadOptions sfm_options;
        sfm_options.enu_from_model = config.sfm_mesh->enuFromModel();
        const TriangleMesh& sfm_mesh =
            loaded_sfm_mesh.emplace(loadSiteMesh(config.sfm_mesh->path, sfm_options, &warnings));
        printMesh("sfm mesh", config.sfm_mesh->path, sfm_mesh);
        if (sfm_mesh.triangleCount() == 0) warnings.push_back("the SfM mesh has no triangles");
        else if (!overlapHorizontally(meshBounds(sfm_mesh), meshBounds(building_mesh)))
            warnings.push_back("the building does not overlap the SfM mesh seen from above; check both placements");
    } else {
        std::printf("sfm mesh: none\n");
        warnings.push_back("no sfm_mesh: nothing around the building to bounce light or to receive its shadow");
    }

    const ImageRGBA sunny_radiance = checkSky("sunny", config.sunny_sky, warnings);
    if (config.overcast_sky) checkSky("overcast", *config.overcast_sky, warnings);
    // Placement: the building on the ground, the mesh's up, the sky's sun (site_checks.h); preview draws them.
    std::vector<std::string> placement_notes;
    for (std::string& warning : placementWarnings(config, building_mesh, loaded_sfm_mesh ? &*loaded_sfm_mesh : nullptr,
                                                  sunny_radiance, placement_notes))
        warnings.push_back(std::move(warning));
    std::printf("placement:\n");
    for (const std::string& note : placement_notes) std::printf("  %s\n", note.c_str());

    // What the bake itself would refuse or warn about before tracing, by the bake's own preflight code.
    const std::vector<bake::SlotSun> suns = bake::slotSunPositions(config);
    for (const std::string& message : bake::sunsBelowHorizon(suns)) warnings.push_back(message);
    // The device's buffer limit first: the geometry refuses a texel density past it before charting.
    uint64_t device_limit = uint64_t(1) << 27;  // Vulkan's guaranteed minimum of maxStorageBufferRange
    std::string device = "no Vulkan device; Vulkan's guaranteed minimum";
    try {
        VulkanContext context(vulkanOptionsFromEnvironment());
        device_limit = context.properties().limits.maxStorageBufferRange;
        device = context.deviceDescription();
    } catch (const std::exception&) {
    }
    device_limit = bake::storageBufferLimitBytes(device_limit);
    // The bake's own tracing side for both: the check reads the geometry, not the runtime's texture detail.
    const int trace_texture_size = bake::BakeOptions{}.max_texture_size;
    bake::BakeGeometry geometry = bake::prepareBakeGeometry(config, bake::lowestSunElevationDeg(suns),
                                                            trace_texture_size, trace_texture_size, device_limit);
    bake::refuseBuildingWithoutTexels(config, geometry);
    std::printf("lightmap: %zu texels at %d^2; ground grid: %d x %d cells of %.3g m\n", geometry.texels.size(),
                geometry.lightmap_resolution, geometry.ground_region.columns, geometry.ground_region.rows,
                geometry.ground_region.cell_m);
    if (const std::string reason = bake::emptyGroundReason(config, geometry); !reason.empty())
        warnings.push_back(reason);
    const bake::PreparedSky sunny = bake::prepareSky(config.sunny_sky);
    std::optional<bake::PreparedSky> overcast;
    if (config.overcast_sky) overcast = bake::prepareSky(*config.overcast_sky);
    std::vector<std::pair<std::string, const bake::SkySamplingTables*>> skies = {{"/skies/sunny/path", &sunny.tables}};
    if (overcast) skies.push_back({"/skies/overcast/path", &overcast->tables});
    std::printf("device: %s, storage buffers up to %.1f MiB\n", device.c_str(), double(device_limit) / (1 << 20));
    const std::vector<InputError> too_large =
        bake::deviceLimitProblems(config, bake::bakeDeviceBuffers(config, geometry, skies, 512), device_limit);
    if (!too_large.empty()) throw too_large.front();

    std::printf("warnings: %zu\n", warnings.size());
    for (const std::string& warning : warnings) std::printf("  %s\n", warning.c_str());
    return 0;
}

}  // namespace

int runCheckCommand(const std::vector<std::string>& args) {
    std::string site_path;
    const auto parse = [&](CommandLine& line) {
        const std::vector<std::string> sites = line.positionals();
        line.finish();
        if (sites.size() > 1) line.fail("expected one site.json, got more (see --help)");
        if (sites.empty()) line.fail("missing SITE_JSON (see --help)");
        site_path = sites.front();
    };
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake check", args, checkHelp(), false, parse))
        return *exit_code;
    // Bad input throws InputError, which main() prints as "gusuku-bake: error: FILE: FIELD: PROBLEM" (a whole-file
    // problem without the field; InputError::what()), exit 1.
    return checkSite(site_path);
}

}  // namespace gusuku::bake_cli

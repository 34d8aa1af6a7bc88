#include "bake_preflight.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "gusuku/maths/time_utc.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

namespace {

std::string mebibytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1u << 20));
    return text;
}

std::string metres(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g m", value);
    return text;
}

}  // namespace

std::vector<SlotSun> slotSunPositions(const SiteConfig& site) {
    const SunObserver observer = site.site.sunObserver();
    std::vector<SlotSun> suns;
    for (const BakeSlot& slot : site.bake.slots) {
        if (slot.sky != SlotSky::Sunny) continue;
        try {
            suns.push_back({slot.name, computeSunPosition(observer, slot.utc_seconds)});
        } catch (const std::invalid_argument& error) {
            throw InputError(site.file, "/bake/date", "\"" + site.bake.date + "\" cannot be used for slot " +
                                                          slot.name + ": " + error.what());
        }
    }
    return suns;
}

double lowestSunElevationDeg(const std::vector<SlotSun>& suns) {
    double lowest = -1.0;
    for (const SlotSun& sun : suns)
        if (sun.position.above_horizon)
            lowest = lowest < 0.0 ? sun.position.apparent_elevation_deg
                                  : std::min(lowest, sun.position.apparent_elevation_deg);
    return lowest;
}

std::vector<std::string> sunsBelowHorizon(const std::vector<SlotSun>& suns) {
    std::vector<std::string> messages;
    for (const SlotSun& sun : suns) {
        if (sun.position.above_horizon) continue;
        char text[64];
        std::snprintf(text, sizeof text, "%.2f", sun.position.apparent_elevation_deg);
        messages.push_back("slot " + sun.slot + ": the sun is below the horizon (apparent elevation " + text +
                           " deg); it bakes with sky light only");
    }
    return messages;
}

void refuseBuildingWithoutTexels(const SiteConfig& site, const BakeGeometry& geometry) {
    if (!geometry.texels.empty()) return;
    const size_t triangles = geometry.scene.building_triangle_count;
    throw InputError(site.file, "/building/path",
                     site.building.path + " has no surface to bake: " +
                         (triangles == 0 ? std::string("it has no triangles")
                                         : "none of its " + std::to_string(triangles) +
                                               " triangles covers a lightmap texel (all degenerate: zero area, "
                                               "non-finite, or placed so far from the site reference that float "
                                               "precision collapses them)"));
}

std::string emptyGroundReason(const SiteConfig& site, const BakeGeometry& geometry) {
    for (const GroundCell& cell : geometry.ground_cells)
        if (cell.valid) return "";
    const GroundRegion& region = geometry.ground_region;
    const std::string grid = "no cell centre of the " + std::to_string(region.columns) + " x " +
                             std::to_string(region.rows) + " ground grid (cell " + metres(region.cell_m) +
                             ", ENU x " + metres(region.origin_enu_m.x) + " .. " +
                             metres(region.origin_enu_m.x + region.columns * region.cell_m) + ", y " +
                             metres(region.origin_enu_m.y) + " .. " +
                             metres(region.origin_enu_m.y + region.rows * region.cell_m) + ")";
    std::string cause;
    if (!site.sfm_mesh) cause = "lies over the flat stand-in ground";
    else if (geometry.scene.mesh.triangleCount() == geometry.scene.building_triangle_count)
        cause = "can lie over the SfM mesh: it has no triangles that can be traced";
    else
        cause = "lies over the SfM mesh (check sfm_mesh's placement against the building's, and that "
                "bake.ground_cell_m is smaller than the site)";
    return grid + " " + cause + "; the ground terms will be empty";
}

uint64_t storageBufferLimitBytes(uint64_t device_max_storage_buffer_range) {
    uint64_t limit = device_max_storage_buffer_range;
    if (const char* text = std::getenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES")) {
        char* end = nullptr;
        const unsigned long long value = std::strtoull(text, &end, 10);
        if (end != text && *end == '\0' && value > 0) limit = std::min<uint64_t>(limit, value);
    }
    return limit;
}

std::vector<DeviceBuffer> bakeDeviceBuffers(const SiteConfig& site, const BakeGeometry& geometry,
                                            const std::vector<std::pair<std::string, const SkySamplingTables*>>& skies,
                                            int max_texture_size) {
    std::vector<DeviceBuffer> buffers;
    // The scene's buffers grow with the larger of the two meshes; name the field of the one that dominates.
    const size_t building_triangles = geometry.scene.building_triangle_count;
    const size_t site_triangles = geometry.scene.mesh.triangleCount() - building_triangles;
    const std::string scene_field = site.sfm_mesh && site_triangles > building_triangles ? "/sfm_mesh/path"
                                                                                         : "/building/path";
    const std::string triangles = std::to_string(geometry.scene.mesh.triangleCount()) + " triangles";
    const Bvh& bvh = geometry.cpuBvh();  // built over the same mesh and flags as the tracer's
    buffers.push_back({scene_field, "BVH nodes (" + triangles + ")", bvh.nodes.size() * sizeof(BvhNodeGpu)});
    buffers.push_back({scene_field, "BVH triangles (" + triangles + ")",
                       bvh.triangles.size() * sizeof(BvhTriangleGpu)});
    buffers.push_back({scene_field, "triangle shading (" + triangles + ")",
                       geometry.scene.mesh.triangleCount() * sizeof(TriangleShadingGpu)});
    uint64_t texture_bytes = 0;
    for (const ImageRGBA& texture : geometry.scene.mesh.textures) {  // an upper bound of the downsampled sizes
        const int width = std::min(texture.width, max_texture_size);
        const int height = std::min(texture.height, max_texture_size);
        texture_bytes += uint64_t(width) * uint64_t(height) * 4;
    }
    buffers.push_back({scene_field, "albedo textures (" + std::to_string(geometry.scene.mesh.textures.size()) +
                                        " textures, each at most " + std::to_string(max_texture_size) + "^2)",
                       texture_bytes});
    for (const auto& [field, tables] : skies) {
        const std::string size = std::to_string(tables->width) + " x " + std::to_string(tables->height);
        buffers.push_back({field, "sky radiance (" + size + ")", tables->radiance_rgba.size() * sizeof(float)});
        buffers.push_back({field, "sky sampling tables (" + size + ")", tables->table.size() * sizeof(float)});
    }
    const std::string texels = std::to_string(geometry.texels.size()) + " lightmap texels at " +
                               std::to_string(geometry.lightmap_resolution) + "^2";
    buffers.push_back({"/bake/texels_per_metre", "building query points (" + texels + ")",
                       geometry.texels.size() * sizeof(QueryPointGpu)});
    const std::string cells = std::to_string(geometry.ground_cells.size()) + " ground cells";
    buffers.push_back({"/bake/ground_cell_m", "ground query points (" + cells + ")",
                       geometry.ground_cells.size() * sizeof(QueryPointGpu)});
    return buffers;
}

std::vector<InputError> deviceLimitProblems(const SiteConfig& site, const std::vector<DeviceBuffer>& buffers,
                                            uint64_t limit_bytes) {
    std::vector<InputError> problems;
    for (const DeviceBuffer& buffer : buffers) {
        if (buffer.bytes <= limit_bytes) continue;
        std::string advice;
        if (buffer.field == "/bake/texels_per_metre")
            advice = "lower bake.texels_per_metre (the texel count grows with its square)";
        else if (buffer.field == "/bake/ground_cell_m")
            advice = "raise bake.ground_cell_m";
        else if (buffer.field.rfind("/skies/", 0) == 0)
            advice = "downsample the sky map";
        else
            advice = "simplify the mesh or lower its texture count";
        problems.emplace_back(site.file, buffer.field,
                              buffer.what + " need " + mebibytes(buffer.bytes) +
                                  " in one storage buffer, over the device's maxStorageBufferRange of " +
                                  mebibytes(limit_bytes) + "; " + advice);
    }
    return problems;
}

}  // namespace gusuku::bake

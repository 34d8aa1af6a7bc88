// The closed-form bake set of synthetic_bakeset.h.

#include "gusuku/synthetic/synthetic_bakeset.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku::testing {
namespace {

constexpr double kLatitude = 26.2856, kLongitude = 127.8008, kHeight = 160.0;
constexpr int kUtcOffsetMinutes = 540;

BakeSetImage constantImage(int width, int height, float value, float alpha) {
    BakeSetImage image;
    image.width = width;
    image.height = height;
    image.rgba.assign(size_t(width) * height * 4, value);
    for (size_t texel = 0; texel < size_t(width) * height; ++texel) image.rgba[texel * 4 + 3] = alpha;
    return image;
}

}  // namespace

double syntheticGroundHeight(const SyntheticBakeSetOptions& options, double y) {
    return y < options.step_north_m ? -options.step_height_m : 0.0;
}

bool mayShowTheBoxOrItsShadow(const glm::dvec3& camera_enu, const glm::dvec3& ray_enu, const glm::dvec3& sun_enu,
                              double box_margin_m) {
    constexpr double kStepM = 0.05, kShadowSearchM = 20.0, kRaySearchM = 40.0;
    constexpr double kBoxHalfM = 1.0, kBoxHeightM = 3.0, kShadowMarginM = 0.5;
    if (ray_enu.z < 0.0) {
        const glm::dvec3 ground = camera_enu + ray_enu * (-camera_enu.z / ray_enu.z);
        for (double t = 0.0; t < kShadowSearchM; t += kStepM) {
            const glm::dvec3 p = ground + sun_enu * t;
            if (std::abs(p.x) < kBoxHalfM + kShadowMarginM && std::abs(p.y) < kBoxHalfM + kShadowMarginM &&
                p.z < kBoxHeightM + kShadowMarginM)
                return true;
        }
    }
    const glm::dvec3 direction = glm::normalize(ray_enu);
    for (double t = 0.0; t < kRaySearchM; t += kStepM) {
        const glm::dvec3 p = camera_enu + direction * t;
        if (std::abs(p.x) < kBoxHalfM + box_margin_m && std::abs(p.y) < kBoxHalfM + box_margin_m &&
            p.z > -box_margin_m && p.z < kBoxHeightM + box_margin_m)
            return true;
    }
    return false;
}

double syntheticLocalTime(int hours, int minutes) {
    return parseDateAtOffset("2026-06-21", kUtcOffsetMinutes) + hours * 3600.0 + minutes * 60.0;
}

BakeSetData makeSyntheticBakeSet(const SyntheticBakeSetOptions& options) {
    BakeSetData data;
    BakeSetManifest& manifest = data.manifest;
    manifest.site = {"synthetic", kLatitude, kLongitude, kHeight, kUtcOffsetMinutes};
    manifest.settings = {16, 2, 1, true};
    manifest.building.lightmap_resolution = options.lightmap_resolution;
    manifest.building.texels_per_metre = 4.0;
    manifest.building.texels = uint64_t(options.lightmap_resolution) * options.lightmap_resolution;
    manifest.building.lightmap_uv_source = "synthetic";

    // The box: six faces, each a quad in its own sixth of the lightmap (a 3 x 2 layout).
    const float h = float(options.building_height_m);
    const glm::vec3 corners[8] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
                                  {-1, -1, h}, {1, -1, h}, {1, 1, h}, {-1, 1, h}};
    struct Face {
        int corner[4];  // counter-clockwise seen from outside
        glm::vec3 normal;
    };
    const Face faces[6] = {
        {{0, 1, 5, 4}, {0, -1, 0}},  // south
        {{1, 2, 6, 5}, {1, 0, 0}},   // east
        {{2, 3, 7, 6}, {0, 1, 0}},   // north
        {{3, 0, 4, 7}, {-1, 0, 0}},  // west
        {{4, 5, 6, 7}, {0, 0, 1}},   // roof
        {{3, 2, 1, 0}, {0, 0, -1}},  // floor
    };
    BakeSetMesh& mesh = data.building;
    for (int face = 0; face < 6; ++face) {
        const glm::vec2 cell_origin(float(face % 3) / 3.0f, float(face / 3) / 2.0f);
        const glm::vec2 cell_size(1.0f / 3.0f, 0.5f);
        const glm::vec2 quad_uv[4] = {{0.15f, 0.15f}, {0.85f, 0.15f}, {0.85f, 0.85f}, {0.15f, 0.85f}};
        const uint32_t first = uint32_t(mesh.positions.size());
        for (int corner = 0; corner < 4; ++corner) {
            mesh.positions.push_back(corners[faces[face].corner[corner]]);
            mesh.normals.push_back(faces[face].normal);
            mesh.uv0.push_back(quad_uv[corner]);
            mesh.uv1.push_back(cell_origin + quad_uv[corner] * cell_size);
        }
        for (uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + index);
        mesh.triangle_material.push_back(0);
        mesh.triangle_material.push_back(0);
    }
    mesh.materials.push_back({glm::vec4(options.albedo, options.albedo, options.albedo, 1.0f), -1});

    if (options.ground_occluder) {
        const float half = float(options.grid_half_m) * 2.0f;
        const float step_y = float(options.step_north_m), low = -float(options.step_height_m);
        // Upper level north of the step, the riser, the lower level south of it.
        data.occluder.positions = {{-half, step_y, 0}, {half, step_y, 0}, {half, half, 0},   {-half, half, 0},
                                   {-half, -half, low}, {half, -half, low}, {half, step_y, low}, {-half, step_y, low}};
        data.occluder.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 7, 6, 1, 7, 1, 0};
    }

    const int cells = int(std::lround(2.0 * options.grid_half_m / options.cell_m));
    GroundGrid& grid = manifest.ground_grid.grid;
    grid.origin_enu_m = glm::dvec2(-options.grid_half_m);
    grid.cell_m = options.cell_m;
    grid.columns = cells;
    grid.rows = cells;
    manifest.ground_grid.ground_source = "synthetic flat plane";
    data.ground_geometry = constantImage(cells, cells, 0.0f, 0.0f);
    for (int row = 0; row < cells; ++row)
        for (int column = 0; column < cells; ++column) {
            const size_t texel = size_t(row) * cells + column;
            const double y = grid.origin_enu_m.y + (cells - row - 0.5) * grid.cell_m;
            data.ground_geometry.rgba[texel * 4 + 2] = 1.0f;
            data.ground_geometry.rgba[texel * 4 + 3] = float(syntheticGroundHeight(options, y));
        }
    if (options.ground_albedo > 0.0f) {
        manifest.ground_grid.albedo = "ground_albedo.exr";
        data.ground_albedo = constantImage(cells, cells, options.ground_albedo, 1.0f);
    }

    SunObserver observer;
    observer.latitude_deg = kLatitude;
    observer.longitude_deg = kLongitude;
    observer.height_m = kHeight;
    const int hours[3] = {9, 12, 15};
    for (int slot_index = 0; slot_index < 4; ++slot_index) {
        BakeSetSlot slot;
        if (slot_index < 3) {
            const double utc = syntheticLocalTime(hours[slot_index], 0);
            const SunPosition sun = computeSunPosition(observer, utc);
            slot.name = "sunny_" + std::string(hours[slot_index] < 10 ? "0" : "") + std::to_string(hours[slot_index]) +
                        "00";
            slot.sky = BakeSetSky::Sunny;
            slot.local_time = formatIso8601(utc, kUtcOffsetMinutes);
            slot.utc = formatIso8601(utc, 0);
            slot.sun.present = true;
            slot.sun.irradiance_source = "synthetic";
            slot.sun.position = BakeSetSunPosition{sun.azimuth_deg, sun.apparent_elevation_deg, sun.direction_enu};
            slot.sun.irradiance_rgb = glm::dvec3(options.sun_irradiance);
            slot.sun.angular_radius_deg = 0.2675;
        } else {
            slot.name = "overcast";
            slot.sky = BakeSetSky::Overcast;
            slot.sun.irradiance_source = "none: overcast";
        }
        slot.sky_map = "synthetic";
        slot.sky_sampling_method = "cosine";
        slot.building_irradiance = "building_" + slot.name + ".exr";
        slot.ground_irradiance_with_building = "ground_" + slot.name + "_with.exr";
        slot.ground_irradiance_without_building = "ground_" + slot.name + "_without.exr";
        BakeSetColourStatistics statistics;
        statistics.lab_mean = glm::dvec3(50.0, 0.0, 0.0);
        statistics.lab_sigma = glm::dvec3(10.0, 2.0, 2.0);
        statistics.texels = manifest.building.texels;
        slot.colour_statistics = statistics;
        manifest.slots.push_back(slot);

        BakeSetSlotImages images;
        images.building = constantImage(options.lightmap_resolution, options.lightmap_resolution,
                                        options.indirect_irradiance, 1.0f);
        images.ground_with = constantImage(cells, cells, options.ground_irradiance, 1.0f);
        images.ground_without = constantImage(cells, cells, options.ground_irradiance, 1.0f);
        data.slots.push_back(std::move(images));
    }
    return data;
}

}  // namespace gusuku::testing

// The C API's bake set desc (gusuku.h's gusuku_bakeset_desc) into the runtime's BakeSetData: every array and
// field checked in the order the desc declares them, the first problem named as "desc.FIELD: PROBLEM".
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "gusuku_c_api_detail.h"

namespace gusuku::c_api_detail {
namespace {

/// A missing pointer where an array of `count` elements is required: "FIELD: NULL with COUNT_NAME N".
bool missingArray(const void* pointer, uint64_t count) { return pointer == nullptr && count > 0; }


DescProblem argumentProblem(std::string message) { return {GUSUKU_ERROR_INVALID_ARGUMENT, std::move(message)}; }
DescProblem bakeSetProblem(std::string message) { return {GUSUKU_ERROR_INVALID_BAKE_SET, std::move(message)}; }

/// Larger sides than any device's image limit, refused before a byte count could overflow.
constexpr int32_t kMaxImageSide = 65536;
/// A site's height above the ellipsoid is refused beyond 100 km either way: no site on the ground lies there,
/// so such a value is a caller's mistake (another unit, an uninitialised field).
constexpr double kMaxSiteHeightM = 1e5;

DescProblem tooLarge(const std::string& field, int32_t width, int32_t height) {
    return bakeSetProblem(field + ": " + std::to_string(width) + " x " + std::to_string(height) +
                          " texels, at most " + std::to_string(kMaxImageSide) + " per side");
}

/// Copies a float RGBA image, unless it is too large or its pointer is missing.
DescProblem copyImage(const gusuku_image& source, const std::string& field, gusuku::BakeSetImage& image) {
    if (source.width > kMaxImageSide || source.height > kMaxImageSide)
        return tooLarge(field, source.width, source.height);
    image.width = source.width;
    image.height = source.height;
    const uint64_t floats = (source.width > 0 && source.height > 0) ? uint64_t(source.width) * source.height * 4 : 0;
    if (missingArray(source.rgba, floats))
        return argumentProblem(field + ".rgba: NULL for a " + std::to_string(source.width) + " x " +
                               std::to_string(source.height) + " image");
    image.rgba.assign(source.rgba, source.rgba + floats);
    return {};
}

template <typename Vector>
std::vector<Vector> copyVectors(const float* values, uint32_t count) {
    std::vector<Vector> vectors(count);
    for (uint32_t i = 0; i < count; ++i)
        for (int c = 0; c < Vector::length(); ++c) vectors[i][c] = values[size_t(i) * Vector::length() + size_t(c)];
    return vectors;
}

/// The first array the desc names a count for but gives no pointer to.
DescProblem checkDescArrays(const gusuku_bakeset_desc& desc) {
    struct Array {
        const void* pointer;
        uint64_t count;      // elements the pointer must hold
        const char* name;    // "FIELD: NULL with COUNT_NAME "
        uint64_t reported;   // the count the app gave
    };
    const Array arrays[] = {
        {desc.positions, desc.vertex_count, "desc.positions: NULL with vertex_count ", desc.vertex_count},
        {desc.normals, desc.vertex_count, "desc.normals: NULL with vertex_count ", desc.vertex_count},
        {desc.uv0, desc.vertex_count, "desc.uv0: NULL with vertex_count ", desc.vertex_count},
        {desc.uv1, desc.vertex_count, "desc.uv1: NULL with vertex_count ", desc.vertex_count},
        {desc.indices, desc.index_count, "desc.indices: NULL with index_count ", desc.index_count},
        {desc.triangle_material, desc.index_count / 3,
         "desc.triangle_material: NULL with index_count ", desc.index_count},
        {desc.materials, desc.material_count, "desc.materials: NULL with material_count ", desc.material_count},
        {desc.textures, desc.texture_count, "desc.textures: NULL with texture_count ", desc.texture_count},
        {desc.occluder_positions, desc.occluder_vertex_count,
         "desc.occluder_positions: NULL with occluder_vertex_count ", desc.occluder_vertex_count},
        {desc.occluder_indices, desc.occluder_index_count,
         "desc.occluder_indices: NULL with occluder_index_count ", desc.occluder_index_count},
        {desc.slots, desc.slot_count, "desc.slots: NULL with slot_count ", desc.slot_count},
    };
    for (const Array& array : arrays)
        if (missingArray(array.pointer, array.count))
            return argumentProblem(array.name + std::to_string(array.reported));
    return {};
}

/// The site's position (checked for range) and the grids into the manifest.
DescProblem convertSite(const gusuku_bakeset_desc& desc, gusuku::BakeSetManifest& manifest) {
    if (!(std::abs(desc.latitude_deg) <= 90.0)) return bakeSetProblem("desc.latitude_deg: must be in [-90, 90]");
    if (!(std::abs(desc.longitude_deg) <= 180.0))
        return bakeSetProblem("desc.longitude_deg: must be in [-180, 180]");
    if (!(std::abs(desc.height_m) <= kMaxSiteHeightM))
        return bakeSetProblem("desc.height_m: must be in [-100000, 100000]");
    manifest.site.name = "gusuku_bakeset_desc";
    manifest.site.latitude_deg = desc.latitude_deg;
    manifest.site.longitude_deg = desc.longitude_deg;
    manifest.site.height_m = desc.height_m;
    manifest.building.lightmap_resolution = desc.lightmap_resolution;
    manifest.ground_grid.grid.origin_enu_m = glm::dvec2(desc.ground_origin_enu_m[0], desc.ground_origin_enu_m[1]);
    manifest.ground_grid.grid.cell_m = desc.ground_cell_m;
    manifest.ground_grid.grid.columns = desc.ground_columns;
    manifest.ground_grid.grid.rows = desc.ground_rows;
    return {};
}

/// The building's mesh, materials and textures (a texture too large or without pixels is a problem).
DescProblem convertBuilding(const gusuku_bakeset_desc& desc, gusuku::BakeSetMesh& mesh) {
    mesh.positions = copyVectors<glm::vec3>(desc.positions, desc.vertex_count);
    mesh.normals = copyVectors<glm::vec3>(desc.normals, desc.vertex_count);
    mesh.uv0 = copyVectors<glm::vec2>(desc.uv0, desc.vertex_count);
    mesh.uv1 = copyVectors<glm::vec2>(desc.uv1, desc.vertex_count);
    if (desc.index_count > 0) mesh.indices.assign(desc.indices, desc.indices + desc.index_count);
    if (desc.index_count >= 3)
        mesh.triangle_material.assign(desc.triangle_material, desc.triangle_material + desc.index_count / 3);
    for (uint32_t m = 0; m < desc.material_count; ++m) {
        const gusuku_material& material = desc.materials[m];
        mesh.materials.push_back({glm::vec4(material.base_color_factor[0], material.base_color_factor[1],
                                            material.base_color_factor[2], material.base_color_factor[3]),
                                  material.base_color_texture});
        // API version 2; an older app's desc reads NULL here (gusuku_c_api_sizes.h, readSized).
        const float cutoff = desc.material_alpha_cutoffs != nullptr ? desc.material_alpha_cutoffs[m] : -1.0f;
        if (!(cutoff < 0.0f)) {  // NaN and values above 1 are masked here and refused by findBakeSetProblem
            mesh.materials.back().alpha_masked = true;
            mesh.materials.back().alpha_cutoff = cutoff;
        }
    }
    for (uint32_t t = 0; t < desc.texture_count; ++t) {
        const gusuku_texture& source = desc.textures[t];
        if (source.width > kMaxImageSide || source.height > kMaxImageSide)
            return tooLarge("desc.textures[" + std::to_string(t) + "]", source.width, source.height);
        gusuku::BakeSetTexture texture;
        texture.width = source.width;
        texture.height = source.height;
        const uint64_t bytes =
            (source.width > 0 && source.height > 0) ? uint64_t(source.width) * source.height * 4 : 0;
        if (missingArray(source.rgba8, bytes))
            return argumentProblem("desc.textures[" + std::to_string(t) + "].rgba8: NULL for a " +
                                   std::to_string(source.width) + " x " + std::to_string(source.height) + " texture");
        texture.rgba8.assign(source.rgba8, source.rgba8 + bytes);
        mesh.textures.push_back(std::move(texture));
    }
    return {};
}

/// Slot s: its manifest entry (sky, sun, colour statistics) and its images.
DescProblem convertSlot(const gusuku_slot& source, uint32_t s, gusuku::BakeSetData& data) {
    const std::string field = "desc.slots[" + std::to_string(s) + "]";
    gusuku::BakeSetSlot slot;
    slot.name = "slot " + std::to_string(s);
    if (source.sky == GUSUKU_SKY_OVERCAST) {
        slot.sky = gusuku::BakeSetSky::Overcast;
        slot.sun.irradiance_source = "none: overcast";
    } else if (source.sky == GUSUKU_SKY_SUNNY) {
        slot.sky = gusuku::BakeSetSky::Sunny;
        const double azimuth = source.sun_azimuth_deg * std::numbers::pi / 180.0;
        const double elevation = source.sun_apparent_elevation_deg * std::numbers::pi / 180.0;
        if (!std::isfinite(azimuth) || !(std::abs(source.sun_apparent_elevation_deg) <= 90.0))
            return bakeSetProblem(field + ".sun_azimuth_deg, sun_apparent_elevation_deg: must be finite, "
                                          "elevation in [-90, 90]");
        slot.sun.position = gusuku::BakeSetSunPosition{
            source.sun_azimuth_deg, source.sun_apparent_elevation_deg,
            glm::dvec3(std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                       std::sin(elevation))};
        slot.sun.present = source.sun_present != 0;
        slot.sun.irradiance_source = slot.sun.present ? "gusuku_bakeset_desc" : "none: sun below the horizon";
        if (slot.sun.present)
            slot.sun.irradiance_rgb = glm::dvec3(source.sun_irradiance_rgb[0], source.sun_irradiance_rgb[1],
                                                 source.sun_irradiance_rgb[2]);
    } else {
        return bakeSetProblem(field + ".sky: " + std::to_string(int(source.sky)) +
                              " is neither GUSUKU_SKY_SUNNY nor GUSUKU_SKY_OVERCAST");
    }
    if (source.has_colour_statistics) {
        gusuku::BakeSetColourStatistics statistics;
        statistics.lab_mean = glm::dvec3(source.lab_mean[0], source.lab_mean[1], source.lab_mean[2]);
        statistics.lab_sigma = glm::dvec3(source.lab_sigma[0], source.lab_sigma[1], source.lab_sigma[2]);
        slot.colour_statistics = statistics;
    }
    data.manifest.slots.push_back(std::move(slot));

    gusuku::BakeSetSlotImages images;
    for (auto [image, source_image, name] :
         {std::tuple{&images.building, &source.building, ".building"},
          std::tuple{&images.ground_with, &source.ground_with, ".ground_with"},
          std::tuple{&images.ground_without, &source.ground_without, ".ground_without"}})
        if (DescProblem problem = copyImage(*source_image, field + name, *image)) return problem;
    data.slots.push_back(std::move(images));
    return {};
}

}  // namespace

/// The desc's arrays into data, or the first problem found on the way (findBakeSetProblem checks the rest).
DescProblem convertDesc(const gusuku_bakeset_desc& desc, gusuku::BakeSetData& data) {
    if (DescProblem problem = checkDescArrays(desc)) return problem;
    if (DescProblem problem = convertSite(desc, data.manifest)) return problem;
    if (DescProblem problem = convertBuilding(desc, data.building)) return problem;
    data.occluder.positions = copyVectors<glm::vec3>(desc.occluder_positions, desc.occluder_vertex_count);
    if (desc.occluder_index_count > 0)
        data.occluder.indices.assign(desc.occluder_indices, desc.occluder_indices + desc.occluder_index_count);
    if (DescProblem problem = copyImage(desc.ground_geometry, "desc.ground_geometry", data.ground_geometry))
        return problem;
    for (uint32_t s = 0; s < desc.slot_count; ++s)
        if (DescProblem problem = convertSlot(desc.slots[s], s, data)) return problem;
    // API version 1. A bake set with ground albedo names it in its manifest, as a loaded one does.
    if (DescProblem problem = copyImage(desc.ground_albedo, "desc.ground_albedo", data.ground_albedo))
        return problem;
    if (!data.ground_albedo.rgba.empty()) data.manifest.ground_grid.albedo = "gusuku_bakeset_desc";
    return {};
}


}  // namespace gusuku::c_api_detail

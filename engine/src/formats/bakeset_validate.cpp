// findBakeSetProblem (gusuku/formats/bakeset_validate.h): every size, count, index and number the runtime relies on,
// checked once, reported as the first "FIELD: PROBLEM".
#include "gusuku/formats/bakeset_validate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gusuku/formats/format_table.h"
#include "gusuku/formats/ktx2.h"

namespace gusuku {

namespace {

// The ASTC 6x6 levels of a texture, when it has them: the full chain, each level's blocks.
std::optional<std::string> astcLevelsProblem(const BakeSetTexture& texture, const std::string& field) {
    if (texture.astc6x6_levels.empty()) return std::nullopt;
    const uint32_t width = uint32_t(texture.width), height = uint32_t(texture.height);
    const uint32_t level_count = ktx2FullLevelCount(width, height);
    if (texture.astc6x6_levels.size() != level_count)
        return field + ".astc6x6_levels: " + std::to_string(texture.astc6x6_levels.size()) +
               " levels, the full chain of " + std::to_string(width) + " x " + std::to_string(height) + " has " +
               std::to_string(level_count);
    for (uint32_t level = 0; level < level_count; ++level) {
        const uint64_t bytes = ktx2LevelBytes(Ktx2Format::kAstc6x6Srgb, std::max(1u, width >> level),
                                              std::max(1u, height >> level));
        if (texture.astc6x6_levels[level].size() != bytes)
            return field + ".astc6x6_levels[" + std::to_string(level) + "]: " +
                   std::to_string(texture.astc6x6_levels[level].size()) + " bytes, its 6 x 6 blocks need " +
                   std::to_string(bytes);
    }
    return std::nullopt;
}

using Problem = std::optional<std::string>;

std::string number(double value) {
    if (std::isnan(value)) return "NaN";
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }
bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }


/// The first element of values that is not finite, as "FIELD[i]: ... is not finite".
template <typename Vector>
Problem firstNonFinite(const std::vector<Vector>& values, const std::string& field) {
    for (size_t i = 0; i < values.size(); ++i)
        if (!finite(values[i])) return field + "[" + std::to_string(i) + "]: is not finite";
    return std::nullopt;
}

Problem checkIndices(const std::vector<uint32_t>& indices, size_t vertex_count, const std::string& field) {
    if (indices.size() % 3 != 0)
        return field + ".indices: " + std::to_string(indices.size()) + " indices, not a multiple of 3";
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= vertex_count)
            return field + ".indices[" + std::to_string(i) + "]: " + std::to_string(indices[i]) +
                   " is out of range (" + std::to_string(vertex_count) + " positions)";
    return std::nullopt;
}

Problem checkPerVertex(size_t count, size_t positions, const std::string& field) {
    if (count == positions) return std::nullopt;
    return field + ": " + std::to_string(count) + " entries, but " + std::to_string(positions) + " positions";
}

/// Size against the expected size (`what` says where the expectation comes from), storage, and texels: finite
/// everywhere, RGB >= 0 when rgb_non_negative.
Problem checkImage(const BakeSetImage& image, const std::string& field, int expected_width, int expected_height,
                   const std::string& what, bool rgb_non_negative) {
    if (image.width != expected_width || image.height != expected_height)
        return field + ": " + std::to_string(image.width) + " x " + std::to_string(image.height) + " texels, " + what;
    const size_t floats = size_t(image.width) * size_t(image.height) * 4;
    if (image.rgba.size() != floats)
        return field + ": " + std::to_string(image.rgba.size()) + " floats, " + std::to_string(image.width) + " x " +
               std::to_string(image.height) + " RGBA needs " + std::to_string(floats);
    static const char kChannel[4] = {'R', 'G', 'B', 'A'};
    for (size_t i = 0; i < floats; ++i) {
        const float value = image.rgba[i];
        const int channel = int(i % 4);
        const bool bad = !std::isfinite(value) || (rgb_non_negative && channel < 3 && value < 0.0f);
        if (!bad) continue;
        const size_t texel = i / 4;
        return field + ": texel (" + std::to_string(texel % size_t(image.width)) + ", " +
               std::to_string(texel / size_t(image.width)) + ") channel " + kChannel[channel] + " is " +
               number(value) + (std::isfinite(value) ? " (negative irradiance)" : "");
    }
    return std::nullopt;
}

Problem checkManifest(const BakeSetManifest& manifest) {
    if (manifest.building.lightmap_resolution <= 0)
        return "manifest.building.lightmap_resolution: " + std::to_string(manifest.building.lightmap_resolution) +
               " is not positive";
    const GroundGrid& grid = manifest.ground_grid.grid;
    if (grid.columns <= 0 || grid.rows <= 0)
        return "manifest.ground_grid: " + std::to_string(grid.columns) + " x " + std::to_string(grid.rows) +
               " cells, both must be positive";
    if (!(grid.cell_m > 0.0) || !std::isfinite(grid.cell_m) || !std::isfinite(grid.origin_enu_m.x) ||
        !std::isfinite(grid.origin_enu_m.y))
        return "manifest.ground_grid: cell_m " + number(grid.cell_m) + ", origin (" + number(grid.origin_enu_m.x) +
               ", " + number(grid.origin_enu_m.y) + "): the cell must be positive and all finite";
    // The runtime uploads the slots as the layers of one array image, which may not have 0 layers.
    if (manifest.slots.empty()) return "manifest.slots: empty; a bake set holds at least one slot";
    for (size_t s = 0; s < manifest.slots.size(); ++s) {
        const BakeSetSun& sun = manifest.slots[s].sun;
        const std::string field = "manifest.slots[" + std::to_string(s) + "].sun";
        if (sun.position) {
            const glm::dvec3& d = sun.position->direction_enu;
            if (!finite(d) || std::fabs(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z) - 1.0) > 1e-5)
                return field + ".direction_enu: (" + number(d.x) + ", " + number(d.y) + ", " + number(d.z) +
                       ") is not a finite unit vector";
        }
        if (sun.present) {
            const glm::dvec3& e = sun.irradiance_rgb;
            if (!finite(e) || e.x < 0.0 || e.y < 0.0 || e.z < 0.0)
                return field + ".irradiance_rgb: (" + number(e.x) + ", " + number(e.y) + ", " + number(e.z) +
                       ") must be finite and >= 0";
        }
    }
    return std::nullopt;
}

Problem checkBuilding(const BakeSetMesh& mesh) {
    if (mesh.indices.empty()) return std::string("building.indices: the building has no triangles");
    if (Problem p = checkIndices(mesh.indices, mesh.positions.size(), "building")) return p;
    const size_t vertices = mesh.positions.size();
    if (Problem p = checkPerVertex(mesh.normals.size(), vertices, "building.normals")) return p;
    if (Problem p = checkPerVertex(mesh.uv0.size(), vertices, "building.uv0")) return p;
    if (Problem p = checkPerVertex(mesh.uv1.size(), vertices, "building.uv1")) return p;
    const size_t triangles = mesh.indices.size() / 3;
    if (mesh.triangle_material.size() != triangles)
        return "building.triangle_material: " + std::to_string(mesh.triangle_material.size()) + " entries, but " +
               std::to_string(triangles) + " triangles";
    for (size_t t = 0; t < triangles; ++t)
        if (mesh.triangle_material[t] >= mesh.materials.size())
            return "building.triangle_material[" + std::to_string(t) + "]: material " +
                   std::to_string(mesh.triangle_material[t]) + " does not exist (" +
                   std::to_string(mesh.materials.size()) + " materials)";
    for (size_t m = 0; m < mesh.materials.size(); ++m) {
        const BakeSetMaterial& material = mesh.materials[m];
        const std::string field = "building.materials[" + std::to_string(m) + "]";
        if (!finite(material.base_color_factor)) return field + ".base_color_factor: is not finite";
        if (material.alpha_masked && !(material.alpha_cutoff >= 0.0f && material.alpha_cutoff <= 1.0f))
            return field + ".alpha_cutoff: " + std::to_string(material.alpha_cutoff) + " is not in [0, 1]";
        if (material.base_color_texture < -1 || material.base_color_texture >= int(mesh.textures.size()))
            return field + ".base_color_texture: " + std::to_string(material.base_color_texture) +
                   " is neither -1 nor a texture (" + std::to_string(mesh.textures.size()) + " textures)";
    }
    for (size_t t = 0; t < mesh.textures.size(); ++t) {
        const BakeSetTexture& texture = mesh.textures[t];
        const std::string field = "building.textures[" + std::to_string(t) + "]";
        if (texture.width <= 0 || texture.height <= 0)
            return field + ": " + std::to_string(texture.width) + " x " + std::to_string(texture.height) +
                   " texels, both must be positive";
        const size_t bytes = size_t(texture.width) * size_t(texture.height) * 4;
        // A pack for ASTC devices may hold only the blocks (BakeSetTexture): rgba8 empty then.
        if (texture.rgba8.size() != bytes && !(texture.rgba8.empty() && !texture.astc6x6_levels.empty()))
            return field + ".rgba8: " + std::to_string(texture.rgba8.size()) + " bytes, " +
                   std::to_string(texture.width) + " x " + std::to_string(texture.height) + " RGBA8 needs " +
                   std::to_string(bytes);
        if (Problem p = astcLevelsProblem(texture, field)) return p;
    }
    if (Problem p = firstNonFinite(mesh.positions, "building.positions")) return p;
    if (Problem p = firstNonFinite(mesh.normals, "building.normals")) return p;
    if (Problem p = firstNonFinite(mesh.uv0, "building.uv0")) return p;
    if (Problem p = firstNonFinite(mesh.uv1, "building.uv1")) return p;
    return std::nullopt;
}

Problem checkOccluder(const BakeSetOccluder& occluder, const BakeSetManifest& manifest) {
    if (Problem p = checkIndices(occluder.indices, occluder.positions.size(), "occluder")) return p;
    if (Problem p = firstNonFinite(occluder.positions, "occluder.positions")) return p;
    const uint64_t triangles = occluder.indices.size() / 3;
    if (manifest.occluder && manifest.occluder->triangles != triangles)
        return "occluder: " + std::to_string(triangles) + " triangles, the manifest says occluder.triangles " +
               std::to_string(manifest.occluder->triangles);
    return std::nullopt;
}

// A slot's lightmap blocks: each a lightmap block format of the format table, of the row's block_bytes for each
// started block of the lightmap; every slot has the formats slot 0 has (the runtime holds one array of one
// format).
Problem checkLightmapBlocks(const BakeSetData& bake_set, size_t slot, const std::string& lightmap_size) {
    const uint32_t side = uint32_t(bake_set.manifest.building.lightmap_resolution);
    const std::string field = "slots[" + std::to_string(slot) + "].building_blocks";
    const auto& blocks = bake_set.slots[slot].building_blocks;
    const auto& first = bake_set.slots[0].building_blocks;
    for (const auto& [vk_format, bytes] : blocks) {
        const formats::FormatRow* row = formats::findFormat(vk_format);
        if (row == nullptr || row->family != formats::FormatFamily::kLightmap || !formats::isBlockCodec(row->codec))
            return field + ": " + ktx2FormatName(vk_format) + " is not a lightmap block format";
        const uint64_t expected = formats::levelBytes(*row, side, side);
        if (bytes.size() != expected)
            return field + "[" + row->vk_name + "]: " + std::to_string(bytes.size()) + " bytes, not the " +
                   std::to_string(expected) + " of " + std::to_string(row->block_side) + " x " +
                   std::to_string(row->block_side) + " blocks (" + lightmap_size + ")";
        if (first.count(vk_format) == 0)
            return field + "[" + row->vk_name + "]: present, but slots[0].building_blocks has none (every slot or "
                   "none has each format's blocks)";
    }
    for (const auto& [vk_format, bytes] : first)
        if (blocks.count(vk_format) == 0)
            return field + "[" + ktx2FormatName(vk_format) + "]: missing, but slots[0].building_blocks has them "
                   "(every slot or none has each format's blocks)";
    return std::nullopt;
}

}  // namespace

std::optional<std::string> findBakeSetProblem(const BakeSetData& bake_set) {
    const BakeSetManifest& manifest = bake_set.manifest;
    if (Problem p = checkManifest(manifest)) return p;
    if (Problem p = checkBuilding(bake_set.building)) return p;
    if (Problem p = checkOccluder(bake_set.occluder, manifest)) return p;

    const GroundGrid& grid = manifest.ground_grid.grid;
    const std::string grid_size = "the manifest's ground grid is " + std::to_string(grid.columns) + " x " +
                                  std::to_string(grid.rows);
    if (Problem p = checkImage(bake_set.ground_geometry, "ground_geometry", grid.columns, grid.rows, grid_size, false))
        return p;
    // The ground albedo is optional (older bake sets): absent, both it and the manifest's name are empty.
    if (manifest.ground_grid.albedo.empty() != bake_set.ground_albedo.rgba.empty())
        return std::string("ground_albedo: ") +
               (bake_set.ground_albedo.rgba.empty() ? "missing, but the manifest names ground_grid.albedo"
                                                    : "present, but the manifest names no ground_grid.albedo");
    if (!bake_set.ground_albedo.rgba.empty())
        if (Problem p = checkImage(bake_set.ground_albedo, "ground_albedo", grid.columns, grid.rows, grid_size, true))
            return p;

    if (bake_set.slots.size() != manifest.slots.size())
        return "slots: " + std::to_string(bake_set.slots.size()) + " entries, but manifest.slots has " +
               std::to_string(manifest.slots.size());
    const int resolution = manifest.building.lightmap_resolution;
    const std::string lightmap_size = "the manifest says lightmap_resolution " + std::to_string(resolution);
    // The sun horizons are optional (older bake sets have none); present, a square over the lightmap's
    // coordinates at a resolution of their own (finer than the lightmap's where a tile row needs it).
    const BakeSetSunHorizon& horizon = bake_set.building_sun_horizon;
    if (manifest.building.sun_horizon.empty() != horizon.empty())
        return std::string("building_sun_horizon: ") +
               (horizon.empty() ? "missing, but the manifest names building.sun_horizon"
                                : "present, but the manifest names no building.sun_horizon");
    if (!horizon.empty() &&
        (horizon.width < kMinSunHorizonResolution || horizon.width > kMaxSunHorizonResolution ||
         horizon.height != horizon.width ||
         horizon.rgba8.size() != size_t(kSunHorizonLayers) * size_t(horizon.width) * size_t(horizon.height) * 4))
        return "building_sun_horizon: " + std::to_string(horizon.width) + " x " + std::to_string(horizon.height) +
               " texels in " + std::to_string(horizon.rgba8.size()) + " bytes: not a square of " +
               std::to_string(kMinSunHorizonResolution) + " to " + std::to_string(kMaxSunHorizonResolution) +
               " texels a side in 2 layers of RGBA8";
    for (size_t s = 0; s < bake_set.slots.size(); ++s) {
        const BakeSetSlotImages& slot = bake_set.slots[s];
        const std::string field = "slots[" + std::to_string(s) + "]";
        if (Problem p = checkImage(slot.building, field + ".building", resolution, resolution, lightmap_size, true))
            return p;
        if (Problem p = checkImage(slot.ground_with, field + ".ground_with", grid.columns, grid.rows, grid_size, true))
            return p;
        if (Problem p = checkImage(slot.ground_without, field + ".ground_without", grid.columns, grid.rows, grid_size,
                                   true))
            return p;
        if (Problem p = checkLightmapBlocks(bake_set, s, lightmap_size)) return p;
    }
    if (!(bake_set.building_blocks_scale > 0.0f && std::isfinite(bake_set.building_blocks_scale)))
        return "building_blocks_scale: " + std::to_string(bake_set.building_blocks_scale) + " is not a positive number";
    return std::nullopt;
}

}  // namespace gusuku

// loadBakeSet (gusuku/assets/bakeset_loader.h): manifest first, then each file it names, each checked against the
// manifest as it is read so errors name the file; findBakeSetProblem last, as the runtime will.
#include "gusuku/assets/bakeset_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/maths/colour.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/sun_horizon_ktx2.h"

namespace gusuku {

namespace {

/// A bake set file, by the manifest field that names it (a JSON pointer) and the name found there.
struct NamedFile {
    std::string pointer;
    std::string name;
};

/// folder/name after checking that the manifest's name stays in the folder and names a regular file.
std::string bakeSetFile(const std::string& folder, const std::string& manifest_path, const NamedFile& file) {
    // A NUL would cut the path short where the system reads it, so the file opened would not be the one named.
    if (file.name.find('\0') != std::string::npos)
        throw InputError(manifest_path, file.pointer, "holds a NUL character (\\u0000), which no file name may");
    if (file.name.find('/') != std::string::npos || file.name.find('\\') != std::string::npos ||
        file.name == "." || file.name == "..")
        throw InputError(manifest_path, file.pointer,
                         "\"" + file.name + "\" is not a plain file name in the bake set folder");
    const std::string path = folder + "/" + file.name;
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (!std::filesystem::exists(status))
        throw InputError(manifest_path, file.pointer, "names \"" + file.name + "\", which is not in " + folder);
    if (status.type() != std::filesystem::file_type::regular)
        throw InputError(manifest_path, file.pointer, "names \"" + file.name + "\", which is not a regular file");
    return path;
}

uint8_t unorm8(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

BakeSetTexture texture8(const ImageRGBA& image) {
    BakeSetTexture texture;
    texture.width = image.width;
    texture.height = image.height;
    texture.rgba8.resize(image.texels.size());
    for (size_t i = 0; i < image.texels.size(); ++i) {
        const float value = image.texels[i];
        texture.rgba8[i] = unorm8(i % 4 == 3 ? value : srgbEncode(std::clamp(value, 0.0f, 1.0f)));
    }
    return texture;
}

BakeSetMesh loadBuilding(const std::string& path) {
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();  // the bake set's frame: glTF Y-up axes on site ENU metres
    TriangleMesh mesh = loadGltf(path, options);
    if (mesh.indices.empty()) throw InputError(path, "meshes", "the building has no triangles");
    if (!mesh.has_uv1)
        throw InputError(path, "TEXCOORD_1", "missing: a bake set's building carries its lightmap UVs there");
    BakeSetMesh building;
    building.positions = std::move(mesh.positions);
    building.normals = std::move(mesh.normals);
    building.uv0 = std::move(mesh.uv0);
    building.uv1 = std::move(mesh.uv1);
    building.indices = std::move(mesh.indices);
    building.triangle_material = std::move(mesh.triangle_material);
    for (const Material& material : mesh.materials)
        building.materials.push_back(
            {material.base_color_factor, material.base_color_texture, material.alpha_masked, material.alpha_cutoff});
    for (const ImageRGBA& texture : mesh.textures) building.textures.push_back(texture8(texture));
    return building;
}

/// Positions and indices; loadGltf gives a primitive without normals one vertex per corner, so exactly
/// coincident corners are welded back (in order of first use, so the result does not depend on hashing).
BakeSetOccluder loadOccluder(const std::string& path, uint64_t expected_triangles) {
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    const TriangleMesh mesh = loadGltf(path, options);
    if (mesh.triangleCount() != expected_triangles)
        throw InputError(path, "meshes", std::to_string(mesh.triangleCount()) +
                                             " triangles, the manifest's /occluder/triangles says " +
                                             std::to_string(expected_triangles));
    BakeSetOccluder occluder;
    std::map<std::array<uint32_t, 3>, uint32_t> welded;
    occluder.indices.reserve(mesh.indices.size());
    for (const uint32_t corner : mesh.indices) {
        const glm::vec3& p = mesh.positions[corner];
        std::array<uint32_t, 3> bits;
        std::memcpy(bits.data(), &p, sizeof bits);
        const auto [entry, inserted] = welded.try_emplace(bits, uint32_t(occluder.positions.size()));
        if (inserted) occluder.positions.push_back(p);
        occluder.indices.push_back(entry->second);
    }
    return occluder;
}

/// An EXR of 4 float32 channels at the manifest's size (`size_source` says which field sets it), every texel
/// within `ranges` (gusuku/formats/bakeset_ranges.h, as the runtime pack's reader holds its KTX2 texels). The first
/// bad texel is named.
BakeSetImage loadExr(const std::string& path, int width, int height, const std::string& size_source,
                     std::initializer_list<BakeSetRange> ranges) {
    // The header's size first: a file that declares another size is refused before its texels are decoded (a
    // corrupt header can declare a gigabyte of them).
    const ImageSize declared = readImageSize(path);
    if (declared.width != width || declared.height != height)
        throw InputError(path, "image size",
                         std::to_string(declared.width) + " x " + std::to_string(declared.height) +
                             " texels, expected " + std::to_string(width) + " x " + std::to_string(height) + " (" +
                             size_source + ")");
    ImageRGBA image = readFloatRgbaExr(path);
    if (image.width != width || image.height != height)
        throw InputError(path, "image size",
                         std::to_string(image.width) + " x " + std::to_string(image.height) + " texels, expected " +
                             std::to_string(width) + " x " + std::to_string(height) + " (" + size_source + ")");
    BakeSetImage out{image.width, image.height, std::move(image.texels)};
    if (const std::optional<BakeSetTexelProblem> problem = findBakeSetTexelProblem(out, ranges))
        throw InputError(path, problem->field, problem->problem);
    return out;
}

/// The path with symbolic links resolved as far as it exists (the rest appended lexically), absolute.
std::filesystem::path physicalPath(const std::string& path) {
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(path);
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, error);
    return (error ? absolute : canonical).lexically_normal();
}

}  // namespace

std::string resolveBakeSetInputPath(const std::string& folder, const BakeSetManifest& manifest,
                                    const std::string& path) {
    const std::filesystem::path input(path);
    if (input.is_absolute() || !manifest.input_paths_relative_to_folder) return path;
    return (physicalPath(folder) / input).lexically_normal().string();
}

std::string bakeSetRelativeInputPath(const std::string& folder, const std::string& path) {
    const std::filesystem::path input = physicalPath(path);
    const std::filesystem::path relative = input.lexically_relative(physicalPath(folder));
    return relative.empty() ? input.string() : relative.generic_string();
}

namespace {

BakeSetManifest readManifestOf(const std::string& manifest_path) {
    std::error_code error;
    if (!std::filesystem::exists(manifest_path, error))
        throw InputError(manifest_path, "",
                         "file not found: not a bake set folder, or its bake has not finished (the manifest is "
                         "written last)");
    return readBakeSetManifest(manifest_path);
}

// Every file the manifest names, read and checked as the runtime needs them; whole and partial sets alike.
BakeSetData loadNamedFiles(const std::string& folder, const std::string& manifest_path, BakeSetManifest manifest_read) {
    BakeSetData data;
    data.manifest = std::move(manifest_read);
    const BakeSetManifest& manifest = data.manifest;
    // Every named file must be there before anything large is read.
    const std::string building_path = bakeSetFile(folder, manifest_path, {"/building/mesh", manifest.building.mesh});
    std::string occluder_path;
    if (manifest.occluder) occluder_path = bakeSetFile(folder, manifest_path, {"/occluder/mesh", manifest.occluder->mesh});
    const std::string geometry_path =
        bakeSetFile(folder, manifest_path, {"/ground_grid/geometry", manifest.ground_grid.geometry});
    std::string albedo_path;
    if (!manifest.ground_grid.albedo.empty())
        albedo_path = bakeSetFile(folder, manifest_path, {"/ground_grid/albedo", manifest.ground_grid.albedo});
    std::string horizon_path;
    if (!manifest.building.sun_horizon.empty())
        horizon_path = bakeSetFile(folder, manifest_path, {"/building/sun_horizon", manifest.building.sun_horizon});
    std::vector<std::array<std::string, 3>> slot_paths;
    for (size_t s = 0; s < manifest.slots.size(); ++s) {
        const BakeSetSlot& slot = manifest.slots[s];
        const std::string pointer = "/slots/" + std::to_string(s) + "/";
        slot_paths.push_back(
            {bakeSetFile(folder, manifest_path, {pointer + "building_irradiance", slot.building_irradiance}),
             bakeSetFile(folder, manifest_path,
                         {pointer + "ground_irradiance_with_building", slot.ground_irradiance_with_building}),
             bakeSetFile(folder, manifest_path,
                         {pointer + "ground_irradiance_without_building", slot.ground_irradiance_without_building})});
    }

    data.building = loadBuilding(building_path);
    if (manifest.occluder) data.occluder = loadOccluder(occluder_path, manifest.occluder->triangles);
    const GroundGrid& grid = manifest.ground_grid.grid;
    const std::string grid_size = "the manifest's /ground_grid/columns x rows";
    // RGB is the ground's unit normal (docs/bakeset.md): the ratio's sun term is its cosine, so a zero or
    // unnormalised normal would darken or brighten the camera's ground with no building there.
    data.ground_geometry =
        loadExr(geometry_path, grid.columns, grid.rows, grid_size, {kBakeSetGroundNormal, kBakeSetGroundHeightM});
    if (!albedo_path.empty())
        data.ground_albedo = loadExr(albedo_path, grid.columns, grid.rows, grid_size, {kBakeSetGroundAlbedo});
    if (!horizon_path.empty()) {
        const std::string bytes = readWholeFile(horizon_path);
        data.building_sun_horizon =
            decodeSunHorizonKtx2(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), horizon_path);
    }
    const int resolution = manifest.building.lightmap_resolution;
    for (const auto& paths : slot_paths) {
        BakeSetSlotImages slot;
        slot.building = loadExr(paths[0], resolution, resolution, "the manifest's /building/lightmap_resolution",
                                {kBakeSetTexelIrradiance, kBakeSetTexelCoverage});
        slot.ground_with =
            loadExr(paths[1], grid.columns, grid.rows, grid_size, {kBakeSetTexelIrradiance, kBakeSetTexelCoverage});
        slot.ground_without =
            loadExr(paths[2], grid.columns, grid.rows, grid_size, {kBakeSetTexelIrradiance, kBakeSetTexelCoverage});
        data.slots.push_back(std::move(slot));
    }

    if (const std::optional<std::string> problem = findBakeSetProblem(data)) {
        const size_t colon = problem->find(": ");
        throw InputError(folder, problem->substr(0, colon),
                         colon == std::string::npos ? "" : problem->substr(colon + 2));
    }
    return data;
}

}  // namespace

BakeSetData loadBakeSet(const std::string& folder) {
    const std::string manifest_path = folder + "/manifest.json";
    BakeSetManifest manifest = readManifestOf(manifest_path);
    if (manifest.partial)
        throw InputError(manifest_path, "/partial",
                         "a partial bake set (slot \"" + manifest.partial->slot + "\" of " +
                             std::to_string(manifest.partial->site_slots.size()) +
                             "): join the partial sets with gusuku-bake merge first");
    return loadNamedFiles(folder, manifest_path, std::move(manifest));
}

BakeSetData loadPartialBakeSet(const std::string& folder) {
    const std::string manifest_path = folder + "/manifest.json";
    BakeSetManifest manifest = readManifestOf(manifest_path);
    if (!manifest.partial)
        throw InputError(manifest_path, "/partial",
                         "missing: this is a whole bake set, not one slot's partial set (bake with --slot NAME)");
    return loadNamedFiles(folder, manifest_path, std::move(manifest));
}

}  // namespace gusuku

// The runtime pack reader (gusuku/pack_loader/runtime_pack.h): standard library only.

#include "gusuku/pack_loader/runtime_pack.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <utility>

#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/formats/format_table.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/formats/pack_geometry.h"
#include "gusuku/maths/shared_exponent.h"
#include "gusuku/formats/sun_horizon_ktx2.h"
#include "pack_manifest.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
constexpr uintmax_t kLargestPackFile = uintmax_t(1) << 30;
// A manifest is about 10 KB; far above that is not one (and would only cost the JSON reader time).
constexpr size_t kLargestManifest = size_t(16) << 20;

std::vector<uint8_t> readPackFile(const std::string& path) {
    std::error_code error;
    if (!fs::is_regular_file(path, error)) throw InputError(path, "", "is missing or not a regular file");
    const uintmax_t size = fs::file_size(path, error);
    if (error || size > kLargestPackFile) throw InputError(path, "", "is unreadable or larger than 1 GiB");
    std::ifstream stream(path, std::ios::binary);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (!stream.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
        throw InputError(path, "", "could not be read");
    return bytes;
}

// A file name from the manifest must name a file inside the pack.
std::string packFileOf(const std::string& folder, const std::string& manifest_path, const std::string& field,
                       const std::string& exr_name) {
    if (exr_name.find('\0') != std::string::npos)
        throw InputError(manifest_path, field, "holds a NUL character (\\u0000), which no file name may");
    if (exr_name.empty() || exr_name.find('/') != std::string::npos || exr_name.find('\\') != std::string::npos ||
        exr_name == "." || exr_name == "..")
        throw InputError(manifest_path, field, quotedForMessage(exr_name) + " is not a plain file name");
    const size_t dot = exr_name.rfind('.');
    return folder + "/" + (dot == std::string::npos ? exr_name : exr_name.substr(0, dot)) + ".ktx2";
}

Ktx2Image readKtx2(const std::string& path, Ktx2Format format, uint32_t width, uint32_t height) {
    const std::vector<uint8_t> bytes = readPackFile(path);
    Ktx2Image image = decodeKtx2(bytes.data(), bytes.size(), path, format);
    if (image.width != width || image.height != height)
        throw InputError(path, "pixelWidth/pixelHeight",
                         std::to_string(image.width) + " x " + std::to_string(image.height) + " is not the manifest's " +
                             std::to_string(width) + " x " + std::to_string(height));
    return image;
}

std::string formatScale(float scale) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(scale));
    return text;
}

// Every decoded texel within the rows of gusuku/formats/bakeset_ranges.h, as the EXR set's loader holds its texels.
void requireTexelsInRange(const std::string& path, const BakeSetImage& image,
                          std::initializer_list<BakeSetRange> ranges, const std::string& note = "") {
    if (const std::optional<BakeSetTexelProblem> problem = findBakeSetTexelProblem(image, ranges))
        throw InputError(path, problem->field, problem->problem + note);
}

BakeSetImage floatImage(const std::string& path, uint32_t width, uint32_t height,
                        std::initializer_list<BakeSetRange> ranges) {
    const Ktx2Image image = readKtx2(path, Ktx2Format::kR32g32b32a32Sfloat, width, height);
    BakeSetImage out{int(width), int(height), std::vector<float>(image.texels.size() / 4)};
    std::memcpy(out.rgba.data(), image.texels.data(), image.texels.size());
    requireTexelsInRange(path, out, ranges);
    return out;
}

BakeSetImage lightmapImage(const std::string& path, uint32_t resolution, float scale) {
    const Ktx2Image packed = readKtx2(path, Ktx2Format::kE5b9g9r9Ufloat, resolution, resolution);
    const std::string valid_path = path.substr(0, path.size() - 5) + "_valid.ktx2";
    const Ktx2Image valid = readKtx2(valid_path, Ktx2Format::kR8Unorm, resolution, resolution);
    BakeSetImage out{int(resolution), int(resolution), std::vector<float>(size_t(resolution) * resolution * 4)};
    for (size_t texel = 0; texel < valid.texels.size(); ++texel) {
        uint32_t bits;
        std::memcpy(&bits, &packed.texels[texel * 4], 4);
        float rgb[3];
        unpackE5b9g9r9(bits, rgb);
        for (int channel = 0; channel < 3; ++channel) out.rgba[texel * 4 + channel] = rgb[channel] * scale;
        const uint8_t mark = valid.texels[texel];
        if (mark != 0 && mark != 255)
            throw InputError(valid_path, "texel (" + std::to_string(texel % resolution) + ", " +
                                             std::to_string(texel / resolution) + ")",
                             std::to_string(mark) + " is neither 0 (invalid) nor 255 (valid)");
        out.rgba[texel * 4 + 3] = mark == 255 ? 1.0f : 0.0f;
    }
    // The range holds the texels as the runtime will see them: a large lightmap_scale makes every one too bright.
    requireTexelsInRange(path, out, {kBakeSetTexelIrradiance, kBakeSetTexelCoverage},
                         " after pack.bin's lightmap_scale " + formatScale(scale));
    return out;
}

// The slot's lightmap blocks in each block format the format table gives a pack file (building_<slot>_astc.ktx2
// for ASTC 4x4 HDR), those the pack has; a pack written before them has none, and the
// runtime then draws the E5B9G9R9 lightmap.
std::map<uint32_t, std::vector<uint8_t>> lightmapBlocks(const std::string& lightmap_path, uint32_t resolution) {
    std::map<uint32_t, std::vector<uint8_t>> blocks;
    for (const formats::FormatRow& row : formats::kFormatRows) {
        if (row.pack_suffix == nullptr) continue;
        const std::string path = lightmap_path.substr(0, lightmap_path.size() - 5) + row.pack_suffix + ".ktx2";
        std::error_code error;
        if (!fs::exists(path, error)) continue;
        blocks[row.vk_format] = readKtx2(path, Ktx2Format(row.vk_format), resolution, resolution).texels;
    }
    return blocks;
}

// A base-colour texture: texture_<n>.ktx2 (RGBA8) and texture_<n>_astc.ktx2 (ASTC 6x6 blocks, the full chain),
// either of which may be absent but not both (a phone's pack may leave out the RGBA8, a pack written before the
// blocks has none).
void readTexture(const std::string& folder, size_t index, BakeSetTexture& texture) {
    const std::string rgba8_path = folder + "/texture_" + std::to_string(index) + ".ktx2";
    const std::string astc_path = folder + "/texture_" + std::to_string(index) + "_astc.ktx2";
    const uint32_t width = uint32_t(texture.width), height = uint32_t(texture.height);
    std::error_code error;
    if (fs::exists(astc_path, error)) {
        const std::vector<uint8_t> bytes = readPackFile(astc_path);
        Ktx2Image image = decodeKtx2MipChain(bytes.data(), bytes.size(), astc_path, Ktx2Format::kAstc6x6Srgb);
        if (image.width != width || image.height != height)
            throw InputError(astc_path, "pixelWidth/pixelHeight",
                             std::to_string(image.width) + " x " + std::to_string(image.height) +
                                 " is not pack.bin's " + std::to_string(width) + " x " + std::to_string(height));
        texture.astc6x6_levels.push_back(std::move(image.texels));
        for (std::vector<uint8_t>& level : image.smaller_levels) texture.astc6x6_levels.push_back(std::move(level));
        if (!fs::exists(rgba8_path, error)) return;
    }
    texture.rgba8 = readKtx2(rgba8_path, Ktx2Format::kR8g8b8a8Srgb, width, height).texels;
}

std::string packFolderOf(const std::string& folder) {
    std::error_code error;
    if (!fs::exists(folder + "/pack.bin", error) && fs::exists(folder + "/pack/pack.bin", error)) return folder + "/pack";
    return folder;
}

}  // namespace

BakeSetData loadRuntimePack(const std::string& given_folder) {
    const std::string folder = packFolderOf(given_folder);
    const std::string manifest_path = folder + "/manifest.json";
    const std::vector<uint8_t> manifest_bytes = readPackFile(manifest_path);
    if (manifest_bytes.size() > kLargestManifest)
        throw InputError(manifest_path, "", std::to_string(manifest_bytes.size()) + " bytes is more than a manifest's 16 MiB");
    BakeSetData data;
    data.manifest = pack_detail::readPackManifest(std::string(manifest_bytes.begin(), manifest_bytes.end()), manifest_path);
    const std::string geometry_path = folder + "/pack.bin";
    const std::vector<uint8_t> geometry_bytes = readPackFile(geometry_path);
    PackGeometry geometry = decodePackGeometry(geometry_bytes.data(), geometry_bytes.size(), geometry_path);
    for (size_t index = 0; index < geometry.building.textures.size(); ++index)
        readTexture(folder, index, geometry.building.textures[index]);
    data.building = std::move(geometry.building);
    data.occluder = std::move(geometry.occluder);

    const BakeSetManifest& manifest = data.manifest;
    const uint32_t columns = uint32_t(manifest.ground_grid.grid.columns), rows = uint32_t(manifest.ground_grid.grid.rows);
    data.ground_geometry =
        floatImage(packFileOf(folder, manifest_path, "/ground_grid/geometry", manifest.ground_grid.geometry), columns,
                   rows, {kBakeSetGroundNormal, kBakeSetGroundHeightM});
    if (!manifest.ground_grid.albedo.empty())
        data.ground_albedo =
            floatImage(packFileOf(folder, manifest_path, "/ground_grid/albedo", manifest.ground_grid.albedo), columns,
                       rows, {kBakeSetGroundAlbedo});
    if (!manifest.building.sun_horizon.empty()) {
        const std::string path =
            packFileOf(folder, manifest_path, "/building/sun_horizon", manifest.building.sun_horizon);
        const std::vector<uint8_t> bytes = readPackFile(path);
        data.building_sun_horizon = decodeSunHorizonKtx2(bytes.data(), bytes.size(), path);
    }
    const uint32_t resolution = uint32_t(manifest.building.lightmap_resolution);
    for (size_t slot = 0; slot < manifest.slots.size(); ++slot) {
        const BakeSetSlot& entry = manifest.slots[slot];
        const std::string pointer = "/slots/" + std::to_string(slot) + "/";
        BakeSetSlotImages images;
        const std::string lightmap_path =
            packFileOf(folder, manifest_path, pointer + "building_irradiance", entry.building_irradiance);
        images.building = lightmapImage(lightmap_path, resolution, geometry.lightmap_scale);
        images.building_blocks = lightmapBlocks(lightmap_path, resolution);
        images.ground_with = floatImage(packFileOf(folder, manifest_path, pointer + "ground_irradiance_with_building",
                                                   entry.ground_irradiance_with_building),
                                        columns, rows, {kBakeSetTexelIrradiance, kBakeSetTexelCoverage});
        images.ground_without = floatImage(packFileOf(folder, manifest_path, pointer + "ground_irradiance_without_building",
                                                      entry.ground_irradiance_without_building),
                                           columns, rows, {kBakeSetTexelIrradiance, kBakeSetTexelCoverage});
        data.slots.push_back(std::move(images));
    }
    data.building_blocks_scale = geometry.lightmap_scale;
    if (const std::optional<std::string> problem = findBakeSetProblem(data))
        throw InputError(folder, "bake set", *problem);
    return data;
}

}  // namespace gusuku

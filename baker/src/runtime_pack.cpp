// Writes BAKESET/pack/ from a finished bake set (gusuku_bake/runtime_pack.h).

#include "gusuku_bake/runtime_pack.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/format_table.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/formats/pack_geometry.h"
#include "gusuku/maths/shared_exponent.h"
#include "gusuku/maths/texture_coverage.h"
#include "gusuku_bake/astc_lightmap.h"
#include "gusuku_bake/astc_texture.h"
#include "gusuku_bake/output_guard.h"
#include "gusuku/formats/sun_horizon_ktx2.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;

// building_noon.exr -> building_noon.ktx2: the pack's name for each image the manifest names.
std::string packName(const std::string& exr_name) {
    const size_t dot = exr_name.rfind('.');
    return (dot == std::string::npos ? exr_name : exr_name.substr(0, dot)) + ".ktx2";
}

// building_noon.exr -> building_noon_valid.ktx2, building_noon_astc.ktx2: the lightmap's companion files.
std::string lightmapCompanionName(const std::string& exr_name, const char* suffix) {
    const std::string base = packName(exr_name);
    return base.substr(0, base.size() - 5) + suffix + ".ktx2";
}

// The smallest power of 2 (>= 1) that brings every lightmap's RGB within E5B9G9R9's range: dividing by a power
// of 2 changes no float but its exponent, so the pack's scale loses nothing.
float lightmapScaleOf(const BakeSetData& bake_set) {
    float largest = 0.0f;
    for (const BakeSetSlotImages& slot : bake_set.slots)
        for (size_t index = 0; index < slot.building.rgba.size(); ++index)
            if (index % 4 != 3) largest = std::max(largest, slot.building.rgba[index]);
    float scale = 1.0f;
    while (largest / scale > kLargestSharedExponentValue) scale *= 2.0f;
    return scale;
}

Ktx2Image sharedExponentLightmap(const BakeSetImage& image, float inverse_scale) {
    Ktx2Image out{Ktx2Format::kE5b9g9r9Ufloat, uint32_t(image.width), uint32_t(image.height), {}};
    out.texels.resize(size_t(image.width) * image.height * 4);
    for (size_t texel = 0; texel < out.texels.size() / 4; ++texel) {
        const float* rgba = &image.rgba[texel * 4];
        const uint32_t packed = packE5b9g9r9(rgba[0] * inverse_scale, rgba[1] * inverse_scale, rgba[2] * inverse_scale);
        std::memcpy(&out.texels[texel * 4], &packed, 4);
    }
    return out;
}

// The lightmap's alpha (1 on traced, valid texels) as 255 and 0.
Ktx2Image validityMask(const BakeSetImage& image) {
    Ktx2Image out{Ktx2Format::kR8Unorm, uint32_t(image.width), uint32_t(image.height), {}};
    for (size_t texel = 0; texel < image.rgba.size() / 4; ++texel)
        out.texels.push_back(image.rgba[texel * 4 + 3] > 0.0f ? 255 : 0);
    return out;
}

// The lightmap's RGB / scale as the blocks of a lightmap row with a pack file (the same scale as the E5B9G9R9
// file, so pack.bin's lightmap_scale serves all; HDR ASTC's largest, 65504, is above E5B9G9R9's 65408).
Ktx2Image blockLightmap(const formats::FormatRow& row, const BakeSetImage& image, float inverse_scale) {
    if (row.codec != formats::TexelCodec::kAstcHdr)
        throw std::logic_error(std::string("blockLightmap: no encoder for ") + row.vk_name);
    return {Ktx2Format(row.vk_format), uint32_t(image.width), uint32_t(image.height),
            encodeAstcLightmap(image, inverse_scale, kAstcBakeQuality, 0, row.block_side)};
}

Ktx2Image floatImage(const BakeSetImage& image) {
    Ktx2Image out{Ktx2Format::kR32g32b32a32Sfloat, uint32_t(image.width), uint32_t(image.height), {}};
    out.texels.resize(image.rgba.size() * 4);
    std::memcpy(out.texels.data(), image.rgba.data(), out.texels.size());
    return out;
}

// The pack's manifest: the bake set's, but for its statistics (this run's rays and seconds) zeroed, so that two
// bakes of the same inputs, or a bake and a merge, write the same pack byte for byte.
std::string packManifestText(BakeSetManifest manifest) {
    manifest.statistics = BakeSetStatistics{};
    return bakeSetManifestJson(manifest);
}

// Each file of the pack, written into the staging folder but named in messages by its place in the pack the
// user asked for (the temporary folder is an implementation detail).
class PackFiles {
public:
    PackFiles(std::string staging_folder, std::string pack_folder)
        : staging_folder_(std::move(staging_folder)), pack_folder_(std::move(pack_folder)) {}
    uint64_t write(const std::string& name, const std::vector<uint8_t>& bytes) {
        const std::string staged = staging_folder_ + "/" + name;
        try {
            writeBytesAtomically(staged, bytes.data(), bytes.size());
        } catch (const std::exception& error) {
            std::string message = error.what();
            for (size_t at = message.find(staging_folder_); at != std::string::npos;
                 at = message.find(staging_folder_, at + pack_folder_.size()))
                message.replace(at, staging_folder_.size(), pack_folder_);
            throw std::runtime_error(message);
        }
        bytes_ += bytes.size();
        return bytes.size();
    }
    uint64_t writeKtx2(const std::string& name, const Ktx2Image& image) { return write(name, encodeKtx2(image)); }
    uint64_t bytes() const { return bytes_; }

private:
    std::string staging_folder_;
    std::string pack_folder_;
    uint64_t bytes_ = 0;
};

// Where a pack is written before it is renamed into place: a fresh sibling of the pack's folder (same file
// system, so the rename is atomic), removed again unless committed. The old pack, manifest and all, stays whole
// until the new one is complete.
class PackStaging {
public:
    explicit PackStaging(const std::string& pack_folder) : shown_(pack_folder) {
        std::error_code error;
        fs::path target = fs::weakly_canonical(fs::absolute(pack_folder), error);
        if (error) target = fs::absolute(pack_folder).lexically_normal();
        if (target.has_relative_path() && target.filename().empty()) target = target.parent_path();
        target_ = target;
        fs::create_directories(target_.parent_path(), error);
        if (error) throw InputError(shown_, "-o", "cannot create the folder: " + error.message());
        static std::atomic<unsigned> counter{0};
        const std::string tag = ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
        staging_ = target_.parent_path() / ("." + target_.filename().string() + tag);
        old_ = target_.parent_path() / ("." + target_.filename().string() + ".old" + tag);
        if (!fs::create_directory(staging_, error) || error)
            throw InputError(shown_, "-o", "cannot create the folder: " + (error ? error.message() : "it exists"));
    }
    ~PackStaging() {
        std::error_code ignored;
        if (!committed_) fs::remove_all(staging_, ignored);
    }
    PackStaging(const PackStaging&) = delete;
    PackStaging& operator=(const PackStaging&) = delete;

    std::string folder() const { return staging_.string(); }

    /// Puts the staged pack in the pack's place: a new name is renamed onto; an existing folder (a previous pack,
    /// an empty folder) is swapped with it in one step where the system can (Linux's RENAME_EXCHANGE), else moved
    /// aside first and put back if the second rename fails; then the old pack is removed.
    void commit() {
        std::error_code error;
        if (!fs::exists(target_, error)) {
            fs::rename(staging_, target_, error);
            if (error) throw std::runtime_error(shown_ + ": cannot rename the written pack into place: " + error.message());
            committed_ = true;
            return;
        }
#ifdef RENAME_EXCHANGE
        if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
            committed_ = true;
            fs::remove_all(staging_, error);  // now the old pack
            return;
        }
#endif
        fs::rename(target_, old_, error);
        if (error) throw std::runtime_error(shown_ + ": cannot move the old pack aside: " + error.message());
        fs::rename(staging_, target_, error);
        if (error) {
            std::error_code ignored;
            fs::rename(old_, target_, ignored);
            throw std::runtime_error(shown_ + ": cannot rename the written pack into place: " + error.message());
        }
        committed_ = true;
        fs::remove_all(old_, error);
    }

private:
    std::string shown_;
    fs::path target_, staging_, old_;
    bool committed_ = false;
};

// The pack may not be, hold or lie inside an input of the set's bake or another bake set or pack
// (gusuku_bake/output_guard.h); the set's own BAKESET/pack and a previous pack are its to replace.
void guardPackFolder(const std::string& bake_set_folder, const BakeSetManifest& manifest,
                     const std::string& pack_folder, bool named_by_user) {
    OutputRequest request;
    request.output = pack_folder;
    request.field = named_by_user ? "-o" : "";
    request.command = "pack";
    request.kind = OutputKind::kRuntimePack;
    for (const BakeSetInput& input : manifest.inputs)
        request.inputs.push_back(resolveBakeSetInputPath(bake_set_folder, manifest, input.path));
    request.read_sets = {bake_set_folder};
    request.packed_set = bake_set_folder;
    refuseUnsafeOutput(request);
}

}  // namespace

RuntimePackReport writeRuntimePack(const std::string& bake_set_folder, const std::string& pack_folder,
                                   PackTextures textures) {
    const BakeSetData bake_set = loadBakeSet(bake_set_folder);
    RuntimePackReport report;
    report.folder = pack_folder.empty() ? bake_set_folder + "/" + kRuntimePackFolder : pack_folder;
    guardPackFolder(bake_set_folder, bake_set.manifest, report.folder, !pack_folder.empty());
    PackStaging staging(report.folder);
    PackFiles files(staging.folder(), report.folder);

    report.lightmap_scale = lightmapScaleOf(bake_set);
    PackGeometry geometry{report.lightmap_scale, bake_set.building, bake_set.occluder};
    const std::vector<float> coverage_alpha = textureCoverageAlphas(bake_set.building);
    for (size_t index = 0; index < geometry.building.textures.size(); ++index) {
        BakeSetTexture& texture = geometry.building.textures[index];
        const std::string name = "texture_" + std::to_string(index);
        if (textures != PackTextures::kAstc)
            report.texture_bytes += files.writeKtx2(name + ".ktx2", {Ktx2Format::kR8g8b8a8Srgb, uint32_t(texture.width),
                                                                     uint32_t(texture.height), texture.rgba8});
        if (textures != PackTextures::kRgba8) {
            const auto encode_start = std::chrono::steady_clock::now();
            const Ktx2Image astc = encodeAstcTexture(texture, coverage_alpha[index]);
            report.astc_encode_seconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - encode_start).count();
            report.astc_texture_bytes += files.writeKtx2(name + "_astc.ktx2", astc);
        }
        texture.rgba8.clear();  // pack.bin holds the sides; the texels are the KTX2's
    }
    files.write("pack.bin", encodePackGeometry(geometry));

    const BakeSetManifest& manifest = bake_set.manifest;
    files.writeKtx2(packName(manifest.ground_grid.geometry), floatImage(bake_set.ground_geometry));
    if (!manifest.ground_grid.albedo.empty())
        files.writeKtx2(packName(manifest.ground_grid.albedo), floatImage(bake_set.ground_albedo));
    if (!manifest.building.sun_horizon.empty())  // the bake set's own KTX2 bytes
        files.write(packName(manifest.building.sun_horizon), encodeSunHorizonKtx2(bake_set.building_sun_horizon));
    for (size_t slot = 0; slot < bake_set.slots.size(); ++slot) {
        const BakeSetSlot& entry = manifest.slots[slot];
        const BakeSetSlotImages& images = bake_set.slots[slot];
        report.lightmap_bytes +=
            files.writeKtx2(packName(entry.building_irradiance),
                            sharedExponentLightmap(images.building, 1.0f / report.lightmap_scale));
        files.writeKtx2(lightmapCompanionName(entry.building_irradiance, "_valid"), validityMask(images.building));
        for (const formats::FormatRow& row : formats::kFormatRows) {
            if (row.pack_suffix == nullptr) continue;
            const auto encode_start = std::chrono::steady_clock::now();
            const Ktx2Image blocks = blockLightmap(row, images.building, 1.0f / report.lightmap_scale);
            report.astc_encode_seconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - encode_start).count();
            report.block_lightmap_bytes[row.vk_format] +=
                files.writeKtx2(lightmapCompanionName(entry.building_irradiance, row.pack_suffix), blocks);
        }
        files.writeKtx2(packName(entry.ground_irradiance_with_building), floatImage(images.ground_with));
        files.writeKtx2(packName(entry.ground_irradiance_without_building), floatImage(images.ground_without));
    }
    const std::string manifest_text = packManifestText(manifest);
    files.write("manifest.json", std::vector<uint8_t>(manifest_text.begin(), manifest_text.end()));
    staging.commit();
    report.bytes = files.bytes();
    return report;
}

bool runtimePackIsUpToDate(const std::string& bake_set_folder) {
    const std::string packed = bake_set_folder + "/" + kRuntimePackFolder + "/manifest.json";
    if (!fs::exists(packed)) return false;
    try {
        const BakeSetManifest manifest = readBakeSetManifest(bake_set_folder + "/manifest.json");
        // A pack written before the ASTC lightmaps or textures has none: writing it again adds them. (A
        // building without textures has no texture_0 of either kind.)
        const std::string pack = bake_set_folder + "/" + kRuntimePackFolder + "/";
        for (const BakeSetSlot& slot : manifest.slots)
            for (const formats::FormatRow& row : formats::kFormatRows)
                if (row.pack_suffix != nullptr &&
                    !fs::exists(pack + lightmapCompanionName(slot.building_irradiance, row.pack_suffix)))
                    return false;
        if (fs::exists(pack + "texture_0.ktx2") && !fs::exists(pack + "texture_0_astc.ktx2")) return false;
        return readWholeFile(packed) == packManifestText(manifest);
    } catch (const std::exception&) {
        return false;
    }
}

std::string blockLightmapSummary(const RuntimePackReport& report) {
    std::string text;
    for (const formats::FormatRow& row : formats::kFormatRows) {
        const auto found = report.block_lightmap_bytes.find(row.vk_format);
        if (row.pack_suffix == nullptr || found == report.block_lightmap_bytes.end()) continue;
        char part[96];
        std::snprintf(part, sizeof part, "%s%s %.2f MiB", text.empty() ? "" : ", ", row.name,
                      double(found->second) / 1048576.0);
        text += part;
    }
    return text;
}

}  // namespace gusuku::bake

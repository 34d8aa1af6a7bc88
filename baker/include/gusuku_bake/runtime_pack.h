#pragma once
// The runtime pack (docs/bakeset.md, "The runtime pack"): BAKESET/pack/, what a phone app ships and
// gusuku_loader's gusuku_bakeset_load_pack reads with the C++ standard library alone. Written by `gusuku-bake
// bake` after the bake set's manifest, from the finished bake set (so it holds exactly what loadBakeSet reads).

#include <cstdint>
#include <map>
#include <string>

namespace gusuku::bake {

/// The pack's folder inside a bake set: "pack".
inline constexpr const char* kRuntimePackFolder = "pack";

/// Which kinds of base-colour texture files the pack holds (docs/bakeset.md, "The runtime pack").
enum class PackTextures {
    kBoth,   ///< texture_<n>.ktx2 (RGBA8) and texture_<n>_astc.ktx2 (ASTC 6x6 chains): every device (the default)
    kAstc,   ///< the blocks alone: a phone's pack (8x smaller textures), drawn only where ASTC LDR is sampled
    kRgba8,  ///< the RGBA8 alone: a desktop's pack (no astcenc time)
};

struct RuntimePackReport {
    std::string folder;     ///< BAKESET/pack
    uint64_t bytes = 0;     ///< all its files
    uint64_t lightmap_bytes = 0;  ///< its building_<slot>.ktx2 files (E5B9G9R9)
    /// Its lightmap block files, by the format row's vk_format (gusuku/formats/format_table.h: each lightmap row
    /// with a pack_suffix: building_<slot><suffix>.ktx2, as building_<slot>_astc.ktx2 for ASTC 4x4 HDR).
    std::map<uint32_t, uint64_t> block_lightmap_bytes;
    uint64_t texture_bytes = 0;        ///< its texture_<n>.ktx2 files (RGBA8, level 0)
    uint64_t astc_texture_bytes = 0;   ///< its texture_<n>_astc.ktx2 files (ASTC 6x6 sRGB, full mip chains)
    double astc_encode_seconds = 0.0;  ///< wall time astcenc took for all slots and textures
    float lightmap_scale = 1.0f;  ///< pack.bin's lightmap_scale
};

/// Loads the bake set in `bake_set_folder` (loadBakeSet: complete and checked, or InputError) and writes its pack
/// into pack_folder (empty: bake_set_folder/pack; `gusuku-bake pack BAKESET -o DIR` writes it elsewhere, as for
/// a bake set one may not write into). Before anything is written the output guard (gusuku_bake/output_guard.h)
/// refuses a folder that is, holds or lies inside an input of the set's bake, a bake set (the packed one
/// included) or another pack, or an existing folder that holds something else than a pack; the set's own
/// BAKESET/pack and a previous pack are replaced. The pack is written whole into a temporary sibling folder
/// (the manifest last: the set's with its statistics zeroed, so the same inputs give the same pack byte for
/// byte) and renamed into place, so any failure, a full disk included, leaves the old pack as it was, manifest
/// and all. A partial set (loadBakeSet refuses it) has no pack. Throws InputError naming the bake set's file
/// and field or the refused folder, or std::runtime_error on a write failure naming the pack's file.
/// `textures` chooses the texture files; the folder holds no other kind's files afterwards.
RuntimePackReport writeRuntimePack(const std::string& bake_set_folder, const std::string& pack_folder = "",
                                   PackTextures textures = PackTextures::kBoth);

/// True when bake_set_folder/pack/manifest.json is the pack manifest of bake_set_folder/manifest.json.
bool runtimePackIsUpToDate(const std::string& bake_set_folder);

/// "astc 4x4 hdr 0.25 MiB, ...": the report's lightmap block files, each by its row's name, in the format table's
/// order, for the pack line gusuku-bake prints.
std::string blockLightmapSummary(const RuntimePackReport& report);

}  // namespace gusuku::bake

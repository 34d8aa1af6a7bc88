#pragma once
// Every pixel format the project stores or draws, one constexpr row each (docs/runtime.md, "Lightmap formats"):
// its Vulkan format (which is also its KTX2 vkFormat), block size and bytes, how its texels are encoded and
// decoded, what a device must offer to sample it, its C enum value and its name in options and messages. The KTX2
// writer and reader, the GPU upload, the runtime's format choice, the pack writer and loader, the baker's encoders
// and the C mirror read the row; none keeps its own switch. Adding a lightmap format is a row here and its
// enumerators in runtime.h (LightmapFormat) and gusuku.h (gusuku_lightmap_format); test_format_table walks the rows.
//
// Header only and without Vulkan's headers, so that every library (the file formats, the GPU layer, the runtime,
// the baker, the tools) reads the same rows; the runtime checks the feature bits against Vulkan's
// (lightmap_format_choice.cpp).

#include <cstdint>
#include <cstring>

namespace gusuku::formats {

/// What a format holds.
enum class FormatFamily {
    kData,      ///< the pack's other images: validity masks, the ground's float terms
    kLightmap,  ///< the building's irradiance (RuntimeOptions::lightmap_format)
    kTexture,   ///< the building's base-colour textures (RGB sRGB, A linear)
};

/// How texels are encoded from, and decoded to, the bake's floats or RGBA8 bytes: the codec names the encoder and
/// the decoder together (the ASTC ones are astcenc's, gusuku_bake/astc_lightmap.h and astc_texture.h; the others
/// are the runtime's own: gusuku/maths/shared_exponent.h, half floats, plain copies). It also says how the KTX2
/// DFD describes the format (ktx2.cpp).
enum class TexelCodec {
    kUnorm8,          ///< one 8-bit unsigned normalised channel
    kRgba8Srgb,       ///< four 8-bit channels, RGB sRGB, A linear
    kRgba8Unorm,      ///< four 8-bit unsigned normalised channels, all linear (gusuku/formats/sun_horizon.h's codes)
    kFloat32,         ///< four 32-bit floats
    kHalfFloat,       ///< four 16-bit floats (the runtime converts at upload)
    kSharedExponent,  ///< E5B9G9R9: three 9-bit mantissas and a shared 5-bit exponent
    kAstcHdr,         ///< ASTC blocks, profile HDR RGB with LDR alpha (astcenc ASTCENC_PRF_HDR_RGB_LDR_A)
    kAstcLdrSrgb,     ///< ASTC blocks, profile LDR sRGB (astcenc ASTCENC_PRF_LDR_SRGB)
};

/// The device feature an app must enable before the runtime may sample the format (RuntimeOptions).
enum class DeviceFeature {
    kCore,     ///< none: every Vulkan device samples it (its format features are still queried)
    kAstcHdr,  ///< textureCompressionASTC_HDR (RuntimeOptions::texture_compression_astc_hdr)
    kAstcLdr,  ///< textureCompressionASTC_LDR (RuntimeOptions::texture_compression_astc_ldr)
};

/// Vulkan's VkFormatFeatureFlagBits the rows name (the values are Vulkan's; lightmap_format_choice.cpp asserts so).
inline constexpr uint32_t kFeatureSampledImage = 0x00000001u;        ///< VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT
inline constexpr uint32_t kFeatureTransferDst = 0x00008000u;         ///< VK_FORMAT_FEATURE_TRANSFER_DST_BIT
inline constexpr uint32_t kFeatureFilterLinear = 0x00001000u;        ///< ..._SAMPLED_IMAGE_FILTER_LINEAR_BIT
/// What the runtime needs of a format it uploads and samples bilinearly (optimal tiling).
inline constexpr uint32_t kSampledFiltered = kFeatureSampledImage | kFeatureTransferDst | kFeatureFilterLinear;

/// No C enum value (the format is not a gusuku_lightmap_format).
inline constexpr int kNoCEnum = -1;

struct FormatRow {
    FormatFamily family;
    /// The name options, CLI and messages use ("e5b9g9r9", "astc 4x4 hdr").
    const char* name;
    /// The VkFormat value, which is also the KTX2 header's vkFormat.
    uint32_t vk_format;
    /// "VK_FORMAT_E5B9G9R9_UFLOAT_PACK32" and so on.
    const char* vk_name;
    /// Texels a side of a block (1 for the texel formats).
    uint32_t block_side;
    /// Bytes a block (a texel for the texel formats).
    uint32_t block_bytes;
    /// The KTX2 header's typeSize: the size of the component the format is made of (1 for block formats).
    uint32_t ktx2_type_size;
    TexelCodec codec;
    DeviceFeature feature;
    /// The VkFormatFeatureFlags the runtime needs of it with optimal tiling (0: the runtime never samples it).
    uint32_t format_features;
    /// The LightmapFormat / gusuku_lightmap_format value (kNoCEnum for the other families).
    int c_enum;
    /// A lightmap format the runtime pack carries: the file each slot's blocks are in is the slot's lightmap
    /// (building_<slot>.ktx2) with this before ".ktx2" (docs/bakeset.md, "The runtime pack"); nullptr: not in
    /// the pack (the runtime converts the E5B9G9R9 file, or the format is the pack's own E5B9G9R9).
    const char* pack_suffix;
    /// RuntimeOptions::lightmap_format kAuto's preference: the lowest nonzero rank the device, the app's
    /// features and the bake set allow; 0: chosen only when asked for.
    uint32_t auto_rank;
};

// VkFormat values (Vulkan's vulkan_core.h).
inline constexpr uint32_t kVkR8Unorm = 9, kVkR8g8b8a8Unorm = 37, kVkR8g8b8a8Srgb = 43, kVkR16g16b16a16Sfloat = 97,
                          kVkR32g32b32a32Sfloat = 109, kVkE5b9g9r9Ufloat = 123, kVkAstc6x6Srgb = 166,
                          kVkAstc4x4Sfloat = 1000066000, kVkAstc6x6Sfloat = 1000066004;

/// Every format, one row each. The lightmap rows' c_enum values are LightmapFormat's (runtime.h) and
/// gusuku_lightmap_format's (gusuku.h); LightmapFormat::kAuto (4) is no format and has no row.
inline constexpr FormatRow kFormatRows[] = {
    // family, name, vk_format, vk_name, block side, block bytes, KTX2 typeSize, codec, feature, features,
    // C enum, pack suffix, auto rank
    {FormatFamily::kData, "r8", kVkR8Unorm, "VK_FORMAT_R8_UNORM", 1, 1, 1, TexelCodec::kUnorm8,
     DeviceFeature::kCore, 0, kNoCEnum, nullptr, 0},
    {FormatFamily::kData, "rgba32f data", kVkR32g32b32a32Sfloat, "VK_FORMAT_R32G32B32A32_SFLOAT", 1, 16, 4,
     TexelCodec::kFloat32, DeviceFeature::kCore, 0, kNoCEnum, nullptr, 0},
    // The building's sun horizons (sun_horizon.h): eight horizon codes a texel in two layers, sampled by gathers.
    {FormatFamily::kData, "rgba8 data", kVkR8g8b8a8Unorm, "VK_FORMAT_R8G8B8A8_UNORM", 1, 4, 1,
     TexelCodec::kRgba8Unorm, DeviceFeature::kCore, kFeatureSampledImage | kFeatureTransferDst, kNoCEnum, nullptr,
     0},

    {FormatFamily::kLightmap, "e5b9g9r9", kVkE5b9g9r9Ufloat, "VK_FORMAT_E5B9G9R9_UFLOAT_PACK32", 1, 4, 4,
     TexelCodec::kSharedExponent, DeviceFeature::kCore, kSampledFiltered, 0, nullptr, 2},
    {FormatFamily::kLightmap, "rgba16f", kVkR16g16b16a16Sfloat, "VK_FORMAT_R16G16B16A16_SFLOAT", 1, 8, 2,
     TexelCodec::kHalfFloat, DeviceFeature::kCore, kSampledFiltered, 1, nullptr, 0},
    {FormatFamily::kLightmap, "rgba32f", kVkR32g32b32a32Sfloat, "VK_FORMAT_R32G32B32A32_SFLOAT", 1, 16, 4,
     TexelCodec::kFloat32, DeviceFeature::kCore, kSampledFiltered, 2, nullptr, 0},
    {FormatFamily::kLightmap, "astc 4x4 hdr", kVkAstc4x4Sfloat, "VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK", 4, 16, 1,
     TexelCodec::kAstcHdr, DeviceFeature::kAstcHdr, kSampledFiltered, 3, "_astc", 1},
    {FormatFamily::kLightmap, "astc 6x6 hdr", kVkAstc6x6Sfloat, "VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK", 6, 16, 1,
     TexelCodec::kAstcHdr, DeviceFeature::kAstcHdr, kSampledFiltered, 5, "_astc6x6", 0},

    {FormatFamily::kTexture, "rgba8", kVkR8g8b8a8Srgb, "VK_FORMAT_R8G8B8A8_SRGB", 1, 4, 1, TexelCodec::kRgba8Srgb,
     DeviceFeature::kCore, kSampledFiltered, kNoCEnum, nullptr, 0},
    {FormatFamily::kTexture, "astc 6x6", kVkAstc6x6Srgb, "VK_FORMAT_ASTC_6x6_SRGB_BLOCK", 6, 16, 1,
     TexelCodec::kAstcLdrSrgb, DeviceFeature::kAstcLdr, kSampledFiltered, kNoCEnum, nullptr, 0},
};

/// Whether the row's texels come in blocks (ASTC) rather than one at a time.
constexpr bool isBlockCodec(TexelCodec codec) { return codec == TexelCodec::kAstcHdr || codec == TexelCodec::kAstcLdrSrgb; }

/// The first row of `vk_format` (the data row for R32G32B32A32_SFLOAT: the KTX2 description is the same), or
/// nullptr.
constexpr const FormatRow* findFormat(uint32_t vk_format) {
    for (const FormatRow& row : kFormatRows)
        if (row.vk_format == vk_format) return &row;
    return nullptr;
}

/// The lightmap row whose C enum value is `c_enum`, or nullptr (kAuto, or a value no row has).
constexpr const FormatRow* findLightmapFormat(int c_enum) {
    for (const FormatRow& row : kFormatRows)
        if (row.family == FormatFamily::kLightmap && row.c_enum == c_enum) return &row;
    return nullptr;
}

/// The lightmap row named `name` ("astc 6x6 hdr"), or nullptr.
inline const FormatRow* findLightmapFormatNamed(const char* name) {
    for (const FormatRow& row : kFormatRows)
        if (row.family == FormatFamily::kLightmap && std::strcmp(row.name, name) == 0) return &row;
    return nullptr;
}

/// Bytes one width x height level takes: block_bytes for every started block.
constexpr uint64_t levelBytes(const FormatRow& row, uint32_t width, uint32_t height) {
    return (uint64_t(width) + row.block_side - 1) / row.block_side *
           ((uint64_t(height) + row.block_side - 1) / row.block_side) * row.block_bytes;
}

/// The C enum value kAuto has (no row may take it).
inline constexpr int kAutoCEnum = 4;

namespace table_checks {
constexpr bool lightmapEnumsDistinct() {
    for (const FormatRow& a : kFormatRows)
        for (const FormatRow& b : kFormatRows)
            if (&a != &b && a.family == FormatFamily::kLightmap && b.family == FormatFamily::kLightmap &&
                a.c_enum == b.c_enum)
                return false;
    return true;
}
constexpr bool rowsWellFormed() {
    for (const FormatRow& row : kFormatRows) {
        if ((row.family == FormatFamily::kLightmap) != (row.c_enum >= 0) || row.c_enum == kAutoCEnum) return false;
        if (isBlockCodec(row.codec) != (row.block_side > 1) || row.block_bytes == 0) return false;
        // The runtime pack stores block formats only beside its E5B9G9R9 file.
        if (row.pack_suffix != nullptr && !(row.family == FormatFamily::kLightmap && isBlockCodec(row.codec)))
            return false;
    }
    return true;
}
}  // namespace table_checks
static_assert(table_checks::lightmapEnumsDistinct(), "two lightmap rows share a C enum value");
static_assert(table_checks::rowsWellFormed(), "a row's family, C enum, block size and pack file disagree");

}  // namespace gusuku::formats

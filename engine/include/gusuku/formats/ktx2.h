#pragma once
// KTX 2.0 containers (Khronos KTX File Format Specification 2.0, with the Khronos Data Format Specification 1.3's
// basic descriptor block) for the runtime pack (docs/bakeset.md, "The runtime pack"): one 2D image, one level or
// a full mip chain, no array layers, one face, no supercompression, in one of the few formats the pack uses (ASTC
// blocks included: the file carries them as they are; nothing here encodes or decodes ASTC). Standard library
// only, so a phone app's loader reads them without an image library.
//
// Written: the 12-byte identifier, the header, the index, a level index entry per level, the DFD (what the
// format's texels are, as libktx's vk2dfd would describe them), key/value data with KTXwriter and KTXorientation
// "rd" (row 0 at the top, as the bake set's images), then the levels' texels, the smallest first as the
// specification orders them, each at an offset aligned to lcm(texel block size, 4).
// Read: every field checked against that layout; anything else is InputError "FILE: FIELD: PROBLEM".

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gusuku {

/// VkFormat values (the library has no Vulkan headers; the values are Vulkan's). Every function here accepts
/// any format with a row in gusuku/formats/format_table.h, which says its block size, bytes and DFD; a
/// Ktx2Format(row.vk_format) needs no enumerator here (RGBA16F has none).
enum class Ktx2Format : uint32_t {
    kR8Unorm = 9,              ///< VK_FORMAT_R8_UNORM: the lightmaps' validity (0 or 255)
    kR8g8b8a8Srgb = 43,        ///< VK_FORMAT_R8G8B8A8_SRGB: base-colour textures (A linear)
    kR32g32b32a32Sfloat = 109, ///< VK_FORMAT_R32G32B32A32_SFLOAT: the ground terms, geometry and albedo
    kE5b9g9r9Ufloat = 123,     ///< VK_FORMAT_E5B9G9R9_UFLOAT_PACK32: the lightmaps (gusuku/maths/shared_exponent.h)
    /// VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK (VK_EXT_texture_compression_astc_hdr, core in Vulkan 1.3): the lightmaps
    /// for devices that sample ASTC HDR. 16 bytes a 4 x 4 block, blocks row by row from the top left.
    kAstc4x4Sfloat = 1000066000,
    /// VK_FORMAT_ASTC_6x6_SRGB_BLOCK (core; sampled where textureCompressionASTC_LDR is enabled, which every
    /// Vulkan phone GPU has): the base-colour textures for such devices, RGB sRGB and A linear. 16 bytes a 6 x 6
    /// block (3.56 bits a texel), blocks row by row from the top left.
    kAstc6x6Srgb = 166,
};

/// Whether `format` is made of blocks (ASTC) rather than texels.
bool ktx2IsBlockFormat(Ktx2Format format);
/// The side of a block of `format` in texels (1 for the texel formats).
uint32_t ktx2BlockSide(Ktx2Format format);
/// The number of levels of a full mip chain of a width x height image: floor(log2(max(width, height))) + 1.
uint32_t ktx2FullLevelCount(uint32_t width, uint32_t height);

/// "VK_FORMAT_E5B9G9R9_UFLOAT_PACK32" and so on, for messages; "VkFormat N" for any other value.
std::string ktx2FormatName(uint32_t vk_format);
/// Bytes a texel of `format` takes; for a block-compressed format, the bytes of one block.
uint32_t ktx2TexelBytes(Ktx2Format format);
/// Bytes one width x height level of `format` takes: texels times ktx2TexelBytes, or for ASTC 16 bytes for every
/// started block.
uint64_t ktx2LevelBytes(Ktx2Format format, uint32_t width, uint32_t height);

/// A decoded container: level 0's texels (ktx2LevelBytes(format, width, height) bytes, row 0 at the top; for ASTC
/// the blocks as they are), and for a mip chain levels 1 and on (element k is level k + 1, max(1, width >> (k + 1))
/// x max(1, height >> (k + 1)) texels).
struct Ktx2Image {
    Ktx2Format format = Ktx2Format::kR8Unorm;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> texels;
    std::vector<std::vector<uint8_t>> smaller_levels;  ///< empty, or all ktx2FullLevelCount - 1 of them
};

/// The file's bytes. std::invalid_argument when a side is 0, texels (or a smaller level) is not ktx2LevelBytes
/// long, or smaller_levels is neither empty nor the rest of the full chain.
std::vector<uint8_t> encodeKtx2(const Ktx2Image& image);

/// Reads a container written as encodeKtx2 writes, whose format must be `expected`; `file` names it in errors.
/// InputError(file, field, problem) for: a file shorter than its header or its parts, a wrong identifier, another
/// format, a typeSize, depth, layer, face or level count or supercompression other than written, a DFD that does
/// not describe the format, key/value data that does not parse or lacks KTXorientation "rd" (a KTX key
/// the specification does not define, as one that lost its NUL reads, or a KTX text value without its NUL), a
/// level outside the file, misaligned, or whose
/// byte length is not width x height texels. Never reads outside `bytes`; allocates at most `size` bytes.
/// One level only: a mip chain is refused at levelCount.
Ktx2Image decodeKtx2(const uint8_t* bytes, size_t size, const std::string& file, Ktx2Format expected);

/// As decodeKtx2, for a container that holds a full mip chain (levelCount ktx2FullLevelCount of its sides), each
/// level checked as level 0 is, and the levels laid out smallest first without overlap; the result's
/// smaller_levels hold levels 1 and on.
Ktx2Image decodeKtx2MipChain(const uint8_t* bytes, size_t size, const std::string& file, Ktx2Format expected);

}  // namespace gusuku

#pragma once
// ASTC HDR lightmaps (docs/runtime.md, "Lightmap formats"): the bake encodes each slot's lightmap with Arm's
// astcenc (Debian's libastcenc-dev) into the runtime pack, once for each lightmap row of the format table whose
// codec is kAstcHdr (gusuku/formats/format_table.h, with its block side: 4x4 is 1 byte a texel), and a device that samples
// ASTC HDR draws the blocks as they are (against E5B9G9R9's 4 bytes). The decoder is for the tools and tests,
// which measure what the blocks cost on a device that lavapipe is not; the runtime and the pack loader never link
// astcenc.

#include <cstdint>
#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::bake {

/// astcenc's quality the bake encodes with (its 0-100 scale; 60 is its "medium" preset): measured in
/// docs/runtime.md ("Lightmap formats") for time against the composite's error.
inline constexpr float kAstcBakeQuality = 60.0f;

/// The block side of ASTC 4x4, the default of the functions below.
inline constexpr uint32_t kAstcLightmapDefaultBlockSide = 4;

/// The lightmap's RGB times `inverse_scale` as ASTC blocks of block_side x block_side texels (a format table
/// row's block_side; profile HDR RGB with LDR alpha, alpha 1: the runtime reads RGB only; validity stays in the
/// pack's _valid file), encoded on up to `threads` threads (0: the machine's). 16 bytes for each started block,
/// row by row from the top. HDR ASTC holds up to 65504 (a half float's largest); larger values are clamped.
/// std::runtime_error naming astcenc's error when it fails (a block side ASTC has not among them).
std::vector<uint8_t> encodeAstcLightmap(const BakeSetImage& lightmap, float inverse_scale,
                                        float quality = kAstcBakeQuality, unsigned threads = 0,
                                        uint32_t block_side = kAstcLightmapDefaultBlockSide);

/// The blocks of a width x height image decoded (astcenc_decompress_image) to float RGBA, row 0 at the top, as a
/// device's sampler reads them at texel centres. std::runtime_error when the blocks are not 16 bytes for each
/// started block_side x block_side block, or astcenc fails.
BakeSetImage decodeAstcLightmap(const std::vector<uint8_t>& blocks, int width, int height,
                                uint32_t block_side = kAstcLightmapDefaultBlockSide);

/// Bytes an image of width x height takes as ASTC blocks of block_side x block_side texels.
size_t astcLightmapBytes(int width, int height, uint32_t block_side = kAstcLightmapDefaultBlockSide);

}  // namespace gusuku::bake

#pragma once
// ASTC 4x4 HDR lightmaps (docs/runtime.md, "Lightmap formats"): the bake encodes each slot's lightmap with Arm's
// astcenc (Debian's libastcenc-dev) into the runtime pack, and a device that samples ASTC HDR draws the blocks as
// they are (1 byte a texel, against E5B9G9R9's 4). The decoder is for the tools and tests, which measure what the
// blocks cost on a device that lavapipe is not; the runtime and the pack loader never link astcenc.

#include <cstdint>
#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::bake {

/// astcenc's quality the bake encodes with (its 0-100 scale; 60 is its "medium" preset): measured in
/// docs/runtime.md ("Lightmap formats") for time against the composite's error.
inline constexpr float kAstcBakeQuality = 60.0f;

/// The lightmap's RGB times `inverse_scale` as ASTC 4x4 blocks (profile HDR RGB with LDR alpha, alpha 1: the
/// runtime reads RGB only; validity stays in the pack's _valid file), encoded on up to `threads` threads (0: the
/// machine's). 16 bytes for each started 4 x 4 block, row by row from the top. HDR ASTC holds up to 65504 (a half
/// float's largest); larger values are clamped. std::runtime_error naming astcenc's error when it fails.
std::vector<uint8_t> encodeAstcLightmap(const BakeSetImage& lightmap, float inverse_scale,
                                        float quality = kAstcBakeQuality, unsigned threads = 0);

/// The blocks of a width x height image decoded (astcenc_decompress_image) to float RGBA, row 0 at the top, as a
/// device's sampler reads them at texel centres. std::runtime_error when the blocks are not 16 bytes for each
/// started 4 x 4 block, or astcenc fails.
BakeSetImage decodeAstcLightmap(const std::vector<uint8_t>& blocks, int width, int height);

/// Bytes an image of width x height takes as ASTC 4x4 blocks.
size_t astcLightmapBytes(int width, int height);

}  // namespace gusuku::bake

#pragma once
// ASTC 6x6 sRGB base-colour textures (docs/runtime.md, "Textures"): the bake encodes each of the building's
// textures with Arm's astcenc (Debian's libastcenc-dev), its whole mip chain made here, into the runtime pack, and
// a device that samples ASTC LDR (every Vulkan phone GPU) draws the blocks as they are: 3.56 bits a texel against
// RGBA8's 32, and no chain to make at load (a block format cannot be blitted). The decoder is for the tools and
// tests, which measure what the blocks cost on a device that lavapipe is not; the runtime and the pack loader
// never link astcenc.

#include <cstdint>
#include <vector>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/formats/ktx2.h"

namespace gusuku::bake {

/// astcenc's quality the textures are encoded with (its 0-100 scale; 60 is its "medium" preset): measured in
/// docs/runtime.md ("Textures") for time against the composite's error.
inline constexpr float kAstcTextureQuality = 60.0f;

/// `texture` (RGBA8, RGB sRGB, A linear) and its full mip chain as ASTC 6x6 blocks (profile LDR sRGB), in a
/// Ktx2Image of format kAstc6x6Srgb whose texels are level 0's blocks and smaller_levels the rest. The chain is
/// boxFilteredSrgbMipLevels' (gusuku/maths/srgb_mip_chain.h), which the runtime makes for RGBA8 too, keeping the
/// coverage at `coverage_alpha` where it is in (0, 1] (textureCoverageAlphas). Encoded on up to `threads` threads
/// (0: the machine's). std::runtime_error naming astcenc's error when it fails, or for a texture whose rgba8 is
/// not width x height texels.
Ktx2Image encodeAstcTexture(const BakeSetTexture& texture, float coverage_alpha,
                            float quality = kAstcTextureQuality, unsigned threads = 0);

/// One level's blocks (width x height texels) decoded (astcenc_decompress_image) to RGBA8 bytes, RGB
/// sRGB-encoded as the blocks hold it, row 0 at the top: what a device's sampler reads at texel centres, before
/// its sRGB decode. std::runtime_error when the blocks are not 16 bytes for each started 6 x 6 block, or astcenc
/// fails.
std::vector<uint8_t> decodeAstcTextureLevel(const std::vector<uint8_t>& blocks, uint32_t width, uint32_t height);

}  // namespace gusuku::bake

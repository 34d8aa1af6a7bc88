#pragma once
// A base-colour texture's mip chain made on the CPU, for devices whose R8G8B8A8_SRGB cannot be blitted with
// linear filtering (GpuImage::generateMipChain makes it on the GPU elsewhere). Filtered in linear light, as an
// sRGB blit does: averaging the encoded bytes would darken every edge between light and dark texels.

#include <cstdint>
#include <vector>

namespace gusuku {

/// Levels 1 .. level_count - 1 of the mip chain of `rgba8` (width x height texels, R G B A bytes, RGB
/// sRGB-encoded, alpha linear): element k is level k + 1, max(1, width >> (k + 1)) x max(1, height >> (k + 1))
/// texels. Each texel is the area-weighted mean of the texels of level 0 its footprint covers (a box filter:
/// the 2 x 2 texels above it when sides are even), RGB decoded to linear before and encoded after, rounded to
/// the nearest byte. Each level is filtered from the level above in float, so rounding does not accumulate.
/// Empty for level_count <= 1.
std::vector<std::vector<uint8_t>> boxFilteredSrgbMipLevels(const uint8_t* rgba8, uint32_t width, uint32_t height,
                                                            uint32_t level_count);

}  // namespace gusuku

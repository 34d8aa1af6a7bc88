#pragma once
// A base-colour texture's mip chain made on the CPU, for devices whose R8G8B8A8_SRGB cannot be blitted with
// linear filtering (GpuImage::generateMipChain makes it on the GPU elsewhere). Filtered in linear light, as an
// sRGB blit does: averaging the encoded bytes would darken every edge between light and dark texels.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gusuku {

/// Levels 1 .. level_count - 1 of the mip chain of `rgba8` (width x height texels, R G B A bytes, RGB
/// sRGB-encoded, alpha linear): element k is level k + 1, max(1, width >> (k + 1)) x max(1, height >> (k + 1))
/// texels. Each texel is the area-weighted mean of the texels of level 0 its footprint covers (a box filter:
/// the 2 x 2 texels above it when sides are even), RGB decoded to linear before and encoded after, rounded to
/// the nearest byte. Each level is filtered from the level above in float, so rounding does not accumulate.
/// Empty for level_count <= 1.
///
/// `coverage_alpha` in (0, 1] (an alpha-masked material's cutoff over its base colour factor's alpha): each
/// level's alpha is then scaled (by one factor a level, the result held to 1) so that the share of its texels at
/// or above `coverage_alpha` is the nearest it can be to level 0's. A box filter alone moves that share: a
/// foliage card whose leaves cover 40 % of level 0 averages to alpha 0.4 a few levels down and vanishes under a
/// cutoff of 0.5, or goes solid if they cover 60 % (Castano 2010, "Computing alpha mipmaps"). RGB is then
/// alpha-weighted (the box filter of RGB x alpha over alpha's): the colour of the footprint's opaque part, which is
/// all a drawn pixel shows, not the holes' RGB (often black). Outside (0, 1], RGBA is the plain box filter's.
std::vector<std::vector<uint8_t>> boxFilteredSrgbMipLevels(const uint8_t* rgba8, uint32_t width, uint32_t height,
                                                            uint32_t level_count, float coverage_alpha = -1.0f);

/// Whether boxFilteredSrgbMipLevels keeps the coverage at `coverage_alpha` (it lies in (0, 1]); else its chain
/// is the plain box filter's, which a GPU blit makes as well.
inline bool keepsAlphaCoverage(float coverage_alpha) { return coverage_alpha > 0.0f && coverage_alpha <= 1.0f; }

/// The share of the texels of `rgba8` (count texels, R G B A bytes) whose alpha is at or above `coverage_alpha`
/// (alpha byte / 255 >= coverage_alpha).
double alphaCoverage(const uint8_t* rgba8, size_t count, float coverage_alpha);

}  // namespace gusuku

#pragma once
// VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 (the Vulkan spec's "Shared Exponent" conversion, the same as OpenGL's
// GL_EXT_texture_shared_exponent): three unsigned floats with 9-bit mantissas and one 5-bit exponent (bias 15)
// in 4 bytes, bits 0-8 red, 9-17 green, 18-26 blue, 27-31 the exponent. Every Vulkan device samples and filters
// it, so it is the runtime's lightmap format and the runtime pack's (docs/bakeset.md). Standard library only.

#include <cstdint>

namespace gusuku {

/// The largest value a channel holds: (2^9 - 1) / 2^9 * 2^16 = 65408.
constexpr float kLargestSharedExponentValue = 65408.0f;

/// Packs linear RGB: each channel clamped to [0, 65408] (NaN to 0), the exponent chosen from the largest, each
/// mantissa rounded to nearest. A channel below 2^-24 of the largest becomes 0 (the format's relative precision
/// is 1/512 of the largest channel).
uint32_t packE5b9g9r9(float red, float green, float blue);

/// The exact value a packed texel holds, channel by channel (rgb[0] red).
void unpackE5b9g9r9(uint32_t packed, float rgb[3]);

}  // namespace gusuku

#pragma once
// ASTC 4x4 HDR (Arm's astcenc, Debian 12's libastcenc-dev) round trip of a lightmap, for gusuku-lightmap-formats
// to measure what the format would cost on devices that sample it (VK_EXT_texture_compression_astc_hdr): 16 bytes
// a 4 x 4 block, 1 byte a texel. Only the measuring tool uses it; the runtime and the pack do not (yet).

#include "gusuku/maths/bakeset_data.h"

namespace gusuku::bench {

/// Whether this build has astcenc (GUSUKU_HAVE_ASTCENC).
bool astcAvailable();

/// The lightmap's RGB encoded as ASTC 4x4 (profile HDR RGB, LDR alpha; quality `quality`, astcenc's 0-100 scale)
/// and decoded again, alpha kept as it was. std::runtime_error naming astcenc's error when it fails or is absent.
BakeSetImage astcRoundTrip(const BakeSetImage& lightmap, float quality);

/// Bytes the lightmap takes as ASTC 4x4 blocks: 16 per started 4 x 4 block.
size_t astcBytes(int width, int height);

}  // namespace gusuku::bench

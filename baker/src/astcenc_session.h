#pragma once
// What the baker's two ASTC encoders (astc_lightmap.cpp: 4x4 HDR lightmaps; astc_texture.cpp: 6x6 sRGB textures)
// share of astcenc's C API: its errors as exceptions, a context that frees itself, and one image's blocks
// compressed by several threads. Private to gusuku_bake.

#include <astcenc.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace gusuku::bake {

/// The texels as they are: no channel moved or replaced.
inline constexpr astcenc_swizzle kAstcIdentitySwizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};

/// Throws std::runtime_error "astcenc STEP: astcenc's message" unless `error` is ASTCENC_SUCCESS.
void checkAstcenc(astcenc_error error, const char* step);

struct AstcencContextFree {
    void operator()(astcenc_context* context) const { astcenc_context_free(context); }
};
using AstcencContext = std::unique_ptr<astcenc_context, AstcencContextFree>;

/// A context for `profile` and square blocks of `block_side` texels, at `quality` (astcenc's 0-100), for
/// `threads` threads; `alpha_weight`, when given, scales alpha's share of the error astcenc measures (its
/// cw_a_weight; none: astcenc's own choice for the profile).
AstcencContext makeAstcencContext(astcenc_profile profile, unsigned block_side, float quality, unsigned threads,
                                  unsigned flags, std::optional<float> alpha_weight = std::nullopt);

/// Compresses `image` into `blocks` (sized by the caller) on `threads` threads: astcenc splits one image's blocks
/// among the threads that call it with their own thread index. Throws if any thread's share failed. A context
/// compresses a second image only after astcenc_compress_reset.
void compressAstcImage(astcenc_context* context, astcenc_image& image, std::vector<uint8_t>& blocks,
                       unsigned threads);

/// Decompresses `blocks` into `image` on this thread alone (thread index 0). Throws if astcenc fails.
void decompressAstcImage(astcenc_context* context, const std::vector<uint8_t>& blocks, astcenc_image& image);

}  // namespace gusuku::bake

// ASTC HDR lightmaps (any square block side a format table row gives) through astcenc's C API (gusuku_bake/astc_lightmap.h).

#include "gusuku_bake/astc_lightmap.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>

#include "astcenc_session.h"

namespace gusuku::bake {
namespace {

constexpr float kLargestAstcHdrValue = 65504.0f;  // HDR endpoints are half floats

// A context for block_side x block_side blocks, profile HDR RGB with LDR alpha (the alpha is a constant 1), for
// `threads` threads.
AstcencContext makeContext(uint32_t block_side, float quality, unsigned threads, unsigned flags) {
    return makeAstcencContext(ASTCENC_PRF_HDR_RGB_LDR_A, block_side, quality, threads, flags);
}

}  // namespace

size_t astcLightmapBytes(int width, int height, uint32_t block_side) {
    const size_t side = block_side;
    return (size_t(width) + side - 1) / side * ((size_t(height) + side - 1) / side) * 16;
}

std::vector<uint8_t> encodeAstcLightmap(const BakeSetImage& lightmap, float inverse_scale, float quality,
                                        unsigned threads, uint32_t block_side) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<float> texels(lightmap.rgba.size());
    for (size_t index = 0; index < texels.size(); ++index)
        texels[index] = index % 4 == 3 ? 1.0f : std::min(lightmap.rgba[index] * inverse_scale, kLargestAstcHdrValue);
    void* slices[1] = {texels.data()};
    astcenc_image image{unsigned(lightmap.width), unsigned(lightmap.height), 1, ASTCENC_TYPE_F32, slices};
    std::vector<uint8_t> blocks(astcLightmapBytes(lightmap.width, lightmap.height, block_side));
    const AstcencContext context = makeContext(block_side, quality, threads, 0);
    compressAstcImage(context.get(), image, blocks, threads);
    return blocks;
}

BakeSetImage decodeAstcLightmap(const std::vector<uint8_t>& blocks, int width, int height, uint32_t block_side) {
    if (width <= 0 || height <= 0 || block_side == 0 || blocks.size() != astcLightmapBytes(width, height, block_side))
        throw std::runtime_error("decodeAstcLightmap: " + std::to_string(blocks.size()) + " bytes are not the " +
                                 std::to_string(block_side) + " x " + std::to_string(block_side) + " blocks of " + std::to_string(width) + " x " + std::to_string(height) + " texels");
    BakeSetImage out{width, height, std::vector<float>(size_t(width) * height * 4)};
    void* slices[1] = {out.rgba.data()};
    astcenc_image image{unsigned(width), unsigned(height), 1, ASTCENC_TYPE_F32, slices};
    const AstcencContext context = makeContext(block_side, kAstcBakeQuality, 1, ASTCENC_FLG_DECOMPRESS_ONLY);
    decompressAstcImage(context.get(), blocks, image);
    return out;
}

}  // namespace gusuku::bake

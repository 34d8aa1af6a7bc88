// ASTC 6x6 sRGB base-colour textures through astcenc's C API (gusuku_bake/astc_texture.h).

#include "gusuku_bake/astc_texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include "astcenc_session.h"
#include "gusuku/formats/format_table.h"
#include "gusuku/maths/srgb_mip_chain.h"

namespace gusuku::bake {
namespace {

// The texture row of the format table (gusuku/formats/format_table.h) the blocks are written as.
constexpr const formats::FormatRow& kTextureRow = *formats::findFormat(uint32_t(Ktx2Format::kAstc6x6Srgb));
static_assert(kTextureRow.codec == formats::TexelCodec::kAstcLdrSrgb);
constexpr unsigned kBlockSide = kTextureRow.block_side;
constexpr float kMaskedAlphaWeight = 8.0f;

// Profile LDR sRGB: astcenc decodes RGB from sRGB before it measures its error, as a sampler does before
// filtering, so the blocks are chosen for the light they show, not for the bytes. `alpha_weight` scales alpha's
// share of that error (astcenc's cw_a_weight, 1 by default).
AstcencContext makeContext(float quality, unsigned threads, unsigned flags, float alpha_weight = 1.0f) {
    return makeAstcencContext(ASTCENC_PRF_LDR_SRGB, kBlockSide, quality, threads, flags, alpha_weight);
}

// One level's RGBA8 texels as blocks, on `threads` threads; the context is reset for the next image.
std::vector<uint8_t> encodeLevel(astcenc_context* context, const std::vector<uint8_t>& rgba8, uint32_t width,
                                 uint32_t height, unsigned threads) {
    void* slices[1] = {const_cast<uint8_t*>(rgba8.data())};
    astcenc_image image{width, height, 1, ASTCENC_TYPE_U8, slices};
    std::vector<uint8_t> blocks(size_t(ktx2LevelBytes(Ktx2Format::kAstc6x6Srgb, width, height)));
    compressAstcImage(context, image, blocks, threads);
    checkAstcenc(astcenc_compress_reset(context), "reset");
    return blocks;
}

std::vector<uint8_t> decodeLevel(astcenc_context* context, const std::vector<uint8_t>& blocks, uint32_t width,
                                 uint32_t height) {
    std::vector<uint8_t> rgba8(size_t(width) * height * 4);
    void* slices[1] = {rgba8.data()};
    astcenc_image image{width, height, 1, ASTCENC_TYPE_U8, slices};
    decompressAstcImage(context, blocks, image);
    checkAstcenc(astcenc_decompress_reset(context), "reset");
    return rgba8;
}

// A masked texture's level whose blocks, decoded, keep `target` coverage at `coverage_alpha`. The RGBA8 chain
// keeps it by construction (boxFilteredSrgbMipLevels scales each level's alpha), but the blocks of a small level
// whose texels sit near the cutoff (a leaf a few texels wide) move a few codes of alpha, enough to flip many
// texels: measured on test_astc_texture's leaves, a 24^2 level at 0.47 coverage for level 0's 0.31. So the
// level's alpha is scaled once more, by the factor whose decoded blocks come nearest (bisection in its
// logarithm; coverage grows with it), when the first encoding misses by more than kCoverageTolerance.
std::vector<uint8_t> encodeMaskedLevel(astcenc_context* context, const std::vector<uint8_t>& rgba8, uint32_t width,
                                       uint32_t height, unsigned threads, float coverage_alpha, double target) {
    constexpr double kCoverageTolerance = 0.01;
    const size_t count = size_t(width) * height;
    auto encodeScaled = [&](double scale, double& coverage) {
        std::vector<uint8_t> scaled = rgba8;
        for (size_t texel = 0; texel < count; ++texel)
            scaled[texel * 4 + 3] = uint8_t(std::min(255.0, std::round(rgba8[texel * 4 + 3] * scale)));
        std::vector<uint8_t> blocks = encodeLevel(context, scaled, width, height, threads);
        const std::vector<uint8_t> decoded = decodeLevel(context, blocks, width, height);
        coverage = alphaCoverage(decoded.data(), count, coverage_alpha);
        return blocks;
    };
    double coverage = 0.0;
    std::vector<uint8_t> best = encodeScaled(1.0, coverage);
    double best_miss = std::abs(coverage - target);
    double low = -2.0, high = 2.0;  // log2 of the scale
    for (int step = 0; step < 8 && best_miss > kCoverageTolerance; ++step) {
        const double middle = 0.5 * (low + high);
        std::vector<uint8_t> blocks = encodeScaled(std::exp2(middle), coverage);
        if (std::abs(coverage - target) < best_miss) {
            best_miss = std::abs(coverage - target);
            best = std::move(blocks);
        }
        (coverage < target ? low : high) = middle;
    }
    return best;
}

}  // namespace

Ktx2Image encodeAstcTexture(const BakeSetTexture& texture, float coverage_alpha, float quality, unsigned threads) {
    const uint32_t width = uint32_t(texture.width), height = uint32_t(texture.height);
    if (texture.width <= 0 || texture.height <= 0 || texture.rgba8.size() != size_t(width) * height * 4)
        throw std::runtime_error("encodeAstcTexture: the texture's rgba8 is not its " + std::to_string(texture.width) +
                                 " x " + std::to_string(texture.height) + " texels");
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    // A masked texture's alpha decides which texels exist: near the cutoff a few codes of alpha error flip a
    // texel in or out, so alpha weighs more than colour there (kMaskedAlphaWeight, test_astc_texture).
    const bool masked = keepsAlphaCoverage(coverage_alpha);
    const AstcencContext context = makeContext(quality, threads, 0, masked ? kMaskedAlphaWeight : 1.0f);
    const uint32_t level_count = ktx2FullLevelCount(width, height);
    const std::vector<std::vector<uint8_t>> smaller =
        boxFilteredSrgbMipLevels(texture.rgba8.data(), width, height, level_count, coverage_alpha);
    const double target = masked ? alphaCoverage(texture.rgba8.data(), size_t(width) * height, coverage_alpha) : 0.0;
    Ktx2Image out{Ktx2Format::kAstc6x6Srgb, width, height, {}, {}};
    for (uint32_t level = 0; level < level_count; ++level) {
        const std::vector<uint8_t>& texels = level == 0 ? texture.rgba8 : smaller[level - 1];
        const uint32_t level_width = std::max(1u, width >> level), level_height = std::max(1u, height >> level);
        std::vector<uint8_t> blocks =
            masked ? encodeMaskedLevel(context.get(), texels, level_width, level_height, threads, coverage_alpha, target)
                   : encodeLevel(context.get(), texels, level_width, level_height, threads);
        if (level == 0) out.texels = std::move(blocks);
        else out.smaller_levels.push_back(std::move(blocks));
    }
    return out;
}

std::vector<uint8_t> decodeAstcTextureLevel(const std::vector<uint8_t>& blocks, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0 || blocks.size() != ktx2LevelBytes(Ktx2Format::kAstc6x6Srgb, width, height))
        throw std::runtime_error("decodeAstcTextureLevel: " + std::to_string(blocks.size()) + " bytes are not the 6 x 6 "
                                 "blocks of " + std::to_string(width) + " x " + std::to_string(height) + " texels");
    std::vector<uint8_t> rgba8(size_t(width) * height * 4);
    void* slices[1] = {rgba8.data()};
    astcenc_image image{width, height, 1, ASTCENC_TYPE_U8, slices};
    const AstcencContext context = makeContext(kAstcTextureQuality, 1, ASTCENC_FLG_DECOMPRESS_ONLY);
    decompressAstcImage(context.get(), blocks, image);
    return rgba8;
}

}  // namespace gusuku::bake

// The bake's ASTC 6x6 sRGB base-colour textures (gusuku_bake/astc_texture.h), decoded by astcenc (independent of
// the encoder's choices) against the RGBA8 chain the runtime makes for the same texture (boxFilteredSrgbMipLevels):
// every level within ASTC 6x6's error on a photograph-like texture, and an alpha-masked texture's chain keeping
// its coverage at the cutoff, which a plain box filter would lose.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/formats/ktx2.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku_bake/astc_texture.h"

namespace gusuku::bake {
namespace {

// Smooth shading, a fine sinusoid and hard-edged stripes: the mix of a stone or wood photograph.
BakeSetTexture photographLike(int width, int height) {
    BakeSetTexture texture{width, height, std::vector<uint8_t>(size_t(width) * height * 4), {}};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double shade = 0.5 + 0.3 * std::sin(x * 0.05) * std::cos(y * 0.07) + 0.1 * std::sin(x * 0.9 + y * 0.4);
            const bool joint = (x / 17 + y / 11) % 5 == 0;
            uint8_t* texel = &texture.rgba8[(size_t(y) * width + x) * 4];
            const double value = joint ? 0.15 : shade;
            texel[0] = uint8_t(std::lround(255.0 * std::clamp(value * 1.1, 0.0, 1.0)));
            texel[1] = uint8_t(std::lround(255.0 * std::clamp(value * 0.9, 0.0, 1.0)));
            texel[2] = uint8_t(std::lround(255.0 * std::clamp(value * 0.7, 0.0, 1.0)));
            texel[3] = 255;
        }
    return texture;
}

// Leaves: discs of alpha 1 on alpha 0 covering about 40 % of the card, soft at their rims.
BakeSetTexture leaves(int side) {
    BakeSetTexture texture{side, side, std::vector<uint8_t>(size_t(side) * side * 4), {}};
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const double cx = std::fmod(x, 24.0) - 12.0, cy = std::fmod(y + (x / 24) * 7, 24.0) - 12.0;
            const double radius = std::sqrt(cx * cx + cy * cy);
            uint8_t* texel = &texture.rgba8[(size_t(y) * side + x) * 4];
            texel[0] = 60;
            texel[1] = uint8_t(120 + (x * 3 + y) % 60);
            texel[2] = 40;
            texel[3] = uint8_t(std::lround(255.0 * std::clamp((8.5 - radius) / 2.0, 0.0, 1.0)));
        }
    return texture;
}

uint32_t side(uint32_t base, uint32_t level) { return std::max(1u, base >> level); }

// Mean absolute difference in sRGB codes over RGB.
double meanCodeError(const std::vector<uint8_t>& decoded, const std::vector<uint8_t>& reference) {
    double sum = 0.0;
    for (size_t index = 0; index < reference.size(); ++index)
        if (index % 4 != 3) sum += std::abs(int(decoded[index]) - int(reference[index]));
    return sum / double(reference.size() / 4 * 3);
}

TEST(AstcTexture, EveryLevelDecodesToTheRuntimesChainWithinAstc6x6sError) {
    const BakeSetTexture texture = photographLike(200, 120);
    const Ktx2Image astc = encodeAstcTexture(texture, -1.0f);
    EXPECT_EQ(astc.format, Ktx2Format::kAstc6x6Srgb);
    ASSERT_EQ(astc.smaller_levels.size() + 1, ktx2FullLevelCount(200, 120));  // 8 levels: 200 .. 1
    const std::vector<std::vector<uint8_t>> reference =
        boxFilteredSrgbMipLevels(texture.rgba8.data(), 200, 120, ktx2FullLevelCount(200, 120));
    for (uint32_t level = 0; level < ktx2FullLevelCount(200, 120); ++level) {
        const std::vector<uint8_t>& blocks = level == 0 ? astc.texels : astc.smaller_levels[level - 1];
        const std::vector<uint8_t>& expected = level == 0 ? texture.rgba8 : reference[level - 1];
        const std::vector<uint8_t> decoded = decodeAstcTextureLevel(blocks, side(200, level), side(120, level));
        const double error = meanCodeError(decoded, expected);
        // ASTC 6x6 keeps such a texture to a few codes (measured 2-4 on the detailed levels, less on the smooth
        // small ones); a wrong decode (channels or rows swapped, a level misplaced) is tens of codes.
        EXPECT_LT(error, 6.0) << "level " << level;
    }
}

TEST(AstcTexture, AMaskedTexturesChainKeepsItsCoverageAtTheCutoff) {
    const BakeSetTexture texture = leaves(192);
    const float cutoff = 0.5f;
    const double level0_coverage = alphaCoverage(texture.rgba8.data(), 192 * 192, cutoff);
    ASSERT_GT(level0_coverage, 0.2);
    ASSERT_LT(level0_coverage, 0.6);
    const Ktx2Image kept = encodeAstcTexture(texture, cutoff);
    const Ktx2Image plain = encodeAstcTexture(texture, -1.0f);
    double plain_drift = 0.0;
    // Down to 12 x 12 (two blocks a side): below that a leaf is a texel and one block cannot hold the pattern.
    for (uint32_t level = 0; side(192, level) >= 12; ++level) {
        const uint32_t s = side(192, level);
        const std::vector<uint8_t> decoded =
            decodeAstcTextureLevel(level == 0 ? kept.texels : kept.smaller_levels[level - 1], s, s);
        EXPECT_NEAR(alphaCoverage(decoded.data(), size_t(s) * s, cutoff), level0_coverage, 0.05) << "level " << level;
        const std::vector<uint8_t> plain_decoded =
            decodeAstcTextureLevel(level == 0 ? plain.texels : plain.smaller_levels[level - 1], s, s);
        plain_drift = std::max(plain_drift, std::abs(alphaCoverage(plain_decoded.data(), size_t(s) * s, cutoff) -
                                                     level0_coverage));
    }
    // What the coverage-keeping chain mends: the box filter alone moves the leaves' coverage (measured 0.085).
    EXPECT_GT(plain_drift, 0.06);
}

TEST(AstcTexture, BadBlocksAndTexelsAreRefused) {
    EXPECT_THROW(decodeAstcTextureLevel(std::vector<uint8_t>(16), 7, 6), std::runtime_error);  // 2 x 1 blocks
    BakeSetTexture short_texture = photographLike(12, 12);
    short_texture.rgba8.pop_back();
    EXPECT_THROW(encodeAstcTexture(short_texture, -1.0f), std::runtime_error);
}

}  // namespace
}  // namespace gusuku::bake

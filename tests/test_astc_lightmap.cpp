// The bake's ASTC 4x4 and 6x6 HDR lightmaps (gusuku_bake/astc_lightmap.h) against answers known without astcenc: a block
// of one colour is stored exactly (ASTC's constant-colour blocks hold half floats, so it decodes to the colour
// rounded to a half float), and a smooth lightmap spanning 10 stops comes back within the error HDR ASTC is known
// for at 1 byte a texel (a few per cent), including the last, partial blocks of a side that is not a multiple of 4.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "gusuku_bake/astc_lightmap.h"

namespace gusuku {
namespace {

float toHalfAndBack(float value) { return glm::unpackHalf1x16(glm::packHalf1x16(value)); }

TEST(AstcLightmap, BlocksOfOneColourDecodeToThatColourAsHalfFloats) {
    // 16 x 16 texels, each 4 x 4 block its own colour, from 0.01 to about 10 (10 stops), channels unequal.
    BakeSetImage lightmap{16, 16, std::vector<float>(16 * 16 * 4)};
    auto colourOf = [](int block_x, int block_y) {
        const float level = 0.01f * std::pow(2.0f, 0.6f * float(block_x + 4 * block_y));
        return glm::vec3(level, level * 0.7f, level * 0.31f);
    };
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const glm::vec3 colour = colourOf(x / 4, y / 4);
            float* texel = &lightmap.rgba[(size_t(y) * 16 + x) * 4];
            texel[0] = colour.r, texel[1] = colour.g, texel[2] = colour.b, texel[3] = 1.0f;
        }
    const std::vector<uint8_t> blocks = bake::encodeAstcLightmap(lightmap, 1.0f);
    ASSERT_EQ(blocks.size(), 16u * 16u);  // 16 blocks of 16 bytes: 1 byte a texel
    const BakeSetImage decoded = bake::decodeAstcLightmap(blocks, 16, 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const glm::vec3 colour = colourOf(x / 4, y / 4);
            const float* texel = &decoded.rgba[(size_t(y) * 16 + x) * 4];
            for (int channel = 0; channel < 3; ++channel)
                EXPECT_NEAR(texel[channel], toHalfAndBack(colour[channel]), 1e-3f * toHalfAndBack(colour[channel]))
                    << "texel " << x << ", " << y << " channel " << channel;
            EXPECT_EQ(texel[3], 1.0f);  // alpha is written as 1: the runtime reads RGB only
        }
}

// A smooth lightmap: luminance over 10 stops along x, hue turning along y; 61 x 61 so the last blocks are partial.
BakeSetImage smoothLightmap(int side) {
    BakeSetImage lightmap{side, side, std::vector<float>(size_t(side) * side * 4)};
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float level = 0.02f * std::pow(2.0f, 10.0f * float(x) / float(side - 1));
            const float turn = 3.0f * float(y) / float(side - 1);
            float* texel = &lightmap.rgba[(size_t(y) * side + x) * 4];
            texel[0] = level * (0.8f + 0.2f * std::cos(turn));
            texel[1] = level * (0.7f + 0.2f * std::sin(turn));
            texel[2] = level * (0.5f + 0.3f * std::cos(turn + 1.0f));
            texel[3] = 1.0f;
        }
    return lightmap;
}

TEST(AstcLightmap, ASmoothLightmapOverTenStopsComesBackWithinAstcsError) {
    const int side = 61;
    const BakeSetImage lightmap = smoothLightmap(side);
    const std::vector<uint8_t> blocks = bake::encodeAstcLightmap(lightmap, 1.0f);
    ASSERT_EQ(blocks.size(), bake::astcLightmapBytes(side, side));
    ASSERT_EQ(blocks.size(), 16u * 16u * 16u);  // 61 texels are 16 blocks a side
    const BakeSetImage decoded = bake::decodeAstcLightmap(blocks, side, side);
    std::vector<double> errors;  // relative to the texel's largest channel
    for (size_t texel = 0; texel < size_t(side) * side; ++texel) {
        const float* in = &lightmap.rgba[texel * 4];
        const float* out = &decoded.rgba[texel * 4];
        const float largest = std::max({in[0], in[1], in[2]});
        for (int channel = 0; channel < 3; ++channel) errors.push_back(std::abs(out[channel] - in[channel]) / largest);
    }
    std::sort(errors.begin(), errors.end());
    double mean = 0.0;
    for (double error : errors) mean += error / double(errors.size());
    std::printf("relative error: mean %.4f, p99 %.4f, worst %.4f\n", mean, errors[errors.size() * 99 / 100],
                errors.back());
    // Measured (astcenc 4.2, quality 60): mean 0.72 %, p99 3.0 %, worst 4.1 % of the texel's largest channel;
    // bounds at about twice that (a swapped channel or row order gives tens of per cent).
    EXPECT_LT(mean, 0.015);
    EXPECT_LT(errors[errors.size() * 99 / 100], 0.06);
    EXPECT_LT(errors.back(), 0.08);
}

// ASTC 6x6 HDR (the format table's kVkAstc6x6Sfloat row, block side 6): the same lightmap in 11 x 11 blocks, the
// last partial, with the larger error of 2.25x fewer bits.
TEST(AstcLightmap, ASmoothLightmapIn6x6BlocksComesBackWithinTheirLargerError) {
    const int side = 61;
    const BakeSetImage lightmap = smoothLightmap(side);
    const std::vector<uint8_t> blocks = bake::encodeAstcLightmap(lightmap, 1.0f, bake::kAstcBakeQuality, 0, 6);
    ASSERT_EQ(blocks.size(), bake::astcLightmapBytes(side, side, 6));
    ASSERT_EQ(blocks.size(), 11u * 11u * 16u);  // 61 texels are 11 blocks of 6 a side
    const BakeSetImage decoded = bake::decodeAstcLightmap(blocks, side, side, 6);
    std::vector<double> errors;  // relative to the texel's largest channel
    for (size_t texel = 0; texel < size_t(side) * side; ++texel) {
        const float* in = &lightmap.rgba[texel * 4];
        const float* out = &decoded.rgba[texel * 4];
        const float largest = std::max({in[0], in[1], in[2]});
        for (int channel = 0; channel < 3; ++channel) errors.push_back(std::abs(out[channel] - in[channel]) / largest);
        EXPECT_EQ(out[3], 1.0f);
    }
    std::sort(errors.begin(), errors.end());
    double mean = 0.0;
    for (double error : errors) mean += error / double(errors.size());
    std::printf("6x6 relative error: mean %.4f, p99 %.4f, worst %.4f\n", mean, errors[errors.size() * 99 / 100],
                errors.back());
    // Measured (astcenc 4.2, quality 60): mean 1.30 %, p99 4.9 %, worst 6.1 % of the texel's largest channel
    // (4x4: 0.72 %, 3.0 %, 4.1 %); bounds at about twice that.
    EXPECT_LT(mean, 0.026);
    EXPECT_LT(errors[errors.size() * 99 / 100], 0.10);
    EXPECT_LT(errors.back(), 0.12);
    // 4x4 blocks handed to the 6x6 decoder are refused (the byte count is another format's).
    EXPECT_THROW(bake::decodeAstcLightmap(bake::encodeAstcLightmap(lightmap, 1.0f), side, side, 6), std::runtime_error);
}

TEST(AstcLightmap, TheScaleDividesBeforeEncodingAndValuesAboveAHalfFloatAreClamped) {
    BakeSetImage lightmap{4, 4, std::vector<float>(4 * 4 * 4, 1.0f)};
    for (size_t index = 0; index < lightmap.rgba.size(); index += 4) lightmap.rgba[index] = 1.0e6f;  // red above 65504
    const BakeSetImage decoded = bake::decodeAstcLightmap(bake::encodeAstcLightmap(lightmap, 0.5f), 4, 4);
    EXPECT_NEAR(decoded.rgba[0], 65504.0f, 65504.0f * 1e-3f);  // clamped to the largest half float, not infinity
    EXPECT_NEAR(decoded.rgba[1], 0.5f, 1e-3f);                 // green 1 x 0.5
    EXPECT_THROW(bake::decodeAstcLightmap(std::vector<uint8_t>(15), 4, 4), std::runtime_error);
}

}  // namespace
}  // namespace gusuku

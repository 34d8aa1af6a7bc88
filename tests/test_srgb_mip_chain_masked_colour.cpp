// An alpha-masked texture's mip chain takes its colour from the opaque texels only (issue 44 item 3). A foliage
// card's holes hold RGB that no pixel shows (black in the shared house's leaves); averaged into the coarser levels
// unweighted they darkened the vine and the tree a few levels down, 9 % under the truth, whose pixels average the
// leaves' colour alone. Checked against the one colour every leaf has: each level's texels that hold any opacity
// must carry it, while an unmasked chain stays the plain box filter (the colour's mean with the holes, in linear
// light). CPU only.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/srgb_mip_chain.h"

namespace gusuku {
namespace {

constexpr uint32_t kSide = 64;
constexpr uint8_t kLeaf[3] = {200, 150, 90};

// Leaves: blobs of a few texels on a scattered pattern, about half the texels; holes black and transparent.
std::vector<uint8_t> leavesOverBlackHoles() {
    std::vector<uint8_t> rgba(size_t(kSide) * kSide * 4, 0);
    for (uint32_t y = 0; y < kSide; ++y)
        for (uint32_t x = 0; x < kSide; ++x) {
            const bool leaf = ((x / 3 + y / 2) % 3 != 0) && ((x * 7 + y * 5) % 11 < 6);
            if (!leaf) continue;
            uint8_t* texel = &rgba[(size_t(y) * kSide + x) * 4];
            texel[0] = kLeaf[0];
            texel[1] = kLeaf[1];
            texel[2] = kLeaf[2];
            texel[3] = 255;
        }
    return rgba;
}

TEST(SrgbMipChainMaskedColour, EveryLevelKeepsTheLeavesColourNotTheHoles) {
    const std::vector<uint8_t> texture = leavesOverBlackHoles();
    const std::vector<std::vector<uint8_t>> levels = boxFilteredSrgbMipLevels(texture.data(), kSide, kSide, 7, 0.5f);
    ASSERT_EQ(levels.size(), 6u);
    size_t checked = 0;
    for (const std::vector<uint8_t>& level : levels)
        for (size_t texel = 0; texel < level.size() / 4; ++texel) {
            if (level[texel * 4 + 3] == 0) continue;
            for (int channel = 0; channel < 3; ++channel)
                EXPECT_NEAR(level[texel * 4 + channel], kLeaf[channel], 1) << "texel " << texel << " channel " << channel;
            ++checked;
        }
    EXPECT_GT(checked, 1000u);
}

TEST(SrgbMipChainMaskedColour, AnUnmaskedChainStaysThePlainBoxFilter) {
    const std::vector<uint8_t> texture = leavesOverBlackHoles();
    const std::vector<std::vector<uint8_t>> levels = boxFilteredSrgbMipLevels(texture.data(), kSide, kSide, 7);
    // The last level (1 x 1): the linear mean over every texel, holes included.
    double linear_sum[3] = {0.0, 0.0, 0.0};
    for (size_t texel = 0; texel < size_t(kSide) * kSide; ++texel)
        for (int channel = 0; channel < 3; ++channel)
            linear_sum[channel] += srgbDecode(texture[texel * 4 + channel] / 255.0);
    for (int channel = 0; channel < 3; ++channel) {
        const double expected = 255.0 * srgbEncode(linear_sum[channel] / double(kSide * kSide));
        EXPECT_NEAR(levels.back()[channel], expected, 1.0) << "channel " << channel;
        EXPECT_LT(levels.back()[channel], kLeaf[channel] - 20) << "the holes darken an unmasked chain";
    }
}

}  // namespace
}  // namespace gusuku

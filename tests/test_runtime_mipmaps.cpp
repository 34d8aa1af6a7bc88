// Mipmapped base-colour textures on lavapipe with validation on: the mip chain's levels on the GPU (blitted, or
// box-filtered on the CPU) against this file's own box filter in linear light and against the analytic mean of a
// checkerboard; their memory; and a 1-texel checkerboard on a ground-like quad seen at a grazing angle, whose
// pixels must average to the texture's mean without the speckle that sampling level 0 alone gives there.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku/runtime/runtime.h"
#include "runtime_scene.h"
#include "synthetic_bakeset.h"

namespace gusuku {
namespace {

using runtime_detail::MipChainMaker;
using runtime_detail::uploadBaseColourTexture;
using testing::GpuTest;

// ---- Textures and an independent reference -------------------------------------------------------------------

BakeSetTexture checkerboard(int side) {
    BakeSetTexture texture{side, side, std::vector<uint8_t>(size_t(side) * side * 4, 255)};
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            if ((x + y) % 2 == 1)
                for (int channel = 0; channel < 3; ++channel) texture.rgba8[(size_t(y) * side + x) * 4 + channel] = 0;
    return texture;
}

BakeSetTexture noiseTexture(int width, int height, uint32_t seed) {
    BakeSetTexture texture{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
    std::mt19937 random(seed);
    for (uint8_t& byte : texture.rgba8) byte = uint8_t(random() % 256);
    return texture;
}

// A level in linear light (alpha as stored), and the next one by the plain 2 x 2 mean: the textbook box filter for
// even sides (and a side of 1 kept), written here without the runtime's footprint code.
struct Level {
    int width = 0, height = 0;
    std::vector<double> rgba;
};

Level linearLevelOf(const BakeSetTexture& texture) {
    Level level{texture.width, texture.height, {}};
    for (size_t index = 0; index < texture.rgba8.size(); ++index)
        level.rgba.push_back(index % 4 == 3 ? texture.rgba8[index] / 255.0 : srgbDecode(texture.rgba8[index] / 255.0));
    return level;
}

Level halvedByTwoByTwoMean(const Level& above) {
    Level level{std::max(1, above.width / 2), std::max(1, above.height / 2), {}};
    const int step_x = above.width > 1 ? 2 : 1, step_y = above.height > 1 ? 2 : 1;
    for (int y = 0; y < level.height; ++y)
        for (int x = 0; x < level.width; ++x)
            for (int channel = 0; channel < 4; ++channel) {
                double sum = 0.0;
                for (int dy = 0; dy < step_y; ++dy)
                    for (int dx = 0; dx < step_x; ++dx)
                        sum += above.rgba[(size_t(y * step_y + dy) * above.width + x * step_x + dx) * 4 + channel];
                level.rgba.push_back(sum / (step_x * step_y));
            }
    return level;
}

std::vector<uint8_t> encodedBytes(const Level& level) {
    std::vector<uint8_t> bytes;
    for (size_t index = 0; index < level.rgba.size(); ++index) {
        const double value = index % 4 == 3 ? level.rgba[index] : srgbEncode(level.rgba[index]);
        bytes.push_back(uint8_t(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)));
    }
    return bytes;
}

int largestByteDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    EXPECT_EQ(a.size(), b.size());
    int largest = 0;
    for (size_t index = 0; index < std::min(a.size(), b.size()); ++index)
        largest = std::max(largest, std::abs(int(a[index]) - int(b[index])));
    return largest;
}

// Level `level` of layer 0 of an RGBA8 image left in SHADER_READ_ONLY_OPTIMAL, read back (and left as it was).
std::vector<uint8_t> downloadLevel(const GpuDevice& gpu, const GpuImage& image, uint32_t level) {
    const uint32_t width = std::max(1u, image.description().width >> level);
    const uint32_t height = std::max(1u, image.description().height >> level);
    GpuBuffer readback(gpu, size_t(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuMemory::kHostVisible);
    GpuSubmitter submitter(gpu);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        recordImageLayoutTransition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                    VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        region.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1,
                               &region);
        recordImageLayoutTransition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                    VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_SHADER_READ_BIT,
                                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    });
    return readback.downloadVector<uint8_t>(size_t(width) * height * 4);
}

class MipChainTest : public GpuTest {};

TEST(MipChainLevels, CountGoesDownToOneTexel) {
    EXPECT_EQ(fullMipLevelCount(1, 1), 1u);
    EXPECT_EQ(fullMipLevelCount(512, 512), 10u);
    EXPECT_EQ(fullMipLevelCount(64, 32), 7u);
    EXPECT_EQ(fullMipLevelCount(5, 3), 3u);  // 5x3, 2x1, 1x1
}

TEST(MipChainLevels, CpuBoxFilterOfAnOddSideIsTheAreaWeightedMean) {
    // 3 x 3 -> 1 x 1: every texel's footprint weight is 1/9, so the one texel is the linear mean of all nine.
    const BakeSetTexture texture = noiseTexture(3, 3, 11);
    const std::vector<std::vector<uint8_t>> levels = boxFilteredSrgbMipLevels(texture.rgba8.data(), 3, 3, 2);
    ASSERT_EQ(levels.size(), 1u);
    ASSERT_EQ(levels[0].size(), 4u);
    for (int channel = 0; channel < 4; ++channel) {
        double sum = 0.0;
        for (int texel = 0; texel < 9; ++texel) {
            const double byte = texture.rgba8[texel * 4 + channel] / 255.0;
            sum += channel == 3 ? byte : srgbDecode(byte);
        }
        const double mean = sum / 9.0;
        const double expected = std::lround((channel == 3 ? mean : srgbEncode(mean)) * 255.0);
        EXPECT_EQ(levels[0][channel], expected) << "channel " << channel;
    }
}

TEST_F(MipChainTest, BlittedAndCpuChainsMatchALinearLightBoxFilter) {
    const BakeSetTexture texture = noiseTexture(64, 32, 5);
    ASSERT_TRUE(canBlitMipChain(context(), VK_FORMAT_R8G8B8A8_SRGB)) << "lavapipe blits sRGB with linear filtering";
    const GpuImage blitted = uploadBaseColourTexture(context(), texture, MipChainMaker::kGpuBlit);
    const GpuImage filtered = uploadBaseColourTexture(context(), texture, MipChainMaker::kCpuBoxFilter);
    ASSERT_EQ(blitted.description().mip_levels, 7u);
    const std::vector<std::vector<uint8_t>> cpu_levels =
        boxFilteredSrgbMipLevels(texture.rgba8.data(), 64, 32, 7);
    EXPECT_EQ(downloadLevel(context(), blitted, 0), texture.rgba8);
    Level reference = linearLevelOf(texture);
    for (uint32_t level = 1; level < 7; ++level) {
        reference = halvedByTwoByTwoMean(reference);
        const std::vector<uint8_t> expected = encodedBytes(reference);
        const std::vector<uint8_t> from_blits = downloadLevel(context(), blitted, level);
        const std::vector<uint8_t> from_cpu = downloadLevel(context(), filtered, level);
        // The blits filter each level from the one above as stored (8-bit), so rounding adds up down the chain;
        // the CPU filters in float, so only the final rounding differs from the reference.
        EXPECT_LE(largestByteDifference(from_blits, expected), 2) << "blitted level " << level;
        EXPECT_LE(largestByteDifference(from_cpu, expected), 1) << "CPU level " << level;
        EXPECT_EQ(from_cpu, cpu_levels[level - 1]) << "level " << level << " uploaded as made";
    }
}

TEST_F(MipChainTest, CheckerboardLevelsAreItsLinearMean) {
    // Black and white 1-texel squares average to 0.5 in linear light, sRGB 0.7354: byte 188 at every level below
    // 0 (averaging the encoded bytes would give 128: the darkening a gamma-space filter makes).
    const uint8_t grey = uint8_t(std::lround(srgbEncode(0.5) * 255.0));
    ASSERT_EQ(grey, 188);
    for (MipChainMaker maker : {MipChainMaker::kGpuBlit, MipChainMaker::kCpuBoxFilter}) {
        const GpuImage image = uploadBaseColourTexture(context(), checkerboard(512), maker);
        ASSERT_EQ(image.description().mip_levels, 10u);
        for (uint32_t level : {1u, 4u, 9u}) {
            const std::vector<uint8_t> texels = downloadLevel(context(), image, level);
            int largest = 0;
            for (size_t index = 0; index < texels.size(); ++index)
                largest = std::max(largest, std::abs(int(texels[index]) - (index % 4 == 3 ? 255 : grey)));
            EXPECT_LE(largest, 1) << (maker == MipChainMaker::kGpuBlit ? "blit" : "cpu") << " level " << level;
        }
    }
}

TEST_F(MipChainTest, FullChainWeighsAboutFourThirdsOfLevelZero) {
    GpuImageDescription description;
    description.width = description.height = 512;
    const GpuImage single(context(), description);
    description.mip_levels = fullMipLevelCount(512, 512);
    const GpuImage chained(context(), description);
    const double ratio = double(chained.memoryBytes()) / double(single.memoryBytes());
    EXPECT_GE(single.memoryBytes(), 512u * 512u * 4u);
    EXPECT_NEAR(ratio, 4.0 / 3.0, 0.03) << single.memoryBytes() << " -> " << chained.memoryBytes();
}

TEST_F(MipChainTest, BadMipLevelCountsAreRefused) {
    GpuImageDescription description;
    description.width = 64;
    description.height = 32;
    description.mip_levels = 8;  // 64 x 32 has 7
    EXPECT_THROW(GpuImage(context(), description), std::invalid_argument);
    description.mip_levels = 0;
    EXPECT_THROW(GpuImage(context(), description), std::invalid_argument);
    description.mip_levels = 2;
    GpuImage image(context(), description);
    const std::vector<uint8_t> wrong(64 * 32 * 4);  // level 1 is 32 x 16
    EXPECT_THROW(image.upload(wrong.data(), wrong.size(), 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 1),
                 std::invalid_argument);
    EXPECT_THROW(image.upload(wrong.data(), wrong.size(), 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 2),
                 std::invalid_argument);
}

}  // namespace
}  // namespace gusuku

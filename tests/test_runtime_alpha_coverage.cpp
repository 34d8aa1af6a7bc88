// Alpha-masked cards seen from afar (issue 20 items 1 and 2 for masked materials): a foliage-like mask whose
// leaves cover a known share of its texels must cover that share of the pixels it spans however far it is drawn.
// Two parts do that: the mip chain keeps each level's coverage at the cutoff (boxFilteredSrgbMipLevels with
// coverage_alpha), and with multisampling the building pass turns the mask's edge into alpha to coverage.
// Checked on the CPU against level 0's own count, and on lavapipe with validation on against that share: a red
// masked quad over a grey camera frame, the red in the composite over a solid quad's red. A plain box chain
// loses the leaves a few levels down (their mean alpha drops under the cutoff), so the tests fail without it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku/runtime/runtime.h"
#include "shadow_scenes.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

constexpr uint32_t kTextureSide = 256;
constexpr float kCutoff = 0.5f;

uint32_t hashed(uint32_t x, uint32_t y) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    return h ^ (h >> 15);
}

// A foliage-like mask: value noise (bilinear between random lattice values) through a steep ramp, so leaves have
// soft one-texel edges as painted cut-outs do; `threshold` sets how much of it is leaf, `cell` (texels between the
// noise's lattice points) how big a leaf is. RGB a constant red.
std::vector<uint8_t> leafTexture(float threshold, uint32_t cell) {
    std::vector<uint8_t> rgba(size_t(kTextureSide) * kTextureSide * 4);
    const uint32_t lattice = kTextureSide / cell;
    auto value = [&](uint32_t x, uint32_t y) { return float(hashed(x % lattice, y % lattice) & 0xffffu) / 65535.0f; };
    for (uint32_t y = 0; y < kTextureSide; ++y)
        for (uint32_t x = 0; x < kTextureSide; ++x) {
            const float fx = float(x) / cell, fy = float(y) / cell;
            const uint32_t x0 = uint32_t(fx), y0 = uint32_t(fy);
            const float tx = fx - float(x0), ty = fy - float(y0);
            const float noise = (1 - ty) * ((1 - tx) * value(x0, y0) + tx * value(x0 + 1, y0)) +
                                ty * ((1 - tx) * value(x0, y0 + 1) + tx * value(x0 + 1, y0 + 1));
            const float alpha = std::clamp((noise - threshold) * 12.0f + 0.5f, 0.0f, 1.0f);
            uint8_t* texel = &rgba[(size_t(y) * kTextureSide + x) * 4];
            texel[0] = 230;
            texel[1] = 20;
            texel[2] = 20;
            texel[3] = uint8_t(std::lround(alpha * 255.0f));
        }
    return rgba;
}

uint32_t levelSide(size_t level) { return std::max(1u, kTextureSide >> (level + 1)); }

TEST(AlphaCoverageMipChain, EveryLevelKeepsLevelZerosCoverageAtTheCutoff) {
    double plain_drift = 0.0;
    for (float threshold : {0.45f, 0.6f}) {
        const std::vector<uint8_t> texture = leafTexture(threshold, 8);
        const double level0 = alphaCoverage(texture.data(), size_t(kTextureSide) * kTextureSide, kCutoff);
        ASSERT_GT(level0, 0.2);
        ASSERT_LT(level0, 0.7);
        const std::vector<std::vector<uint8_t>> kept =
            boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9, kCutoff);
        const std::vector<std::vector<uint8_t>> plain =
            boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9);
        for (size_t level = 0; level < kept.size(); ++level) {
            const size_t texels = size_t(levelSide(level)) * levelSide(level);
            if (texels < 64) break;  // 8 x 8 and above: a share of fewer texels steps by more than the tolerance
            const double coverage = alphaCoverage(kept[level].data(), texels, kCutoff);
            const double plain_coverage = alphaCoverage(plain[level].data(), texels, kCutoff);
            std::printf("leaf share %.3f, level %zu: kept %.3f, box filter alone %.3f\n", level0, level + 1, coverage,
                        plain_coverage);
            EXPECT_NEAR(coverage, level0, 0.02) << "level " << level + 1;
            plain_drift = std::max(plain_drift, std::abs(plain_coverage - level0));
            // The colour is the box filter's either way.
            for (size_t byte = 0; byte < kept[level].size(); ++byte) {
                if (byte % 4 != 3) {
                    ASSERT_EQ(kept[level][byte], plain[level][byte]);
                }
            }
        }
    }
    EXPECT_GT(plain_drift, 0.2) << "the box filter alone should lose the mask's coverage (the test's teeth)";
}

TEST(AlphaCoverageMipChain, WithoutACutoffTheChainIsThePlainBoxFilter) {
    const std::vector<uint8_t> texture = leafTexture(0.5f, 8);
    EXPECT_EQ(boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9, -1.0f),
              boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9));
    EXPECT_EQ(boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9, 1.5f),
              boxFilteredSrgbMipLevels(texture.data(), kTextureSide, kTextureSide, 9));
}

constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr double kFocal = 300.0;
constexpr uint8_t kCameraCode = 128;
constexpr double kQuadHalf = 1.0, kQuadHeight = 0.5;

BakeSetData quadBakeSet(const std::vector<uint8_t>& rgba, bool masked) {
    testing::SyntheticBakeSetOptions options;
    options.grid_half_m = 6.0;
    const glm::vec3 a(-kQuadHalf, -kQuadHalf, kQuadHeight), b(kQuadHalf, -kQuadHalf, kQuadHeight),
        c(kQuadHalf, kQuadHalf, kQuadHeight), d(-kQuadHalf, kQuadHalf, kQuadHeight);
    BakeSetData data = testing::bakeSetWithBuilding({a, b, c, a, c, d}, options);
    for (size_t vertex = 0; vertex < data.building.positions.size(); ++vertex) {
        const glm::vec3& p = data.building.positions[vertex];
        data.building.uv0[vertex] = glm::vec2((p.x + kQuadHalf) / (2 * kQuadHalf), (p.y + kQuadHalf) / (2 * kQuadHalf));
    }
    BakeSetTexture texture{int(kTextureSide), int(kTextureSide), rgba};
    data.building.textures = {texture};
    data.building.materials[0].base_color_texture = 0;
    data.building.materials[0].alpha_masked = masked;
    data.building.materials[0].alpha_cutoff = kCutoff;
    return data;
}

// The mean over the quad's inner pixels (a 3-pixel margin) of the linear red over green excess, seen straight
// down from `height_m`: the grey camera frame has none, the lit red quad a fixed amount.
double redExcess(const GpuDevice& device, const BakeSetData& bake_set, double height_m, uint32_t msaa) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.msaa_samples = msaa;
    std::unique_ptr<Runtime> runtime = Runtime::open(device, bake_set, options);
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, kCameraCode);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {kFocal, kFocal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.utc_unix_seconds = testing::syntheticLocalTime(12, 0);
    frame.weather = Weather::overcast();  // no sun: the ground seen through the holes stays grey
    frame.exposure = 0.5f;
    frame.colour_match = ColourMatch::kOff;
    frame.mode = RenderMode::kProposed;
    frame.pose = CameraPose::lookingAt({0, 0, height_m}, {0, 0, 0});
    std::vector<uint8_t> pixels(camera.size());
    runtime->renderFrame(frame, pixels.data());
    const double half_pixels = kQuadHalf / (height_m - kQuadHeight) * kFocal - 3.0;
    double sum = 0.0;
    int count = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            if (std::abs(x + 0.5 - kWidth / 2.0) > half_pixels || std::abs(y + 0.5 - kHeight / 2.0) > half_pixels)
                continue;
            const uint8_t* pixel = &pixels[(size_t(y) * kWidth + x) * 4];
            sum += srgbDecode(pixel[0] / 255.0) - srgbDecode(pixel[1] / 255.0);
            ++count;
        }
    EXPECT_GT(count, 400);
    return sum / std::max(count, 1);
}

class RuntimeAlphaCoverage : public testing::GpuTest {};

// From 12 m the quad spans about 52 pixels for its 256 texels: the building pass reads level 2 or so, whose texels
// are wider than the leaves (2 texels across), so a plain box chain's mean alpha there is under the cutoff.
TEST_F(RuntimeAlphaCoverage, AFarMaskedQuadCoversItsLeafShareOfThePixels) {
    const std::vector<uint8_t> leaves = leafTexture(0.6f, 2);
    const double leaf_share = alphaCoverage(leaves.data(), size_t(kTextureSide) * kTextureSide, kCutoff);
    std::vector<uint8_t> solid = leaves;
    for (size_t texel = 3; texel < solid.size(); texel += 4) solid[texel] = 255;
    for (uint32_t msaa : {4u, 1u}) {
        for (double height : {4.0, 12.0}) {
            const double full = redExcess(context(), quadBakeSet(solid, true), height, msaa);
            const double masked = redExcess(context(), quadBakeSet(leaves, true), height, msaa);
            ASSERT_GT(full, 0.05);
            const double covered = masked / full;
            std::printf("msaa %u, %.0f m: leaf share %.3f, covered %.3f of the quad's pixels\n", msaa, height,
                        leaf_share, covered);
            // Multisampled, the coverage is the pixel's share (measured 0.338 and 0.332 of 0.324); without it each
            // pixel is all or nothing on a trilinear alpha, which loses some (0.290 and 0.259; a plain box chain
            // gave 0.159 multisampled and 0.100 without at 12 m).
            EXPECT_NEAR(covered, leaf_share, msaa > 1 ? 0.04 : 0.08) << "msaa " << msaa << ", " << height << " m";
        }
    }
}

}  // namespace
}  // namespace gusuku

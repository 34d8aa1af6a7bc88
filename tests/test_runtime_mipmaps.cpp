// Mipmapped base-colour textures on lavapipe with validation on: the mip chain's levels on the GPU (blitted, or
// box-filtered on the CPU) against this file's own box filter in linear light and against the analytic mean of a
// checkerboard; their memory; and a 1-texel checkerboard on a ground-like quad seen at a grazing angle, whose
// pixels must average to the texture's mean without the speckle that sampling level 0 alone gives there.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku/runtime/runtime.h"
#include "runtime_impl.h"
#include "runtime_scene.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

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

// ---- The checkerboard quad seen at a grazing angle -------------------------------------------------------------

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr double kFocal = 120.0;
// The quad: x in [-20, 20], y in [20, 60] m at z = 0, the 512^2 texture once across it (7.8 cm texels).
constexpr double kQuadHalfWidth = 20.0, kQuadNear = 20.0, kQuadFar = 60.0;
constexpr int kCheckerSide = 512;
// Overcast: radiance = albedo x E_ind / pi, so E_ind = pi and exposure 0.8 put a white texel at display-linear 0.8
// (below the clamp) and the checkerboard's mean at 0.4.
constexpr float kExposure = 0.8f;

const CameraPose& grazingPose() {
    static const CameraPose pose = CameraPose::lookingAt({0.0, 0.0, 1.5}, {0.0, 40.0, 0.0});
    return pose;
}

BakeSetData checkerQuadBakeSet() {
    testing::SyntheticBakeSetOptions options;
    options.indirect_irradiance = float(M_PI);
    options.ground_occluder = false;
    BakeSetData data = testing::makeSyntheticBakeSet(options);
    BakeSetMesh& mesh = data.building;
    mesh = {};
    const glm::vec3 corners[4] = {{-kQuadHalfWidth, kQuadNear, 0}, {kQuadHalfWidth, kQuadNear, 0},
                                  {kQuadHalfWidth, kQuadFar, 0}, {-kQuadHalfWidth, kQuadFar, 0}};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int corner = 0; corner < 4; ++corner) {
        mesh.positions.push_back(corners[corner]);
        mesh.normals.push_back({0, 0, 1});
        mesh.uv0.push_back(uv[corner]);
        mesh.uv1.push_back(glm::vec2(0.25f) + uv[corner] * 0.5f);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.triangle_material = {0, 0};
    mesh.materials.push_back({glm::vec4(1.0f), 0});
    mesh.textures.push_back(checkerboard(kCheckerSide));
    return data;
}

// The point of z = 0 the pixel centre (x, y)'s ray meets (the camera convention of runtime.h's CameraPose).
glm::dvec3 groundPointOf(uint32_t x, uint32_t y) {
    const glm::dvec3 ray_camera((x + 0.5 - kWidth / 2.0) / kFocal, (y + 0.5 - kHeight / 2.0) / kFocal, 1.0);
    const glm::dvec3 ray = grazingPose().camera_to_enu * ray_camera;
    if (ray.z >= 0.0) return glm::dvec3(std::numeric_limits<double>::infinity());
    return grazingPose().position_enu + ray * (-grazingPose().position_enu.z / ray.z);
}

// Pixels whose ray meets the quad at least a metre inside its edges.
std::vector<std::pair<uint32_t, uint32_t>> quadPixels() {
    std::vector<std::pair<uint32_t, uint32_t>> pixels;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::dvec3 point = groundPointOf(x, y);
            if (std::abs(point.x) < kQuadHalfWidth - 1.0 && point.y > kQuadNear + 1.0 && point.y < kQuadFar - 1.0)
                pixels.emplace_back(x, y);
        }
    return pixels;
}

struct Spread {
    double mean = 0.0, standard_deviation = 0.0;
};

Spread spreadOf(const std::vector<double>& values) {
    Spread spread;
    for (double value : values) spread.mean += value / values.size();
    double squares = 0.0;
    for (double value : values) squares += (value - spread.mean) * (value - spread.mean);
    spread.standard_deviation = std::sqrt(squares / values.size());
    return spread;
}

// What the old sampler gave at those pixels: level 0 alone, bilinear, display-linear (no GPU involved).
double levelZeroBilinear(const glm::dvec3& point) {
    const double u = (point.x + kQuadHalfWidth) / (2.0 * kQuadHalfWidth) * kCheckerSide - 0.5;
    const double v = (point.y - kQuadNear) / (kQuadFar - kQuadNear) * kCheckerSide - 0.5;
    const double u0 = std::floor(u), v0 = std::floor(v), fu = u - u0, fv = v - v0;
    auto white = [](double column, double row) { return (long(column) + long(row)) % 2 == 0 ? 1.0 : 0.0; };
    const double value = (1 - fu) * (1 - fv) * white(u0, v0) + fu * (1 - fv) * white(u0 + 1, v0) +
                         (1 - fu) * fv * white(u0, v0 + 1) + fu * fv * white(u0 + 1, v0 + 1);
    return value * kExposure;
}

class GrazingCheckerTest : public GpuTest {
protected:
    std::vector<double> renderedLinear(float max_anisotropy) {
        RuntimeOptions options;
        options.frame_width = kWidth;
        options.frame_height = kHeight;
        options.shadow_map_size = 256;
        options.max_anisotropy = max_anisotropy;
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), checkerQuadBakeSet(), options);
        const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, 0);
        FrameInput frame;
        frame.camera_rgba8 = camera.data();
        frame.intrinsics = {kFocal, kFocal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
        frame.pose = grazingPose();
        frame.utc_unix_seconds = testing::syntheticLocalTime(12, 0);
        frame.weather = Weather::overcast();
        frame.exposure = kExposure;
        frame.ground_ratio = false;
        std::vector<uint8_t> output(camera.size());
        runtime->renderFrame(frame, output.data());
        std::vector<double> values;
        for (const auto& [x, y] : quadPixels())
            values.push_back(srgbDecode(output[(size_t(y) * kWidth + x) * 4 + 1] / 255.0));
        return values;
    }
};

TEST_F(GrazingCheckerTest, LevelZeroAloneSpecklesThere) {
    // The premise, on the CPU: sampling level 0 at the pixel centres (the old sampler) gives values all over
    // [0, 0.8]: a standard deviation of 0.10 here, where the mipmapped render has under 0.02.
    std::vector<double> values;
    for (const auto& [x, y] : quadPixels()) values.push_back(levelZeroBilinear(groundPointOf(x, y)));
    ASSERT_GT(values.size(), 500u);
    const Spread spread = spreadOf(values);
    EXPECT_GT(spread.standard_deviation, 0.08) << "mean " << spread.mean;
}

TEST_F(GrazingCheckerTest, MipmappedPixelsAverageToTheTexturesMeanWithoutSpeckle) {
    const double texture_mean = 0.5 * kExposure;  // linear mean of black and white
    for (float anisotropy : {1.0f, 16.0f}) {
        const std::vector<double> values = renderedLinear(anisotropy);
        ASSERT_GT(values.size(), 500u);
        const Spread spread = spreadOf(values);
        EXPECT_NEAR(spread.mean, texture_mean, 0.01) << "anisotropy " << anisotropy;
        EXPECT_LT(spread.standard_deviation, 0.02) << "anisotropy " << anisotropy << ", mean " << spread.mean;
        std::printf("anisotropy %.0f: %zu pixels, linear mean %.4f (texture %.4f), standard deviation %.4f\n",
                    anisotropy, values.size(), spread.mean, texture_mean, spread.standard_deviation);
    }
}

TEST_F(GrazingCheckerTest, TheRuntimesTextureMemoryIsAboutFourThirdsOfLevelZero) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    BakeSetData untextured = checkerQuadBakeSet();
    untextured.building.textures.clear();
    untextured.building.materials[0].base_color_texture = -1;
    const uint64_t with = Runtime::open(context(), checkerQuadBakeSet(), options)->deviceMemoryBytes();
    const uint64_t without = Runtime::open(context(), untextured, options)->deviceMemoryBytes();
    const double level_zero = double(kCheckerSide) * kCheckerSide * 4;
    EXPECT_NEAR(double(with - without) / level_zero, 4.0 / 3.0, 0.03) << with << " - " << without;
}

TEST(MaxAnisotropyOption, OutsideOneToSixteenIsRefusedByName) {
    for (float bad : {0.5f, 17.0f, std::numeric_limits<float>::quiet_NaN()}) {
        RuntimeOptions options;
        options.max_anisotropy = bad;
        try {
            runtime_detail::checkRuntimeOptions(options);
            ADD_FAILURE() << "max_anisotropy " << bad << " accepted";
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
            EXPECT_NE(std::string(error.what()).find("options.max_anisotropy"), std::string::npos) << error.what();
            EXPECT_NE(std::string(error.what()).find("[1, 16]"), std::string::npos) << error.what();
        }
    }
}

}  // namespace
}  // namespace gusuku

// The runtime's lightmap formats (RuntimeOptions::lightmap_format): the shared-exponent packing against the
// Vulkan spec's equations worked by hand, its round-trip error bound, and on lavapipe with validation on the
// lightmaps' memory per format and the composite's CIEDE2000 against float32 lightmaps on a lightmap with
// values that E5B9G9R9 cannot hold exactly.

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/shared_exponent.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

uint32_t packed(uint32_t exponent, uint32_t red, uint32_t green, uint32_t blue) {
    return exponent << 27 | blue << 18 | green << 9 | red;
}

TEST(SharedExponent, PacksHandWorkedValues) {
    // 1: floor(log2 1) = 0, exponent 0 + 1 + 15 = 16, step 2^(16 - 15 - 9) = 1/256, mantissa 256.
    EXPECT_EQ(packE5b9g9r9(1.0f, 1.0f, 1.0f), packed(16, 256, 256, 256));
    // 0.5, 0.25, 0.125: exponent -1 + 16 = 15, step 1/512.
    EXPECT_EQ(packE5b9g9r9(0.5f, 0.25f, 0.125f), packed(15, 256, 128, 64));
    // The largest value: 511 * 2^(31 - 24).
    EXPECT_EQ(packE5b9g9r9(65408.0f, 0.0f, 0.0f), packed(31, 511, 0, 0));
    EXPECT_EQ(packE5b9g9r9(0.0f, 0.0f, 0.0f), 0u);
    // Negative and NaN to 0, above the largest to the largest.
    EXPECT_EQ(packE5b9g9r9(-1.0f, std::nanf(""), 1e9f), packed(31, 0, 0, 511));
    // 1.999 at exponent 16 rounds to mantissa 512, which does not fit: exponent 17, 1.999 * 128 -> 256 (2.0).
    EXPECT_EQ(packE5b9g9r9(1.999f, 0.0f, 0.0f), packed(17, 256, 0, 0));
    float rgb[3];
    unpackE5b9g9r9(packed(17, 256, 3, 0), rgb);
    EXPECT_EQ(rgb[0], 2.0f);
    EXPECT_EQ(rgb[1], 3.0f / 128.0f);
    EXPECT_EQ(rgb[2], 0.0f);
}

TEST(SharedExponent, RoundTripIsWithinHalfAStepOfTheSharedExponent) {
    std::mt19937 random(21);
    std::uniform_real_distribution<float> log_value(-8.0f, 14.0f);
    for (int trial = 0; trial < 20000; ++trial) {
        const float input[3] = {std::exp2(log_value(random)), std::exp2(log_value(random)), std::exp2(log_value(random))};
        const uint32_t texel = packE5b9g9r9(input[0], input[1], input[2]);
        const double step = std::ldexp(1.0, int(texel >> 27) - 24);
        float output[3];
        unpackE5b9g9r9(texel, output);
        const float largest = std::max({input[0], input[1], input[2]});
        for (int channel = 0; channel < 3; ++channel) {
            ASSERT_LE(std::abs(double(output[channel]) - input[channel]), 0.5 * step + 1e-12) << trial;
            // The step is at most about 1/256 of the largest channel, the format's relative precision (a largest
            // mantissa that rounds up to 512 moves to the next exponent: then largest >= 511.5 * step / 2).
            ASSERT_LE(step, largest / 255.75) << trial;
        }
    }
}

constexpr uint32_t kWidth = 160, kHeight = 120;

// The synthetic box with a lightmap whose texels vary over three decades in hue and level (E5B9G9R9 rounds every
// one of them), so the composite shows what each format's rounding costs.
BakeSetData variedLightmapBakeSet() {
    testing::SyntheticBakeSetOptions options;
    options.lightmap_resolution = 256;
    BakeSetData bake_set = testing::makeSyntheticBakeSet(options);
    for (BakeSetSlotImages& slot : bake_set.slots) {
        const int side = slot.building.width;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                float* texel = &slot.building.rgba[(size_t(y) * side + x) * 4];
                const float level = std::exp2(-4.0f + 10.0f * float(x) / float(side));
                texel[0] = level * 0.7131f;
                texel[1] = level * (0.3 + 0.6f * float(y) / float(side));
                texel[2] = level * 0.2377f;
            }
    }
    return bake_set;
}

class LightmapFormatTest : public testing::GpuTest {
protected:
    std::unique_ptr<Runtime> open(const BakeSetData& bake_set, LightmapFormat format) {
        RuntimeOptions options;
        options.frame_width = kWidth;
        options.frame_height = kHeight;
        options.shadow_map_size = 512;
        options.lightmap_format = format;
        return Runtime::open(context(), bake_set, options);
    }

    std::vector<uint8_t> composite(Runtime& runtime) {
        camera_.assign(size_t(kWidth) * kHeight * 4, 128);
        FrameInput frame;
        frame.camera_rgba8 = camera_.data();
        frame.intrinsics = {110.0, 110.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
        frame.pose = CameraPose::lookingAt({5, -9, 4}, {0, -1.5, 1});
        frame.utc_unix_seconds = testing::syntheticLocalTime(10, 0);
        frame.exposure = 0.1f;
        frame.colour_match = ColourMatch::kOff;
        std::vector<uint8_t> output(camera_.size());
        runtime.renderFrame(frame, output.data());
        return output;
    }

    std::vector<uint8_t> camera_;
};

glm::dvec3 labOf(const uint8_t* pixel) {
    return labFromLinearRec709(
        glm::dvec3(srgbDecode(pixel[0] / 255.0), srgbDecode(pixel[1] / 255.0), srgbDecode(pixel[2] / 255.0)));
}

TEST_F(LightmapFormatTest, SharedExponentHalvesTheLightmapsMemoryAndKeepsTheCompositeWithinAFractionOfADe00) {
    const BakeSetData bake_set = variedLightmapBakeSet();
    std::unique_ptr<Runtime> reference = open(bake_set, LightmapFormat::kRgba32f);
    std::unique_ptr<Runtime> half = open(bake_set, LightmapFormat::kRgba16f);
    std::unique_ptr<Runtime> shared = open(bake_set, LightmapFormat::kE5b9g9r9);
    // Everything but the lightmaps is the same: the differences are 16 - 8 and 8 - 4 bytes a texel and slot.
    const uint64_t texel_slots = 256ull * 256ull * bake_set.slots.size();
    EXPECT_EQ(reference->deviceMemoryBytes() - half->deviceMemoryBytes(), texel_slots * 8);
    EXPECT_EQ(half->deviceMemoryBytes() - shared->deviceMemoryBytes(), texel_slots * 4);

    const std::vector<uint8_t> truth = composite(*reference);
    size_t building_pixels = 0;
    double sum_half = 0.0, sum_shared = 0.0, largest_shared = 0.0;
    for (const auto& [runtime, sum] : {std::pair{half.get(), &sum_half}, std::pair{shared.get(), &sum_shared}}) {
        const std::vector<uint8_t> frame = composite(*runtime);
        for (size_t pixel = 0; pixel < size_t(kWidth) * kHeight; ++pixel) {
            if (truth[pixel * 4] == 128 && truth[pixel * 4 + 1] == 128 && truth[pixel * 4 + 2] == 128) continue;
            const double difference = ciede2000(labOf(&frame[pixel * 4]), labOf(&truth[pixel * 4]));
            *sum += difference;
            if (runtime == shared.get()) {
                ++building_pixels;
                largest_shared = std::max(largest_shared, difference);
            }
        }
    }
    ASSERT_GT(building_pixels, 800u) << "the box fills a good part of the frame";
    const double mean_half = sum_half / double(building_pixels), mean_shared = sum_shared / double(building_pixels);
    std::printf("dE00 vs rgba32f over %zu pixels: rgba16f mean %.4f, e5b9g9r9 mean %.4f (largest %.3f)\n",
                building_pixels, mean_half, mean_shared, largest_shared);
    EXPECT_LT(mean_shared, 0.5);   // the goal
    EXPECT_LT(largest_shared, 2.0);  // 1/512 relative steps are below a just-noticeable difference everywhere
    EXPECT_LE(mean_half, mean_shared + 1e-9);  // half floats keep more mantissa (11 bits against 9)
}

TEST_F(LightmapFormatTest, AnUnknownFormatIsRefusedNamingTheOption) {
    try {
        open(testing::makeSyntheticBakeSet(), LightmapFormat(7));
        FAIL() << "opened with lightmap_format 7";
    } catch (const RuntimeError& error) {
        EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
        EXPECT_NE(std::string(error.what()).find("options.lightmap_format: 7 is not"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace gusuku

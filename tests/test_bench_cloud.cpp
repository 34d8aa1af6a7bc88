// The cloud-cover estimate from a camera frame (gusuku/maths/weather_estimate.h; Weather::estimatedFrom in the runtime) on synthetic frames whose weather
// is known by construction: a clear frame (blue sky, hard shadows on the ground), an overcast one (grey sky, no
// shadows), and their blends, which must read as more clouded the more overcast they hold.

#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "gusuku/maths/weather_estimate.h"
#include "gusuku/maths/colour.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::bench {
namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;

// Linear radiance of pixel (x, y): sky in the top quarter, ground below; sunny ground alternates lit and shaded
// columns (shadow: 1/8 of the light), overcast ground is lit evenly with a little texture.
glm::vec3 sunnyPixel(uint32_t x, uint32_t y) {
    if (y < kHeight / 4) return {0.25f, 0.40f, 0.80f};
    const glm::vec3 albedo = (x / 4) % 3 == 0 ? glm::vec3(0.30f, 0.28f, 0.22f) : glm::vec3(0.22f, 0.30f, 0.16f);
    return albedo * ((x / 8) % 2 == 0 ? 1.6f : 0.2f);
}
glm::vec3 overcastPixel(uint32_t x, uint32_t y) {
    if (y < kHeight / 4) return {0.70f, 0.70f, 0.72f};
    const glm::vec3 albedo = (x / 4) % 3 == 0 ? glm::vec3(0.30f, 0.28f, 0.22f) : glm::vec3(0.22f, 0.30f, 0.16f);
    return albedo * 0.5f;
}

// white_balance: the camera's per-channel gains on linear RGB (a warm camera raises R and lowers B).
std::vector<uint8_t> encode(float overcast_weight, glm::vec3 white_balance = glm::vec3(1.0f)) {
    std::vector<uint8_t> frame(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::vec3 linear =
                white_balance * ((1.0f - overcast_weight) * sunnyPixel(x, y) + overcast_weight * overcastPixel(x, y));
            const glm::vec3 encoded = srgbEncode(glm::clamp(linear, 0.0f, 1.0f));
            uint8_t* pixel = frame.data() + 4 * (size_t(y) * kWidth + x);
            for (int channel = 0; channel < 3; ++channel) pixel[channel] = uint8_t(encoded[channel] * 255.0f + 0.5f);
            pixel[3] = 255;
        }
    return frame;
}

TEST(BenchCloudEstimate, ClearAndOvercastFrames) {
    const CloudEstimate clear = estimateCloudCover(encode(0.0f), kWidth, kHeight);
    EXPECT_LT(clear.cloud_cover, 0.15f);
    EXPECT_GT(clear.shadow_contrast, 2.0f);  // ln 8 = 2.08, plus the texture
    // ln(0.80 / 0.25) = 1.163 for the sky, minus the ground's median ln(B / R): ln(0.16 / 0.22) = -0.318.
    EXPECT_NEAR(clear.sky_blueness, 1.163f + 0.318f, 0.03f);
    const CloudEstimate overcast = estimateCloudCover(encode(1.0f), kWidth, kHeight);
    EXPECT_GT(overcast.cloud_cover, 0.85f);
    EXPECT_LT(overcast.shadow_contrast, kOvercastShadowContrast);
    EXPECT_NEAR(overcast.sky_blueness, 0.028f + 0.318f, 0.03f);  // ln(0.72 / 0.70) + 0.318
    EXPECT_TRUE(overcast.sky_in_view);
}

// A camera's white balance scales B / R over the whole frame: the sky cue, a difference of ln(B / R), does not
// move (up to 8-bit rounding), so a warm camera reads the same weather as a neutral one.
TEST(BenchCloudEstimate, WhiteBalanceDoesNotMoveTheSkyCue) {
    for (const float overcast : {0.0f, 0.5f, 1.0f}) {
        const CloudEstimate neutral = estimateCloudCover(encode(overcast), kWidth, kHeight);
        const CloudEstimate warm = estimateCloudCover(encode(overcast, {1.15f, 1.0f, 0.8f}), kWidth, kHeight);
        const CloudEstimate cool = estimateCloudCover(encode(overcast, {0.85f, 1.0f, 1.2f}), kWidth, kHeight);
        EXPECT_NEAR(warm.sky_blueness, neutral.sky_blueness, 0.03f) << "overcast weight " << overcast;
        EXPECT_NEAR(cool.sky_blueness, neutral.sky_blueness, 0.03f) << "overcast weight " << overcast;
        EXPECT_NEAR(warm.cloud_cover, neutral.cloud_cover, 0.08f) << "overcast weight " << overcast;
    }
}

// The runtime's entry point hands the app the same cover as a Weather.
TEST(BenchCloudEstimate, RuntimeWeatherIsTheEstimate) {
    for (const float overcast : {0.0f, 0.5f, 1.0f}) {
        const std::vector<uint8_t> frame = encode(overcast);
        EXPECT_FLOAT_EQ(Weather::estimatedFrom(frame.data(), kWidth, kHeight).cloud_cover,
                        estimateCloudCover(frame, kWidth, kHeight).cloud_cover);
    }
    EXPECT_FLOAT_EQ(Weather::estimatedFrom(nullptr, kWidth, kHeight).cloud_cover, 1.0f);
}

TEST(BenchCloudEstimate, MoreOvercastReadsMoreClouded) {
    float previous = -1.0f;
    for (float weight : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        const float cover = estimateCloudCover(encode(weight), kWidth, kHeight).cloud_cover;
        EXPECT_GE(cover, previous) << "overcast weight " << weight;
        previous = cover;
    }
    EXPECT_GT(estimateCloudCover(encode(0.5f), kWidth, kHeight).cloud_cover, 0.15f);
}

TEST(BenchCloudEstimate, DegenerateFramesReadAsOvercast) {
    EXPECT_EQ(estimateCloudCover(std::vector<uint8_t>(size_t(kWidth) * kHeight * 4, 0), kWidth, kHeight).cloud_cover,
              1.0f);
    EXPECT_EQ(estimateCloudCover(std::vector<uint8_t>(4 * 4, 200), 4, 1).cloud_cover, 1.0f);
    EXPECT_EQ(estimateCloudCover(std::vector<uint8_t>(7), kWidth, kHeight).cloud_cover, 1.0f);
}

}  // namespace
}  // namespace gusuku::bench

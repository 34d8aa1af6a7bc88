// gusuku-bench's accuracy metrics (bench/bench/image_metrics.h) and camera responses (camera_response.h), against
// values worked out by hand: white against black is CIEDE2000 100 (L' differs by 100 at mean L' 50, where S_L is
// 1, and a = b = 0), a byte error of 10 everywhere is PSNR 10 log10(255^2 / 100), percentiles interpolate
// between ranks as numpy's default does.

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "camera_response.h"
#include "image_metrics.h"
#include "gusuku/maths/colour.h"

namespace gusuku::bench {
namespace {

std::vector<uint8_t> frameOf(const std::vector<std::array<uint8_t, 3>>& pixels) {
    std::vector<uint8_t> frame;
    for (const auto& pixel : pixels) frame.insert(frame.end(), {pixel[0], pixel[1], pixel[2], 255});
    return frame;
}

TEST(BenchMetrics, LabOfWhiteAndBlack) {
    const glm::dvec3 white = labOfSrgb8(255, 255, 255);
    EXPECT_NEAR(white.x, 100.0, 1e-3);
    EXPECT_NEAR(white.y, 0.0, 1e-3);
    EXPECT_NEAR(white.z, 0.0, 1e-3);
    const glm::dvec3 black = labOfSrgb8(0, 0, 0);
    EXPECT_NEAR(black.x, 0.0, 1e-9);
    // sRGB 119 decodes to 0.1845 linear, L* 50.0 (a common grey-card value).
    EXPECT_NEAR(labOfSrgb8(119, 119, 119).x, 50.0, 0.1);
}

TEST(BenchMetrics, PerPixelDifferenceAndAveraging) {
    const std::vector<uint8_t> frame = frameOf({{255, 255, 255}, {0, 0, 0}, {40, 80, 120}, {7, 7, 7}});
    const std::vector<uint8_t> truth = frameOf({{0, 0, 0}, {0, 0, 0}, {40, 80, 120}, {7, 7, 7}});
    const std::vector<double> differences = ciede2000PerPixel(frame, truth);
    ASSERT_EQ(differences.size(), 4u);
    EXPECT_NEAR(differences[0], 100.0, 1e-3);
    EXPECT_EQ(differences[1], 0.0);
    EXPECT_EQ(differences[2], 0.0);
    const ErrorSummary whole = summariseError(frame, truth);
    EXPECT_EQ(whole.pixel_count, 4u);
    EXPECT_NEAR(whole.mean_de00, 25.0, 1e-3);
    // Sorted 0, 0, 0, 100: position 0.95 x 3 = 2.85, so 0.85 of the way from 0 to 100.
    EXPECT_NEAR(whole.p95_de00, 85.0, 1e-3);
    // One pixel of four off by 255 in every channel: MSE 255^2 / 4, PSNR 10 log10(4).
    EXPECT_NEAR(whole.psnr_db, 10.0 * std::log10(4.0), 1e-9);

    const std::vector<uint8_t> only_first{1, 0, 0, 0};
    const ErrorSummary masked = summariseError(frame, truth, only_first);
    EXPECT_EQ(masked.pixel_count, 1u);
    EXPECT_NEAR(masked.mean_de00, 100.0, 1e-3);
    EXPECT_NEAR(masked.p95_de00, 100.0, 1e-3);
    EXPECT_NEAR(masked.psnr_db, 0.0, 1e-9);  // MSE 255^2

    const std::vector<uint8_t> only_equal{0, 1, 1, 0};
    const ErrorSummary equal = summariseError(frame, truth, only_equal);
    EXPECT_EQ(equal.mean_de00, 0.0);
    EXPECT_EQ(equal.psnr_db, std::numeric_limits<double>::infinity());
}

TEST(BenchMetrics, PsnrOfAConstantError) {
    std::vector<uint8_t> frame(64 * 4, 100), truth(64 * 4, 110);
    for (size_t pixel = 0; pixel < 64; ++pixel) frame[4 * pixel + 3] = 0;  // alpha is ignored
    EXPECT_NEAR(psnrDb(frame, truth, {}), 10.0 * std::log10(255.0 * 255.0 / 100.0), 1e-9);  // 28.13 dB
}

TEST(BenchMetrics, Percentiles) {
    std::vector<double> values;
    for (int value = 100; value >= 1; --value) values.push_back(value);  // unsorted on purpose
    EXPECT_NEAR(percentile(values, 0.95), 95.05, 1e-12);
    EXPECT_NEAR(percentile(values, 0.5), 50.5, 1e-12);
    EXPECT_EQ(percentile(values, 0.0), 1.0);
    EXPECT_EQ(percentile(values, 1.0), 100.0);
    EXPECT_EQ(percentile({7.0}, 0.95), 7.0);
    EXPECT_EQ(percentile({}, 0.95), 0.0);
}

TEST(BenchMetrics, ChangedPixelMask) {
    // Identical, one step of one byte (below 1 dE00), and a clear change.
    const std::vector<uint8_t> with = frameOf({{90, 90, 90}, {91, 90, 90}, {30, 30, 30}});
    const std::vector<uint8_t> without = frameOf({{90, 90, 90}, {90, 90, 90}, {90, 90, 90}});
    EXPECT_EQ(changedPixelMask(with, without), (std::vector<uint8_t>{0, 0, 1}));
    EXPECT_EQ(changedPixelMask(with, without, 0.1), (std::vector<uint8_t>{0, 1, 1}));
}

// A checkerboard of black and white low-passes, away from the edges, to the linear mean of its window: 4 or 5 of
// the 9 pixels white, 4/9 or 5/9 in linear light, encoded to sRGB; at a corner the 4 pixels inside, 2 of them white:
// 1/2. A uniform frame stays as it is. The noise correction: sqrt(e^2 - n^2 / 2), 0 when the noise is larger.
TEST(BenchMetrics, LowPassInLinearLightAndTheTruthsNoiseTakenOut) {
    const uint32_t width = 5, height = 4;
    std::vector<uint8_t> board(size_t(width) * height * 4, 255);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            if ((x + y) % 2)
                for (int channel = 0; channel < 3; ++channel) board[(size_t(y) * width + x) * 4 + channel] = 0;
    const std::vector<uint8_t> filtered = lowPass3x3Linear(board, width, height);
    auto byteOf = [](double linear) { return int(std::lround(255.0 * srgbEncode(linear))); };
    // (1, 1): x + y even, white; its 3 x 3 window has 5 white (the centre and the 4 corners).
    EXPECT_EQ(filtered[(1 * width + 1) * 4], byteOf(5.0 / 9.0));
    // (2, 1): black; 4 white (its 4 edge neighbours).
    EXPECT_EQ(filtered[(1 * width + 2) * 4 + 1], byteOf(4.0 / 9.0));
    // (0, 0): white corner, window of 4 inside the frame, 2 white.
    EXPECT_EQ(filtered[2], byteOf(0.5));
    EXPECT_EQ(filtered[3], 255);
    const std::vector<uint8_t> grey(size_t(width) * height * 4, 118);
    EXPECT_EQ(lowPass3x3Linear(grey, width, height), grey);
    EXPECT_THROW(lowPass3x3Linear(grey, width + 1, height), std::invalid_argument);
    EXPECT_NEAR(withoutTruthNoise(2.0, 2.0), std::sqrt(2.0), 1e-12);
    EXPECT_DOUBLE_EQ(withoutTruthNoise(1.0, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(withoutTruthNoise(0.5, 2.0), 0.0);
}

TEST(BenchMetrics, SizesMustAgree) {
    EXPECT_THROW(ciede2000PerPixel(std::vector<uint8_t>(8), std::vector<uint8_t>(12)), std::invalid_argument);
    EXPECT_THROW(summariseError(std::vector<uint8_t>(8), std::vector<uint8_t>(8), std::vector<uint8_t>(3)),
                 std::invalid_argument);
}

TEST(BenchCameraResponse, CurvesAndWhiteBalance) {
    EXPECT_EQ(applyToneCurve(ToneCurve::kLinear, 0.4f), 0.4f);
    EXPECT_NEAR(applyToneCurve(ToneCurve::kFilmic, 1.0f), 1.0f, 1e-6f);  // 1.6 x 1.25 / 2
    EXPECT_NEAR(applyToneCurve(ToneCurve::kContrast, 1.0f), 1.15f, 1e-6f);
    EXPECT_EQ(applyToneCurve(ToneCurve::kFilmic, -1.0f), 0.0f);

    ImageRGBA linear;
    linear.width = 2;
    linear.height = 1;
    linear.texels = {0.21586f, 0.21586f, 0.21586f, 1.0f, 10.0f, 0.0f, 0.5f, 1.0f};
    const std::vector<CameraResponse> responses = benchCameraResponses();
    ASSERT_GE(responses.size(), 3u);
    // Neutral, exposure 1: linear 0.21586 is srgbDecode(128 / 255); 10 clips to 255; 0.5 encodes to 0.7354.
    const std::vector<uint8_t> neutral = applyCameraResponse(linear, 1.0f, responses[0]);
    EXPECT_EQ(neutral, (std::vector<uint8_t>{128, 128, 128, 255, 255, 0, 188, 255}));
    // Warm: red up, blue down against the neutral grey.
    const std::vector<uint8_t> warm = applyCameraResponse(linear, 1.0f, responses[1]);
    EXPECT_GT(warm[0], warm[1]);
    EXPECT_LT(warm[2], warm[1]);
}

}  // namespace
}  // namespace gusuku::bench

// The variance-guided lightmap filter (baker/include/gusuku_bake/lightmap_denoise.h) on detail one texel wide,
// against a known true lightmap (issue 11, item 1: on the shrine site the filter of 447f357 added more bias
// across the 1-2 texel wide beams than the noise it took out).
//
// The true image: four charts of a lightmap at 8 texels per metre (the shrine's density), each a face with a
// smooth falloff towards its foot, a dark texel-wide line across it every 5 rows (the shadow of a beam) and a
// dark outermost column (a face meeting another: the light falls off within a texel). The noise imitates the
// baker's scrambled Sobol samples as measured on the shrine (gusuku-bake converge, overcast and sunny_1200,
// each against an independent 1024-sample reference): the true error of a texel's mean falls as
// 0.9 samples^-0.7 of its irradiance (Gaussian, independent between texels: the measured correlation between
// neighbours was under 0.03), while the variance the bake measures from its squared sums is that of
// independent samples, (0.85 E)^2 / samples, 3 to 9 times the true error's square from 32 to 256 samples.
// At 32, 64, 128 and 256 samples the filter as the bake runs it (denoiseOptionsForSamples) must have a lower
// mean squared error than the raw image and than the filter of 447f357 (5 passes, 0.25 m, 1.5 noise sigmas).
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/colour.h"
#include "gusuku_bake/lightmap_denoise.h"

namespace gusuku::bake {
namespace {

constexpr int kSide = 64;
constexpr float kTexelM = 0.125f;  // 8 texels per metre
constexpr int kCharts = 4, kChartWidth = 14, kChartHeight = 60, kChartGap = 2;

struct TrueLightmap {
    std::vector<glm::vec4> irradiance;  // alpha 1 where valid
    std::vector<DenoiseGuide> guides;
};

TrueLightmap makeTrueLightmap() {
    TrueLightmap truth;
    truth.irradiance.assign(size_t(kSide) * kSide, glm::vec4(0.0f));
    truth.guides.resize(truth.irradiance.size());
    for (int chart = 0; chart < kCharts; ++chart) {
        const int x0 = 1 + chart * (kChartWidth + kChartGap);
        // Each chart a vertical face of its own orientation, 2 m apart from the next in the world.
        const float angle = 0.7f * float(chart);
        const glm::vec3 along(std::cos(angle), std::sin(angle), 0.0f), normal(-std::sin(angle), std::cos(angle), 0.0f);
        const glm::vec3 origin(2.0f * float(chart), 0.0f, 0.0f);
        for (int row = 0; row < kChartHeight; ++row)
            for (int column = 0; column < kChartWidth; ++column) {
                const size_t i = size_t(2 + row) * kSide + size_t(x0 + column);
                const float height_m = (float(row) + 0.5f) * kTexelM;
                // A smooth falloff towards the foot (as under eaves or near the ground), 1 at the top.
                float level = 0.35f + 0.65f * (1.0f - std::exp(-height_m / 1.5f));
                if (row % 4 == 2) level *= 0.8f;                                     // a beam's shadow line
                if (column == 0 || column == kChartWidth - 1) level *= 0.75f;       // the contact falloff
                if (column == 1 || column == kChartWidth - 2) level *= 0.9f;
                truth.irradiance[i] = glm::vec4(glm::vec3(level * (1.0f + 0.1f * float(chart))), 1.0f);
                truth.guides[i] = {origin + along * ((float(column) + 0.5f) * kTexelM) +
                                       glm::vec3(0.0f, 0.0f, height_m),
                                   normal, uint32_t(chart)};
            }
    }
    return truth;
}

double meanSquaredError(const std::vector<glm::vec4>& estimate, const TrueLightmap& truth) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < estimate.size(); ++i) {
        if (truth.irradiance[i].a <= 0.0f) continue;
        const double error = luminanceRec709(glm::vec3(estimate[i])) - luminanceRec709(glm::vec3(truth.irradiance[i]));
        sum += error * error;
        ++count;
    }
    return sum / double(count);
}

TEST(LightmapDenoiseThinFeatures, BeatsRawAndTheFilterOf447f357) {
    const TrueLightmap truth = makeTrueLightmap();
    DenoiseOptions before;  // the filter of 447f357 from 32 samples on
    before.iterations = 5;
    before.position_sigma_m = 0.25f;
    before.normal_power = 64.0f;
    before.luminance_noise_sigmas = 1.5f;
    std::mt19937 random(11);
    std::normal_distribution<float> unit(0.0f, 1.0f);
    for (const uint32_t samples : {32u, 64u, 128u, 256u}) {
        SCOPED_TRACE(samples);
        const float true_relative_sd = 0.9f * std::pow(float(samples), -0.7f);
        const float measured_relative_sd = 0.85f / std::sqrt(float(samples));
        std::vector<glm::vec4> raw = truth.irradiance;
        std::vector<float> variance(raw.size(), 0.0f);
        for (size_t i = 0; i < raw.size(); ++i) {
            if (truth.irradiance[i].a <= 0.0f) continue;
            const float level = truth.irradiance[i].r;
            raw[i] = glm::vec4(glm::vec3(level * (1.0f + true_relative_sd * unit(random))), 1.0f);
            variance[i] = (measured_relative_sd * level) * (measured_relative_sd * level);
        }
        std::vector<glm::vec4> filtered = raw, filtered_before = raw;
        denoiseLightmap(filtered, truth.guides, kSide, denoiseOptionsForSamples(samples, true), variance);
        denoiseLightmap(filtered_before, truth.guides, kSide, before, variance);
        const double raw_mse = meanSquaredError(raw, truth), mse = meanSquaredError(filtered, truth),
                     mse_before = meanSquaredError(filtered_before, truth);
        std::printf("%u samples: MSE raw %.3g, filtered %.3g (%.2fx lower), filter of 447f357 %.3g (%.2fx)\n",
                    samples, raw_mse, mse, raw_mse / mse, mse_before, raw_mse / mse_before);
        EXPECT_LT(mse, raw_mse);
        EXPECT_LT(mse, mse_before);
    }
}

}  // namespace
}  // namespace gusuku::bake

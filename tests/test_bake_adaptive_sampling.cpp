// Adaptive sampling (gusuku_bake/adaptive_sampling.h): extra samples go to texels in proportion to their own
// noise (the allocation that minimises the summed variance for a fixed budget), within the budget and the cap,
// in whole copies of a footprint; a point's sums normalised to the set's sample count keep its mean and the
// variance of its mean; and on the device, a point's copies continue its own random stream, so a pilot plus
// copies is the very estimate a longer uniform trace makes.
#include <cmath>
#include <algorithm>
#include <bit>
#include <numeric>
#include <stdexcept>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku_bake/adaptive_sampling.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

TEST(AdaptiveSampling, ExtraSamplesFollowEachTexelsNoiseWithinTheBudget) {
    // Noise spread as on the measured sites: most texels quiet, a tenth loud.
    std::mt19937 rng(3);
    std::lognormal_distribution<float> spread(0.0f, 1.2f);
    std::vector<float> sigma(4000);
    for (float& s : sigma) s = spread(rng);
    const uint32_t pilot = 32, budget = 64;
    const std::vector<uint32_t> extra = planAdaptiveSamples(sigma, pilot, budget, {4, 8.0});
    ASSERT_EQ(extra.size(), sigma.size());
    for (uint32_t e : extra) EXPECT_EQ(e % 4, 0u) << "whole copies";
    // The budget: the pilot's half again, give or take the rounding to whole copies.
    const double spent = std::accumulate(extra.begin(), extra.end(), 0.0);
    const double wanted = double(budget - pilot) * double(sigma.size());
    EXPECT_NEAR(spent, wanted, 2.0 * sigma.size());
    // Monotone in sigma, proportional to sigma^kAdaptiveNoiseExponent between the pilot floor and the cap (8x
    // the budget in all).
    std::vector<size_t> order(sigma.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sigma[a] < sigma[b]; });
    for (size_t k = 1; k < order.size(); ++k) EXPECT_LE(extra[order[k - 1]], extra[order[k]]);
    for (uint32_t e : extra) EXPECT_LE(pilot + e, 8 * budget + 2);
    const size_t middle = order[order.size() * 9 / 10], higher = order[order.size() * 97 / 100];
    EXPECT_NEAR(double(pilot + extra[higher]) / double(pilot + extra[middle]),
                std::pow(sigma[higher] / sigma[middle], kAdaptiveNoiseExponent), 0.1);
    // With the exponent 1, proportional to sigma itself (the minimum summed variance for exact sigmas).
    AdaptivePlanOptions proportional{4, 8.0};
    proportional.noise_exponent = 1.0;
    const std::vector<uint32_t> extra_by_sigma = planAdaptiveSamples(sigma, pilot, budget, proportional);
    EXPECT_NEAR(double(pilot + extra_by_sigma[higher]) / double(pilot + extra_by_sigma[middle]),
                sigma[higher] / sigma[middle], 0.1);
    // What it buys: the summed variance sigma^2 / n against uniform sampling at the same spent samples.
    double adaptive_variance = 0.0, uniform_variance = 0.0;
    const double uniform_samples = pilot + spent / double(sigma.size());
    for (size_t t = 0; t < sigma.size(); ++t) {
        adaptive_variance += double(sigma[t]) * sigma[t] / double(pilot + extra[t]);
        uniform_variance += double(sigma[t]) * sigma[t] / uniform_samples;
    }
    // The optimum (n proportional to sigma, no pilot floor) is (mean sigma)^2 / mean(sigma^2) = exp(-1.2^2) =
    // 0.24 of uniform here; the pilot's floor of half the budget and the flatter sigma^0.6 keep part of that.
    EXPECT_LT(adaptive_variance, 0.6 * uniform_variance);
}

TEST(AdaptiveSampling, PilotIsAQuarterOfTheSamplesAndAtLeastSixteen) {
    EXPECT_EQ(adaptivePilotSamples(kMinAdaptiveSamples), 16u);  // at least 16: half of the first adaptive count
    EXPECT_EQ(adaptivePilotSamples(64), 16u);
    EXPECT_EQ(adaptivePilotSamples(128), 32u);
    EXPECT_EQ(adaptivePilotSamples(512), 128u);
    EXPECT_EQ(adaptivePilotSamples(24), 12u);  // never more than half: the plan must have samples to place
    // `converge` continues one uniform trace from study point to study point: the pilot must never shrink as
    // the samples double.
    for (uint32_t samples = kMinAdaptiveSamples; samples < (1u << 20); samples *= 2)
        EXPECT_LE(adaptivePilotSamples(samples), adaptivePilotSamples(2 * samples)) << samples;
    // A footprint of 4 points sharing 128 samples a texel (32 each): 8 pilot samples a point, 32 a texel.
    EXPECT_EQ(adaptivePilotSamplesPerPoint(32, 4), 8u);
    EXPECT_EQ(adaptivePilotSamplesPerPoint(64, 1), 16u);
    EXPECT_EQ(adaptivePilotSamplesPerPoint(2, 16), 1u);  // at least one sample a point
}

TEST(AdaptiveSampling, QuietTexelsGetNothingAndCopiesAreWholeFootprints) {
    const std::vector<float> sigma = {0.0f, std::nanf(""), 0.01f, 1.0f, 1.0f, 10.0f};
    const std::vector<uint32_t> extra = planAdaptiveSamples(sigma, 16, 32, {8, 8.0});
    EXPECT_EQ(extra[0], 0u);  // no noise: nothing to gain
    EXPECT_EQ(extra[1], 0u);  // no estimate: nothing
    EXPECT_EQ(extra[2], 0u);  // far quieter than the rest
    EXPECT_EQ(extra[3], extra[4]);
    EXPECT_GT(extra[5], extra[3]);
    EXPECT_LE(16 + extra[5], 8 * 32);  // the loud texel is capped at 8x the budget
    // Nothing to plan: no budget beyond the pilot, or no noise anywhere.
    for (uint32_t e : planAdaptiveSamples(sigma, 32, 32)) EXPECT_EQ(e, 0u);
    for (uint32_t e : planAdaptiveSamples({0.0f, 0.0f}, 16, 32)) EXPECT_EQ(e, 0u);

    // Two slots a texel, 4 samples a copy, after a pilot of 8 a slot: extra 8 is one copy of each slot; the
    // owners are the slots, and each copy continues its slot's random stream where the last one stopped.
    std::vector<QueryPointGpu> points(6);
    for (size_t i = 0; i < points.size(); ++i) points[i].position = glm::vec4(float(i), 0.0f, 0.0f, 1.0f);
    const AdaptiveExtras extras = adaptiveExtraPoints(points, {0, 16, 8}, 2, 4, 8);
    ASSERT_EQ(extras.owners, (std::vector<uint32_t>{2, 3, 2, 3, 4, 5}));
    const std::vector<uint32_t> first_samples = {8, 8, 12, 12, 8, 8};
    for (size_t c = 0; c < extras.points.size(); ++c) {
        EXPECT_EQ(extras.points[c].position.x, float(extras.owners[c]));
        EXPECT_EQ(std::bit_cast<uint32_t>(extras.points[c].normal.w), extras.owners[c] + 1u) << "the owner's stream";
        EXPECT_EQ(std::bit_cast<uint32_t>(extras.points[c].face_normal.w), first_samples[c]);
    }
    EXPECT_THROW(adaptiveExtraPoints(points, {0, 4, 8}, 2, 4, 8), std::invalid_argument);  // half a footprint
    EXPECT_THROW(adaptiveExtraPoints(points, {0, 8}, 2, 4, 8), std::invalid_argument);     // sizes differ

    // Sums added in two batches land on their owners, with their sample counts.
    SetSums set{std::vector<glm::vec4>(6, glm::vec4(1.0f)), std::vector<float>(6, 1.0f), std::vector<uint32_t>(6, 4)};
    addAdaptiveExtraSums(set, extras, 0, std::vector<glm::vec4>(4, glm::vec4(2.0f)), std::vector<float>(4, 3.0f));
    addAdaptiveExtraSums(set, extras, 4, std::vector<glm::vec4>(2, glm::vec4(2.0f)), std::vector<float>(2, 3.0f));
    EXPECT_EQ(set.sums[0], glm::vec4(1.0f));
    EXPECT_EQ(set.sums[2], glm::vec4(5.0f));
    EXPECT_EQ(set.luminance_square_sums[3], 7.0f);
    EXPECT_EQ(set.samples[2], 12u);
    EXPECT_EQ(set.samples[4], 8u);
    EXPECT_EQ(set.samples[1], 4u);
    EXPECT_THROW(addAdaptiveExtraSums(set, extras, 5, std::vector<glm::vec4>(2), std::vector<float>(2)),
                 std::invalid_argument);
}

TEST(AdaptiveSampling, NormalisedSumsKeepTheMeanAndTheVarianceOfTheMean) {
    // 40 samples of a point: the sums, then normalised to 64 as if the set had 64 samples each.
    std::mt19937 rng(11);
    std::normal_distribution<float> noise(2.0f, 0.5f);
    PointSums point;
    for (int s = 0; s < 40; ++s) {
        const float irradiance = noise(rng);
        point.sum += glm::vec4(irradiance, irradiance, irradiance, s % 4 == 0 ? 1.0f : 0.0f);
        point.luminance_square_sum += irradiance * irradiance;  // grey: luminance equals the channel
        ++point.samples;
    }
    const auto meanAndVarianceOfMean = [](const PointSums& p) {
        const double n = p.samples, mean = p.sum.x / n;
        return std::pair<double, double>(mean, (p.luminance_square_sum - n * mean * mean) / (n - 1.0) / n);
    };
    const PointSums normalised = normaliseToSampleCount(point, 64);
    EXPECT_EQ(normalised.samples, 64u);
    const auto [mean, variance] = meanAndVarianceOfMean(point);
    const auto [mean_after, variance_after] = meanAndVarianceOfMean(normalised);
    EXPECT_NEAR(mean_after, mean, 1e-6 * mean);
    EXPECT_NEAR(variance_after, variance, 1e-3 * variance);
    EXPECT_NEAR(normalised.sum.w / 64.0, point.sum.w / 40.0, 1e-6);  // the back-face share too
    // Same count: unchanged; no samples: stays empty.
    EXPECT_EQ(normaliseToSampleCount(point, 40).luminance_square_sum, point.luminance_square_sum);
    EXPECT_EQ(normaliseToSampleCount(PointSums{}, 64).samples, 0u);
}

class AdaptiveSamplingGpu : public gusuku::testing::GpuTest {};

// A ground under a wall, lit by the sun and an uneven sky: 8 pilot samples a point plus two copies of 4 (the
// copies' samples 8-11 and 12-15 of the point's own stream) sum to what 16 uniform samples sum to, up to the
// order of the float additions; copies given streams of their own (normal.w = 0) do not.
TEST_F(AdaptiveSamplingGpu, CopiesContinueTheirPointsRandomStream) {
    TriangleMesh wall = gusuku::testing::emptyMesh(glm::vec3(0.6f));
    gusuku::testing::addQuad(wall, {-5.0f, 0.0f, -1.0f}, {5.0f, 0.0f, -1.0f}, {5.0f, 0.0f, 4.0f}, {-5.0f, 0.0f, 4.0f});
    const TriangleMesh ground = gusuku::testing::horizontalPlane(20.0f, 0.0f, glm::vec3(0.4f));
    const TraceScene scene = makeTraceScene(wall, &ground);
    gusuku::ImageRGBA sky = gusuku::testing::uniformSky(32, 16, glm::vec3(0.2f, 0.3f, 0.5f));
    for (int x = 0; x < 8; ++x) std::fill(sky.texel(x, 5), sky.texel(x, 5) + 3, 40.0f);  // a bright band
    IrradianceTracer tracer(context(), scene, buildSkySamplingTables(sky, 0.0));
    TracePass pass;
    pass.sun.present = true;
    pass.sun.direction_enu = glm::normalize(glm::dvec3(0.3, -0.6, 0.7));
    pass.sun.irradiance_rgb = glm::dvec3(800.0, 750.0, 700.0);
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 40; ++i)
        points.push_back({glm::vec4(-4.0f + 0.2f * float(i), -0.05f - 0.1f * float(i % 7), 0.0f, 1.0f),
                          glm::vec4(0.0f, 0.0f, 1.0f, 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});

    PointAccumulator uniform = tracer.createAccumulator(points);
    tracer.addSamples(uniform, 16, pass);
    PointAccumulator pilot = tracer.createAccumulator(points);
    tracer.addSamples(pilot, 8, pass);
    SetSums set{tracer.readSums(pilot), tracer.readLuminanceSquareSums(pilot), std::vector<uint32_t>(points.size(), 8)};
    const AdaptiveExtras extras =
        adaptiveExtraPoints(points, std::vector<uint32_t>(points.size(), 8), 1, 4, 8);
    ASSERT_EQ(extras.points.size(), 2 * points.size());
    PointAccumulator copies = tracer.createAccumulator(extras.points);
    tracer.addSamples(copies, 4, pass);
    addAdaptiveExtraSums(set, extras, 0, tracer.readSums(copies), tracer.readLuminanceSquareSums(copies));

    const std::vector<glm::vec4> expected = tracer.readSums(uniform);
    const std::vector<float> expected_squares = tracer.readLuminanceSquareSums(uniform);
    double largest_difference = 0.0;
    for (size_t p = 0; p < points.size(); ++p) {
        EXPECT_EQ(set.samples[p], 16u);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(set.sums[p][c], expected[p][c], 1e-5f * std::abs(expected[p][c]) + 1e-6f) << "point " << p;
            largest_difference = std::max(largest_difference, double(std::abs(set.sums[p][c] - expected[p][c])));
        }
        EXPECT_EQ(set.sums[p].w, expected[p].w);
        EXPECT_NEAR(set.luminance_square_sums[p], expected_squares[p], 1e-5f * expected_squares[p] + 1e-6f);
    }
    // The check can fail: copies drawing streams of their own give other sums.
    std::vector<QueryPointGpu> own_streams = extras.points;
    for (QueryPointGpu& point : own_streams) point.normal.w = point.face_normal.w = 0.0f;
    PointAccumulator independent = tracer.createAccumulator(own_streams);
    tracer.addSamples(independent, 4, pass);
    const std::vector<glm::vec4> independent_sums = tracer.readSums(independent);
    const std::vector<glm::vec4> continued_sums = tracer.readSums(copies);
    double largest_change = 0.0;
    for (size_t c = 0; c < own_streams.size(); ++c)
        largest_change = std::max(largest_change, double(glm::length(independent_sums[c] - continued_sums[c])));
    EXPECT_GT(largest_change, 100.0 * largest_difference + 1e-3);
}

}  // namespace
}  // namespace gusuku::bake

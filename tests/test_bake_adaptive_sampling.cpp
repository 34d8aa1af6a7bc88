// Adaptive sampling's plan (baker/src/adaptive_sampling.h): extra samples go to texels in proportion to their
// own noise (the allocation that minimises the summed variance for a fixed budget), within the budget and the
// cap, in classes of whole footprints; and a point's sums normalised to the set's sample count keep its mean
// and the variance of its mean.
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku_bake/adaptive_sampling.h"

namespace gusuku::bake {
namespace {

// The texel -> extra samples map of a plan.
std::vector<uint32_t> extraPerTexel(const std::vector<AdaptiveClass>& plan, size_t texel_count) {
    std::vector<uint32_t> extra(texel_count, 0);
    for (const AdaptiveClass& one_class : plan)
        for (uint32_t texel : one_class.texels) {
            EXPECT_EQ(extra[texel], 0u) << "texel " << texel << " is in two classes";
            extra[texel] = one_class.extra_samples_per_texel;
        }
    return extra;
}

TEST(AdaptiveSampling, ExtraSamplesFollowEachTexelsNoiseWithinTheBudget) {
    // Noise spread as on the measured sites: most texels quiet, a tenth loud.
    std::mt19937 rng(3);
    std::lognormal_distribution<float> spread(0.0f, 1.2f);
    std::vector<float> sigma(4000);
    for (float& s : sigma) s = spread(rng);
    const uint32_t pilot = 32, budget = 64;
    const std::vector<AdaptiveClass> plan = planAdaptiveSamples(sigma, pilot, budget);
    ASSERT_FALSE(plan.empty());
    const std::vector<uint32_t> extra = extraPerTexel(plan, sigma.size());
    // Classes: powers of two, ascending, none empty.
    for (size_t k = 0; k < plan.size(); ++k) {
        const uint32_t e = plan[k].extra_samples_per_texel;
        EXPECT_EQ(e & (e - 1), 0u) << e;
        EXPECT_FALSE(plan[k].texels.empty());
        if (k > 0) {
            EXPECT_GT(e, plan[k - 1].extra_samples_per_texel);
        }
    }
    // The budget: the pilot's half again, give or take the rounding to powers of two (at most 2^0.5 either way).
    const double spent = double(plannedExtraSamples(plan));
    const double wanted = double(budget - pilot) * double(sigma.size());
    EXPECT_GT(spent, wanted / std::sqrt(2.0));
    EXPECT_LT(spent, wanted * std::sqrt(2.0));
    // Monotone in sigma, and the cap (8x the budget in all) holds.
    std::vector<size_t> order(sigma.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sigma[a] < sigma[b]; });
    for (size_t k = 1; k < order.size(); ++k) EXPECT_LE(extra[order[k - 1]], extra[order[k]]);
    for (uint32_t e : extra) EXPECT_LE(pilot + e, 8 * budget * 1.42);
    // What it buys: the summed variance sigma^2 / n against uniform sampling at the same spent samples.
    double adaptive_variance = 0.0, uniform_variance = 0.0;
    const double uniform_samples = pilot + spent / double(sigma.size());
    for (size_t t = 0; t < sigma.size(); ++t) {
        adaptive_variance += double(sigma[t]) * sigma[t] / double(pilot + extra[t]);
        uniform_variance += double(sigma[t]) * sigma[t] / uniform_samples;
    }
    // The optimum (n proportional to sigma, no pilot floor, no rounding) is (mean sigma)^2 / mean(sigma^2)
    // = exp(-1.2^2) = 0.24 of uniform here; the pilot floor and the classes keep part of that.
    EXPECT_LT(adaptive_variance, 0.6 * uniform_variance);
}

TEST(AdaptiveSampling, ClassesAreWholeFootprintsAndQuietTexelsGetNothing) {
    std::vector<float> sigma = {0.0f, std::nanf(""), 0.01f, 1.0f, 1.0f, 10.0f};
    const std::vector<AdaptiveClass> plan = planAdaptiveSamples(sigma, 16, 32, {4, 8.0});
    const std::vector<uint32_t> extra = extraPerTexel(plan, sigma.size());
    EXPECT_EQ(extra[0], 0u);  // no noise: nothing to gain
    EXPECT_EQ(extra[1], 0u);  // no estimate: nothing
    EXPECT_EQ(extra[2], 0u);  // far quieter than the rest
    EXPECT_EQ(extra[3], extra[4]);
    EXPECT_GT(extra[5], extra[3]);
    for (uint32_t e : extra) EXPECT_EQ(e % 4, 0u);
    EXPECT_LE(16 + extra[5], 8 * 32);  // the loud texel is capped at 8x the budget
    // Nothing to plan: no budget beyond the pilot, or no noise anywhere.
    EXPECT_TRUE(planAdaptiveSamples(sigma, 32, 32).empty());
    EXPECT_TRUE(planAdaptiveSamples({0.0f, 0.0f}, 16, 32).empty());
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

}  // namespace
}  // namespace gusuku::bake

// The sun's state and strength from lit against site-shadowed ground (issue 41 items 1 and 2;
// gusuku/maths/sun_evidence.h), on samples whose ratios follow the model in closed form: shadowed ratio = g, lit
// ratio = g (1 + s q), with a camera gain g the estimator never sees, a spread of sun shares q, multiplicative noise
// (texture, albedo error) and outliers (pedestrians, walls standing in front). The GPU side is held to these
// functions by tests/test_runtime_sun_evidence.cpp.

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/maths/sun_evidence.h"

namespace gusuku {
namespace {

struct SampleSet {
    double gain = 0.37;         // the camera's gain (exposure error, tone curve): unknown to the estimator
    double strength = 1.0;      // s
    int shadowed = 600;
    int lit = 1400;
    double noise_log2 = 0.15;   // one sigma of texture and albedo error, stops
    double outliers = 0.0;      // fraction of each side replaced by an unrelated brightness
    uint32_t seed = 7;
};

std::vector<SunEvidenceSample> samplesOf(const SampleSet& set) {
    std::mt19937 random(set.seed);
    std::normal_distribution<double> noise(0.0, set.noise_log2);
    std::uniform_real_distribution<double> share(0.8, 4.0), unit(0.0, 1.0), wild(-3.0, 3.0);
    std::vector<SunEvidenceSample> samples;
    auto add = [&](SunEvidenceSampleKind kind, double ratio, double q) {
        SunEvidenceSample sample;
        sample.kind = kind;
        sample.log2_ratio = float(unit(random) < set.outliers ? wild(random) : std::log2(ratio) + noise(random));
        sample.sun_share = float(q);
        samples.push_back(sample);
    };
    for (int i = 0; i < set.shadowed; ++i) add(SunEvidenceSampleKind::kShadowed, set.gain, share(random));
    for (int i = 0; i < set.lit; ++i) {
        const double q = share(random);
        add(SunEvidenceSampleKind::kLit, set.gain * (1.0 + set.strength * q), q);
    }
    for (int i = 0; i < 300; ++i) samples.push_back({});  // sky, walls: not on the ground
    return samples;
}

TEST(SunEvidence, QuantileIsInterpolatedWithinItsBin) {
    std::vector<uint32_t> counts(kSunEvidenceBins, 0);
    counts[10] = 4;  // bin 10 spans [-0.5 + 10 x 0.05, + 0.05) = [0.0, 0.05)
    EXPECT_NEAR(sunEvidenceQuantile(counts, 0.5, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), 0.025, 1e-12);
    EXPECT_NEAR(sunEvidenceQuantile(counts, 0.25, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), 0.0125,
                1e-12);
    EXPECT_EQ(sunEvidenceBin(-100.0, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), 0u);
    EXPECT_EQ(sunEvidenceBin(100.0, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), kSunEvidenceBins - 1);
    EXPECT_EQ(sunEvidenceBin(std::nan(""), kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), 0u);
}

TEST(SunEvidence, AClearSunIsOutAtFullStrength) {
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf({}));
    EXPECT_EQ(estimate.cue, SunEvidenceCue::kSiteShadowBoundary);
    EXPECT_NEAR(estimate.shade_log2_ratio, std::log2(0.37), 0.05);
    EXPECT_NEAR(estimate.evidence.sun_strength, 1.0, 0.10);
    EXPECT_GT(estimate.evidence.sun_out_probability, 0.99f);
    EXPECT_GT(estimate.evidence.confidence, 0.8f);
    EXPECT_EQ(estimate.shadowed_samples, 600u);
    EXPECT_EQ(estimate.lit_samples, 1400u);
}

TEST(SunEvidence, AHiddenSunIsInWhateverTheCameraGain) {
    for (double gain : {0.05, 0.37, 3.0}) {
        SampleSet set;
        set.gain = gain;
        set.strength = 0.0;
        const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
        EXPECT_EQ(estimate.cue, SunEvidenceCue::kSiteShadowBoundary) << gain;
        EXPECT_LT(estimate.evidence.sun_out_probability, 0.05f) << gain;
        EXPECT_GT(estimate.evidence.confidence, 0.8f) << gain;
        EXPECT_NEAR(estimate.strength, 0.0, 0.05) << gain;
        EXPECT_LT(estimate.evidence.sun_strength, 0.0f) << gain;  // not out: no strength measured
    }
}

TEST(SunEvidence, AThinCloudsThirdIsOutAndMeasuredWithinTwentyPercent) {
    SampleSet set;
    set.strength = 1.0 / 3.0;
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
    EXPECT_GT(estimate.evidence.sun_out_probability, 0.95f);
    EXPECT_NEAR(estimate.evidence.sun_strength, 1.0 / 3.0, 0.2 / 3.0);
}

TEST(SunEvidence, OutliersOnBothSidesMoveNeitherMedianFar) {
    SampleSet set;
    set.outliers = 0.25;
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
    EXPECT_NEAR(estimate.evidence.sun_strength, 1.0, 0.2);
    EXPECT_GT(estimate.evidence.sun_out_probability, 0.95f);
}

TEST(SunEvidence, NoBoundaryInViewGivesNoCueAndNoConfidence) {
    SampleSet all_lit;
    all_lit.shadowed = 0;
    SampleSet all_shade;
    all_shade.lit = 0;
    SampleSet a_few;
    a_few.shadowed = int(kSunEvidenceMinSamples) - 1;
    for (const SampleSet& set : {all_lit, all_shade, a_few}) {
        const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
        EXPECT_EQ(estimate.cue, SunEvidenceCue::kNone);
        EXPECT_EQ(estimate.evidence.confidence, 0.0f);
        EXPECT_EQ(estimate.evidence.sun_out_probability, 0.5f);
        EXPECT_LT(estimate.evidence.sun_strength, 0.0f);
    }
    EXPECT_EQ(estimateSunEvidence(std::vector<SunEvidenceSample>{}).cue, SunEvidenceCue::kNone);
}

TEST(SunEvidence, FewerSamplesAndMoreNoiseGiveLessConfidence) {
    SampleSet many;
    SampleSet few;
    few.shadowed = few.lit = 64;
    SampleSet noisy;
    noisy.noise_log2 = 0.8;
    noisy.shadowed = noisy.lit = 300;
    SampleSet tidy = noisy;
    tidy.noise_log2 = 0.15;
    EXPECT_LT(estimateSunEvidence(samplesOf(few)).evidence.confidence,
              estimateSunEvidence(samplesOf(many)).evidence.confidence);
    EXPECT_LT(estimateSunEvidence(samplesOf(noisy)).evidence.confidence,
              estimateSunEvidence(samplesOf(tidy)).evidence.confidence);
}

TEST(SunEvidence, LitSamplesWithLittleSunAreLeftOut) {
    SampleSet set;
    std::vector<SunEvidenceSample> samples = samplesOf(set);
    for (SunEvidenceSample& sample : samples)
        if (sample.kind == SunEvidenceSampleKind::kLit) sample.sun_share = float(kSunEvidenceMinSunShare) * 0.5f;
    const SunEvidenceEstimate estimate = estimateSunEvidence(samples);
    EXPECT_EQ(estimate.lit_samples, 0u);
    EXPECT_EQ(estimate.cue, SunEvidenceCue::kNone);
}

}  // namespace
}  // namespace gusuku

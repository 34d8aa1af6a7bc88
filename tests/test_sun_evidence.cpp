// The sun's state and strength from lit against site-shadowed ground (issue 41 items 1 and 2;
// gusuku/maths/sun_evidence.h), on samples whose ratios follow the model in closed form: shadowed ratio = g, lit
// ratio = g (1 + s q), with a camera gain g the estimator never sees, a spread of sun shares q, multiplicative noise
// (texture, albedo error) and outliers (pedestrians, walls standing in front). The GPU side is held to these
// functions by tests/test_runtime_sun_evidence.cpp.

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/maths/sun_cue_choice.h"
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
    // The camera's response, display = scale x light^power, and the predicted levels' spread: each sample's cell is
    // one of two albedos (or sky lights) this many stops apart.
    double response_scale = 1.0, response_power = 1.0;
    double predicted_spread_log2 = 0.0;
};

std::vector<SunEvidenceSample> samplesOf(const SampleSet& set) {
    std::mt19937 random(set.seed);
    std::normal_distribution<double> noise(0.0, set.noise_log2);
    std::uniform_real_distribution<double> share(0.8, 4.0), unit(0.0, 1.0), wild(-3.0, 3.0);
    std::vector<SunEvidenceSample> samples;
    auto add = [&](SunEvidenceSampleKind kind, double ratio, double q) {
        SunEvidenceSample sample;
        sample.kind = kind;
        // x: the cell's predicted level; the camera shows scale (x + log2 ratio)^power in log2, r = that - x.
        const double x =
            set.predicted_spread_log2 > 0.0 ? (unit(random) < 0.5 ? -0.5 : 0.5) * set.predicted_spread_log2 : 0.0;
        const double shown = std::log2(set.response_scale) + set.response_power * (x + std::log2(ratio));
        sample.log2_ratio = float(unit(random) < set.outliers ? wild(random) : shown - x + noise(random));
        sample.sun_share = float(q);
        sample.log2_predicted = float(x);
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

// A contrasty tone curve (1.15 x^1.25, the bench's cool_contrast) over cells of two albedos a stop apart: the shade's
// ratios run 0.25 stop higher on the lighter cells, which gives the power; the strength is then read through it.
// Read as a linear camera's (power 1), the clear sun measured s ~1.5.
TEST(SunEvidence, AContrastyResponseIsFittedOnTheShadeAndUndone) {
    for (double strength : {1.0, 1.0 / 3.0}) {
        SampleSet set;
        set.strength = strength;
        set.response_scale = 1.15;
        set.response_power = 1.25;
        set.predicted_spread_log2 = 1.0;
        const std::vector<SunEvidenceSample> samples = samplesOf(set);
        const SunEvidenceEstimate estimate = estimateSunEvidence(samples);
        EXPECT_NEAR(estimate.response_gamma, 1.25, 0.05) << strength;
        EXPECT_NEAR(estimate.evidence.sun_strength, strength, 0.1 * strength) << strength;
        std::vector<SunEvidenceSample> unfitted = samples;
        for (SunEvidenceSample& sample : unfitted) sample.log2_predicted = 0.0f;
        EXPECT_GT(estimateSunEvidence(unfitted).strength, 1.3 * strength) << strength;
    }
}

// One albedo in the shade cannot tell a tone curve from the light: no power is fitted (1), and a linear camera's
// spread fits 1 within the noise.
TEST(SunEvidence, AUniformShadeFitsNoResponseAndALinearCameraFitsOne) {
    SampleSet uniform;
    uniform.response_power = 1.25;
    EXPECT_EQ(estimateSunEvidence(samplesOf(uniform)).response_gamma, 1.0f);
    SampleSet linear;
    linear.predicted_spread_log2 = 1.0;
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(linear));
    EXPECT_NEAR(estimate.response_gamma, 1.0, 0.05);
    EXPECT_NEAR(estimate.evidence.sun_strength, 1.0, 0.1);
}

TEST(SunEvidence, OutliersOnBothSidesMoveNeitherMedianFar) {
    SampleSet set;
    set.outliers = 0.25;
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
    EXPECT_NEAR(estimate.evidence.sun_strength, 1.0, 0.2);
    EXPECT_GT(estimate.evidence.sun_out_probability, 0.95f);
}

TEST(SunEvidence, NoBoundaryInViewGivesNoConfidence) {
    SampleSet all_lit;
    all_lit.shadowed = 0;
    SampleSet all_shade;
    all_shade.lit = 0;
    SampleSet a_few;
    a_few.shadowed = int(kSunEvidenceMinSamples) - 1;
    for (const SampleSet& set : {all_lit, all_shade, a_few}) {
        const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(set));
        // Lit ground alone is the metered ground's, which the filter takes only from an app with a metered exposure.
        EXPECT_EQ(estimate.cue, set.lit > 0 ? SunEvidenceCue::kMeteredGround : SunEvidenceCue::kNone);
        EXPECT_EQ(estimate.evidence.confidence, 0.0f);
        EXPECT_EQ(sunEvidenceForFilter(estimate, false).cue, SunEvidenceCue::kNone);
        EXPECT_EQ(sunEvidenceForFilter(estimate, false).evidence.confidence, 0.0f);
    }
    const SunEvidenceEstimate nothing = estimateSunEvidence(std::vector<SunEvidenceSample>{});
    EXPECT_EQ(nothing.cue, SunEvidenceCue::kNone);
    EXPECT_EQ(nothing.evidence.sun_out_probability, 0.5f);
    EXPECT_LT(nothing.evidence.sun_strength, 0.0f);
    EXPECT_EQ(sunEvidenceForFilter(nothing, true).cue, SunEvidenceCue::kNone);
}

// No boundary in view: the lit ground against the exposure (g = 1, a metered camera) reads s itself, as
// lit / predicted-without-sun = 1 + s q; a camera whose gain is off by 1.4 stops (g 0.37) is why it is opt-in.
TEST(SunEvidence, LitGroundAloneIsReadAgainstAMeteredExposure) {
    for (double strength : {1.0, 1.0 / 3.0, 0.0}) {
        SampleSet metered;
        metered.gain = 1.0;
        metered.shadowed = 0;
        metered.strength = strength;
        const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf(metered));
        EXPECT_EQ(estimate.cue, SunEvidenceCue::kMeteredGround) << strength;
        EXPECT_NEAR(estimate.strength, strength, 0.05 + 0.1 * strength) << strength;
        EXPECT_EQ(estimate.evidence.sun_out_probability >= 0.5f, strength > 0.0) << strength;
        const SunCueChoice choice = sunEvidenceForFilter(estimate, true);
        EXPECT_EQ(choice.cue, SunEvidenceCue::kMeteredGround) << strength;
        EXPECT_GT(choice.evidence.confidence, 0.3f) << strength;
        EXPECT_LE(choice.evidence.confidence, kMeteredGroundConfidence) << strength;
        EXPECT_EQ(choice.evidence.sun_out_probability, estimate.evidence.sun_out_probability) << strength;
    }
    SampleSet unmetered;  // g 0.37: a clear sun's lit ground at 0.37 (1 + q) reads as a hidden sun
    unmetered.shadowed = 0;
    EXPECT_LT(estimateSunEvidence(samplesOf(unmetered)).evidence.sun_out_probability, 0.5f);
}

TEST(SunEvidence, TheBoundaryDecidesWhateverTheExposure) {
    const SunEvidenceEstimate estimate = estimateSunEvidence(samplesOf({}));
    for (bool metered : {false, true}) {
        const SunCueChoice choice = sunEvidenceForFilter(estimate, metered);
        EXPECT_EQ(choice.cue, SunEvidenceCue::kSiteShadowBoundary);
        EXPECT_EQ(choice.evidence.confidence, estimate.evidence.confidence);
        EXPECT_EQ(choice.evidence.sun_strength, estimate.evidence.sun_strength);
    }
    EXPECT_STREQ(sunEvidenceCueName(SunEvidenceCue::kMeteredGround), "metered ground");
    EXPECT_STREQ(sunEvidenceCueName(SunEvidenceCue(7)), "unknown");
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

// A wall across the view: ground at 0 m north of y = 6 m and south of y = 4 m, a 1.5 m block between (cells of
// 0.5 m, the grid's south-west corner at the origin). The camera stands north of it at (5, 15, 3), looking south.
GroundMatchScene steppedScene() {
    GroundMatchScene scene;
    scene.grid.origin_enu_m = {0.0, 0.0};
    scene.grid.cell_m = 0.5;
    scene.grid.columns = 20;
    scene.grid.rows = 24;
    scene.cells.resize(scene.grid.cellCount());
    for (int row = 0; row < scene.grid.rows; ++row)
        for (int column = 0; column < scene.grid.columns; ++column) {
            GroundMatchCell& cell = scene.cells[size_t(row * scene.grid.columns + column)];
            const double north_m = (double(scene.grid.rows - 1 - row) + 0.5) * scene.grid.cell_m;
            cell.ground = true;
            cell.height_m = north_m > 4.0 && north_m < 6.0 ? 1.5f : 0.0f;
        }
    return scene;
}

constexpr double kTop = 1.5;  // the block's height: the highest ground

size_t cellAtEnu(const GroundMatchScene& scene, double east_m, double north_m) {
    const int column = int(std::floor(east_m / scene.grid.cell_m));
    const int row_from_south = int(std::floor(north_m / scene.grid.cell_m));
    return size_t((scene.grid.rows - 1 - row_from_south) * scene.grid.columns + column);
}

// The ray to the ground beyond the wall passes through the block (at y = 6 m it is 0.75 m high, the block 1.5 m):
// that pixel shows the wall's face, not the ground cell the height-field march may settle on (issue 41: such wall
// pixels, read as shaded ground, set the shade's level and hid a clear sun).
TEST(SunEvidence, ARayThroughAStepDoesNotReachTheCellBeyond) {
    const GroundMatchScene scene = steppedScene();
    EXPECT_EQ(sunEvidenceGroundTop(scene), kTop);
    const glm::dvec3 camera(5.0, 15.0, 3.0);
    const glm::dvec3 beyond = glm::dvec3(5.2, 3.1, 0.0) - camera;  // ground south of the block
    EXPECT_FALSE(sunEvidenceRayReachesCell(scene, camera, beyond, cellAtEnu(scene, 5.2, 3.1), kTop));
    // Diagonal rays too (edges crossed on both axes).
    const glm::dvec3 diagonal = glm::dvec3(8.3, 2.2, 0.0) - camera;
    EXPECT_FALSE(sunEvidenceRayReachesCell(scene, camera, diagonal, cellAtEnu(scene, 8.3, 2.2), kTop));
}

TEST(SunEvidence, RaysOntoOpenGroundAndOntoTheStepsTopReachTheirCells) {
    const GroundMatchScene scene = steppedScene();
    const glm::dvec3 camera(5.0, 15.0, 3.0);
    // Ground in front of the block.
    EXPECT_TRUE(sunEvidenceRayReachesCell(scene, camera, glm::dvec3(5.2, 8.1, 0.0) - camera,
                                          cellAtEnu(scene, 5.2, 8.1), kTop));
    // The block's top, 0.3 m behind its north edge: the ray crosses y = 6 m at 1.54 m, above the 1.5 m top.
    EXPECT_TRUE(sunEvidenceRayReachesCell(scene, camera, glm::dvec3(5.2, 5.7, 1.5) - camera,
                                          cellAtEnu(scene, 5.2, 5.7), kTop));
    // Beyond the block, seen over it from high enough: from 20 m up, the ray to (5.2, 2.1) clears its south edge
    // (y = 4 m) at 2.9 m.
    const glm::dvec3 high(5.0, 15.0, 20.0);
    EXPECT_TRUE(
        sunEvidenceRayReachesCell(scene, high, glm::dvec3(5.2, 2.1, 0.0) - high, cellAtEnu(scene, 5.2, 2.1), kTop));
}

}  // namespace
}  // namespace gusuku

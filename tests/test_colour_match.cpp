// The runtime's colour match (gusuku/maths/colour_match.h, docs/design.md 4): the CPU double reference against hand
// values (docs/design.md 4's pinned direction case, the sampling grid, the smoothing's step response), then the GPU
// against that reference: the statistics pass (shaders/runtime/colour_statistics*.comp, recorded by the
// runtime's ColourStatisticsPass) on made-up camera frames, and the GLSL transfer (shaders/include/
// colour_match.glsl, through shaders/tests/colour_match_probe.comp) over a grid of colours in both modes. The
// failure modes of docs/design.md 4 each have a case: a flat frame, a black frame, a clipped white frame, a frame of
// sky only, a step change of the camera (no flash), a reset; and out-of-gamut and non-finite inputs.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "colour_match_interface.h"
#include "colour_match_probe_comp_spv.h"
#include "colour_statistics_pass.h"
#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/vulkan_context.h"

namespace gusuku {
namespace {

using glm::dvec3;
using shader_interface::ColourMatchState;

// ---- Helpers -----------------------------------------------------------------------------------------------

ColourMatchParameters parametersFromState(const ColourMatchState& state) {
    ColourMatchParameters parameters;
    parameters.mode = ColourMatchMode(state.mode);
    for (int c = 0; c < 3; ++c) {
        parameters.source.mean[c] = state.source_lab_mean[c];
        parameters.source.standard_deviation[c] = state.source_lab_sigma[c];
        parameters.target.lab_mean[c] = state.camera_lab_mean[c];
        parameters.target.lab_variance[c] = state.camera_lab_variance[c];
    }
    parameters.target.valid = state.camera_valid != 0;
    parameters.target.frames_accepted = state.frames_accepted;
    parameters.gain_limit = state.gain_limit;
    return parameters;
}

ColourMatchState stateFor(ColourMatchMode mode, const dvec3& source_mean, const dvec3& source_sigma,
                          const dvec3& target_mean, const dvec3& target_sigma, float gain_limit) {
    ColourMatchState state{};
    for (int c = 0; c < 3; ++c) {
        state.source_lab_mean[c] = float(source_mean[c]);
        state.source_lab_sigma[c] = float(source_sigma[c]);
        state.camera_lab_mean[c] = float(target_mean[c]);
        state.camera_lab_variance[c] = float(target_sigma[c] * target_sigma[c]);
    }
    state.mode = uint32_t(mode);
    state.gain_limit = gain_limit;
    state.camera_valid = 1;
    state.frames_accepted = 1;
    return state;
}

// docs/design.md 4's pinned example: src mu (50,0,0) sigma (10,5,5), tgt mu (60,5,-5) sigma (20,5,5).
ColourMatchState designExampleState(ColourMatchMode mode) {
    return stateFor(mode, dvec3(50, 0, 0), dvec3(10, 5, 5), dvec3(60, 5, -5), dvec3(20, 5, 5), 2.0f);
}

bool isFinite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// A camera frame as packed RGBA8 words (R in the low byte).
struct CameraFrame {
    uint32_t width = 0, height = 0;
    std::vector<uint32_t> words;
    std::span<const uint8_t> bytes() const {
        return {reinterpret_cast<const uint8_t*>(words.data()), words.size() * 4};
    }
};

uint32_t packRgba(int r, int g, int b) {
    auto byte = [](int v) { return uint32_t(std::clamp(v, 0, 255)); };
    return byte(r) | byte(g) << 8 | byte(b) << 16 | 255u << 24;
}

/// Something like a photo: colour gradients, a soft blob, per-pixel noise, a blown-out sun patch (255s) and
/// black letterbox rows (all 0), both of which the statistics must leave out.
CameraFrame realLookingFrame(uint32_t width, uint32_t height, uint32_t seed) {
    CameraFrame frame{width, height, std::vector<uint32_t>(size_t(width) * height)};
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, 6.0);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const double u = (x + 0.5) / width, v = (y + 0.5) / height;
            const double blob = std::exp(-((u - 0.3) * (u - 0.3) + (v - 0.6) * (v - 0.6)) / 0.02);
            int r = int(40 + 160 * u + 50 * blob + noise(random));
            int g = int(60 + 120 * v + 20 * std::sin(12 * u) + noise(random));
            int b = int(90 + 60 * (1 - v) - 40 * blob + noise(random));
            // Keep the body away from 0 and 255 so only the regions below are clipped.
            r = std::clamp(r, 1, 254), g = std::clamp(g, 1, 254), b = std::clamp(b, 1, 254);
            const bool letterbox = y < height / 12 || y >= height - height / 12;
            const bool sun = (u - 0.8) * (u - 0.8) + (v - 0.25) * (v - 0.25) < 0.004;
            frame.words[size_t(y) * width + x] =
                letterbox ? packRgba(0, 0, 0) : sun ? packRgba(255, 250, 240) : packRgba(r, g, b);
        }
    }
    return frame;
}

/// Every pixel the same colour plus uniform noise of +-noise_amplitude per channel (0: flat).
CameraFrame uniformFrame(uint32_t width, uint32_t height, int r, int g, int b, int noise_amplitude = 0,
                         uint32_t seed = 1) {
    CameraFrame frame{width, height, std::vector<uint32_t>(size_t(width) * height)};
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> noise(-noise_amplitude, noise_amplitude);
    for (uint32_t& word : frame.words)
        word = noise_amplitude == 0 ? packRgba(r, g, b) : packRgba(r + noise(random), g + noise(random), b + noise(random));
    return frame;
}

void expectNear(const dvec3& actual, const dvec3& expected, double tolerance, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << what << ", channel " << c;
}

dvec3 toDvec3(const shader_interface::vec4& v) { return dvec3(v[0], v[1], v[2]); }

// ---- CPU reference: hand values ----------------------------------------------------------------------------

TEST(ColourMatchReference, DesignDirectionCaseInBothModes) {
    // sigma ratio target / source in L: 20 / 10 = 2, so (60 - 50) * 2 + 60 = 80; a, b: gain 1, (5 - 0) + 5 = 10,
    // (-5 - 0) - 5 = -10. Preserve keeps a, b spread (gain 1 here anyway) and shifts by (5, -5), length 7.07 <
    // the 15 limit: the same answer.
    for (ColourMatchMode mode : {ColourMatchMode::kPaper, ColourMatchMode::kPreserve}) {
        const ColourMatchParameters parameters = parametersFromState(designExampleState(mode));
        expectNear(colourMatchTransferLab(dvec3(60, 5, -5), parameters), dvec3(80, 10, -10), 1e-9, "direction");
        // The mean maps to the target mean.
        expectNear(colourMatchTransferLab(dvec3(50, 0, 0), parameters), dvec3(60, 5, -5), 1e-9, "mean");
    }
}

TEST(ColourMatchReference, ModesDifferInChromaSpreadAndWhiteBalanceBound) {
    // Source a, b spread 10, target 5: the paper halves the chroma around the mean, preserve keeps it.
    const ColourMatchState state = stateFor(ColourMatchMode::kPaper, dvec3(50, 0, 0), dvec3(10, 10, 10),
                                            dvec3(50, 0, 0), dvec3(10, 5, 5), 4.0f);
    ColourMatchParameters paper = parametersFromState(state);
    ColourMatchParameters preserve = paper;
    preserve.mode = ColourMatchMode::kPreserve;
    expectNear(colourMatchTransferLab(dvec3(50, 20, -20), paper), dvec3(50, 10, -10), 1e-9, "paper");
    expectNear(colourMatchTransferLab(dvec3(50, 20, -20), preserve), dvec3(50, 20, -20), 1e-9, "preserve");
    // A sky frame's white balance (a, b) = (-3, -40) from a neutral source: the paper moves all the way,
    // preserve by kColourMatchMaxWhiteBalanceShift along the same direction.
    preserve.target.lab_mean = dvec3(50, -3, -40);
    paper.target.lab_mean = preserve.target.lab_mean;
    expectNear(colourMatchTransferLab(dvec3(50, 0, 0), paper), dvec3(50, -3, -40), 1e-5, "paper sky");
    const double shrink = kColourMatchMaxWhiteBalanceShift / std::sqrt(9.0 + 1600.0);
    expectNear(colourMatchTransferLab(dvec3(50, 0, 0), preserve), dvec3(50, -3 * shrink, -40 * shrink), 1e-5,
               "preserve sky");
}

TEST(ColourMatchReference, GainIsFlooredAndClamped) {
    // Source sigma 0 (flat): floored at 0.01, gain 20 / 0.01 clamped to g = 2. Target sigma 0: gain 1/2.
    ColourMatchParameters parameters =
        parametersFromState(stateFor(ColourMatchMode::kPaper, dvec3(50, 0, 0), dvec3(0, 0, 0), dvec3(50, 0, 0),
                                     dvec3(20, 20, 20), 2.0f));
    expectNear(colourMatchTransferLab(dvec3(60, 10, 10), parameters), dvec3(70, 20, 20), 1e-5, "floor");
    parameters.source.standard_deviation = glm::vec3(10.0f);
    parameters.target.lab_variance = dvec3(0.0);
    expectNear(colourMatchTransferLab(dvec3(60, 10, 10), parameters), dvec3(55, 5, 5), 1e-5, "flat target");
}

TEST(ColourMatchReference, GamutMappingKeepsLightnessAndHue) {
    // Strongly saturated Lab colours far outside sRGB: after mapping, linear RGB in [0, 1] (to rounding), L
    // unchanged, hue unchanged, chroma reduced; an in-gamut colour passes unchanged.
    for (const dvec3 lab : {dvec3(50, 120, 40), dvec3(30, -90, -100), dvec3(90, 10, 130), dvec3(5, 60, -60)}) {
        const dvec3 mapped = colourMatchChromaIntoGamut(lab);
        const dvec3 rgb = linearRec709FromLab(mapped);
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(rgb[c], -1e-5) << lab.x << " " << lab.y << " " << lab.z;
            EXPECT_LE(rgb[c], 1.0 + 1e-5) << lab.x << " " << lab.y << " " << lab.z;
        }
        EXPECT_EQ(mapped.x, lab.x);
        EXPECT_NEAR(std::atan2(mapped.z, mapped.y), std::atan2(lab.z, lab.y), 1e-12);
        EXPECT_LT(std::hypot(mapped.y, mapped.z), std::hypot(lab.y, lab.z));
        // Maximal to the bisection's resolution: 1/2^12 more chroma is out of gamut (or within tolerance).
        const double more = 1.0 + 2.0 / (1 << kColourMatchGamutSteps);
        const dvec3 beyond = linearRec709FromLab(dvec3(mapped.x, mapped.y * more, mapped.z * more));
        EXPECT_TRUE(glm::any(glm::lessThan(beyond, dvec3(-1e-6))) || glm::any(glm::greaterThan(beyond, dvec3(1 + 1e-6))))
            << lab.x << " " << lab.y << " " << lab.z;
    }
    const dvec3 in_gamut = labFromLinearRec709(dvec3(0.2, 0.4, 0.6));
    EXPECT_EQ(colourMatchChromaIntoGamut(in_gamut), in_gamut);
    // L out of [0, 100] is clamped: white above 100 maps to L = 100, a and b to 0 (only grey is in gamut there).
    const dvec3 bright = colourMatchChromaIntoGamut(dvec3(130, 20, 20));
    EXPECT_EQ(bright.x, 100.0);
    EXPECT_NEAR(std::hypot(bright.y, bright.z), 0.0, 0.05);
}

TEST(ColourMatchReference, NonFiniteAndHugeInputGiveDisplayableOutput) {
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    for (ColourMatchMode mode : {ColourMatchMode::kOff, ColourMatchMode::kPaper, ColourMatchMode::kPreserve}) {
        const ColourMatchParameters parameters = parametersFromState(designExampleState(mode));
        for (const dvec3 rgb : {dvec3(nan, 0.5, 0.5), dvec3(inf, 1, 2), dvec3(-inf, -1, 0), dvec3(1e30, 0, 0),
                                dvec3(50, 50, 50)}) {
            const dvec3 out = applyColourMatch(rgb, parameters);
            EXPECT_TRUE(isFinite(out));
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(out, dvec3(0))) && glm::all(glm::lessThanEqual(out, dvec3(1))));
        }
    }
}

TEST(ColourMatchReference, SamplingGrid) {
    const ColourStatisticsGrid g8 = colourStatisticsGrid(1280, 720, 8);
    EXPECT_EQ(g8.offset, 4u);
    EXPECT_EQ(g8.samples_x, 160u);  // x = 4, 12, ..., 1276
    EXPECT_EQ(g8.samples_y, 90u);
    const ColourStatisticsGrid g3 = colourStatisticsGrid(1280, 720, 3);
    EXPECT_EQ(g3.offset, 1u);
    EXPECT_EQ(g3.samples_x, 427u);  // x = 1 + 3 i <= 1279
    EXPECT_EQ(g3.samples_y, 240u);  // y = 1 + 3 j <= 718
    const ColourStatisticsGrid g1 = colourStatisticsGrid(7, 5, 1);
    EXPECT_EQ(g1.sampleCount(), 35u);
    EXPECT_THROW(colourStatisticsGrid(1280, 720, 0), std::invalid_argument);
    EXPECT_THROW(colourStatisticsGrid(4, 720, 5), std::invalid_argument);
    EXPECT_EQ(colourStatisticsMinValidSamples(14400), 720u);  // 5 %
    EXPECT_EQ(colourStatisticsMinValidSamples(100), 16u);     // the floor
    EXPECT_EQ(colourStatisticsMinValidSamples(4), 4u);        // never more than there are
}

TEST(ColourMatchReference, SmoothingStepResponse) {
    // Alpha = 1 / T: a step from m0 to m1 leaves (1 - 1/T)^k of the jump after k frames.
    const double alpha = colourStatisticsSmoothingWeight(8.0);
    EXPECT_EQ(alpha, 0.125);
    EXPECT_EQ(colourStatisticsSmoothingWeight(0.5), 1.0);
    CameraColourStatistics a{dvec3(40, 0, 0), dvec3(10, 2, 2), 1000, 0};
    CameraColourStatistics b{dvec3(80, 10, -20), dvec3(20, 4, 4), 1000, 0};
    SmoothedColourStatistics state = smoothColourStatistics({}, a, 50, alpha);
    EXPECT_TRUE(state.valid);
    EXPECT_EQ(state.lab_mean, a.lab_mean);  // first frame taken as it is
    for (int k = 1; k <= 5; ++k) {
        state = smoothColourStatistics(state, b, 50, alpha);
        const double left = std::pow(1.0 - alpha, k);
        expectNear(state.lab_mean, b.lab_mean + left * (a.lab_mean - b.lab_mean), 1e-12, "step");
        expectNear(state.lab_variance, b.lab_sigma * b.lab_sigma + left * (a.lab_sigma * a.lab_sigma - b.lab_sigma * b.lab_sigma),
                   1e-12, "variance");
    }
    // Too few valid samples: kept. Reset: start over, invalid until a frame is accepted.
    const CameraColourStatistics sparse{dvec3(0), dvec3(0), 10, 990};
    const SmoothedColourStatistics kept = smoothColourStatistics(state, sparse, 50, alpha);
    EXPECT_EQ(kept.lab_mean, state.lab_mean);
    EXPECT_EQ(kept.frames_accepted, state.frames_accepted);
    EXPECT_FALSE(smoothColourStatistics(state, sparse, 50, alpha, /*reset=*/true).valid);
    EXPECT_EQ(smoothColourStatistics(state, a, 50, alpha, /*reset=*/true).lab_mean, a.lab_mean);
}

TEST(ColourMatchReference, BlendsSlotStatistics) {
    const LabStatistics slots[2] = {{glm::vec3(40, 2, 4), glm::vec3(10, 2, 2)},
                                    {glm::vec3(60, 6, 8), glm::vec3(20, 4, 6)}};
    const float weights[2] = {3.0f, 1.0f};
    const LabStatistics blended = blendLabStatistics(slots, weights);
    expectNear(dvec3(blended.mean), dvec3(45, 3, 5), 1e-5, "mean");
    expectNear(dvec3(blended.standard_deviation), dvec3(12.5, 2.5, 3), 1e-5, "sigma");
}

// ---- GPU ---------------------------------------------------------------------------------------------------

class ColourMatchGpu : public testing::GpuTest {
protected:
    /// Runs the GLSL transfer for these colours (linear RGB for applyColourMatch, Lab for the raw transfer)
    /// with the state in state_buffer. Returns per probe {transferLab, applyColourMatch}.
    std::vector<std::pair<dvec3, dvec3>> runProbe(const GpuBuffer& state_buffer, const std::vector<dvec3>& rgb,
                                                  const std::vector<dvec3>& lab) {
        const uint32_t count = uint32_t(rgb.size());
        std::vector<glm::vec4> inputs;
        for (uint32_t i = 0; i < count; ++i) {
            inputs.push_back(glm::vec4(glm::vec3(rgb[i]), 0.0f));
            inputs.push_back(glm::vec4(glm::vec3(lab[i]), 0.0f));
        }
        GpuBuffer input_buffer(context(), inputs.size() * sizeof(glm::vec4));
        input_buffer.uploadVector(inputs);
        GpuBuffer output_buffer(context(), inputs.size() * sizeof(glm::vec4));
        ComputePipeline probe(context(), kColourMatchProbeCompSpirv, sizeof kColourMatchProbeCompSpirv, 3,
                              sizeof(uint32_t));
        probe.bindBuffers({&state_buffer, &input_buffer, &output_buffer});
        probe.dispatchAndWait(&count, (count + 63) / 64);
        const std::vector<glm::vec4> outputs = output_buffer.downloadVector<glm::vec4>(inputs.size());
        std::vector<std::pair<dvec3, dvec3>> results;
        for (uint32_t i = 0; i < count; ++i)
            results.emplace_back(dvec3(glm::vec3(outputs[2 * i])), dvec3(glm::vec3(outputs[2 * i + 1])));
        return results;
    }

    std::vector<std::pair<dvec3, dvec3>> runProbe(const ColourMatchState& state, const std::vector<dvec3>& rgb,
                                                  const std::vector<dvec3>& lab) {
        GpuBuffer state_buffer(context(), sizeof state);
        state_buffer.upload(&state, sizeof state);
        return runProbe(state_buffer, rgb, lab);
    }

    /// One frame: the source update and the statistics of camera, submitted and waited for.
    ColourMatchState runFrame(ColourStatisticsPass& pass, GpuBuffer& camera, const CameraFrame& frame,
                              ColourMatchMode mode = ColourMatchMode::kPreserve) {
        camera.uploadVector(frame.words);
        const LabStatistics source{glm::vec3(50, 0, 0), glm::vec3(10, 5, 5)};
        context().submitAndWait([&](VkCommandBuffer cmd) {
            pass.recordSourceUpdate(cmd, source, mode, 2.0f);
            pass.record(cmd, camera);
        });
        return pass.readState();
    }
};

TEST_F(ColourMatchGpu, DesignDirectionCaseThroughTheGlsl) {
    for (ColourMatchMode mode : {ColourMatchMode::kPaper, ColourMatchMode::kPreserve}) {
        const auto results = runProbe(designExampleState(mode), {dvec3(0.5)}, {dvec3(60, 5, -5)});
        expectNear(results[0].first, dvec3(80, 10, -10), 1e-4, "GLSL direction");
    }
}

TEST_F(ColourMatchGpu, TransferMatchesTheCpuWithinHalfADeltaE00) {
    // A 9^3 grid of linear colours over [0, 1] plus HDR and out-of-range values, through states that exercise
    // the gain clamp, the floor, a large white-balance shift and gamut mapping; both modes.
    std::vector<dvec3> rgb;
    for (int r = 0; r <= 8; ++r)
        for (int g = 0; g <= 8; ++g)
            for (int b = 0; b <= 8; ++b) rgb.push_back(dvec3(r, g, b) / 8.0 * dvec3(r, g, b) / 8.0);
    for (const dvec3 extra : {dvec3(2.0, 1.5, 0.5), dvec3(8.0), dvec3(-0.2, 0.5, 0.5), dvec3(1e6, 0.0, 0.0)})
        rgb.push_back(extra);
    std::vector<dvec3> lab;
    for (const dvec3& colour : rgb) lab.push_back(labFromLinearRec709(glm::clamp(colour, 0.0, 1.0)));

    const ColourMatchState states[] = {
        designExampleState(ColourMatchMode::kPaper),
        stateFor(ColourMatchMode::kPaper, dvec3(45, 5, 10), dvec3(0, 30, 2), dvec3(65, -10, 30), dvec3(30, 3, 40), 3.0f),
        stateFor(ColourMatchMode::kPaper, dvec3(55, 0, 0), dvec3(15, 8, 8), dvec3(70, -3, -35), dvec3(4, 2, 6), 2.0f),
    };
    double worst = 0.0;
    size_t gamut_mapped = 0;  // colours whose preserve transfer left the gamut and was mapped back
    for (const ColourMatchState& base : states) {
        for (ColourMatchMode mode : {ColourMatchMode::kPaper, ColourMatchMode::kPreserve}) {
            ColourMatchState state = base;
            state.mode = uint32_t(mode);
            const ColourMatchParameters parameters = parametersFromState(state);
            const auto results = runProbe(state, rgb, lab);
            for (size_t i = 0; i < rgb.size(); ++i) {
                const dvec3 expected = applyColourMatch(rgb[i], parameters);
                const dvec3 actual = results[i].second;
                ASSERT_TRUE(isFinite(actual)) << i;
                EXPECT_TRUE(glm::all(glm::greaterThanEqual(actual, dvec3(0))) &&
                            glm::all(glm::lessThanEqual(actual, dvec3(1))));
                const double difference = ciede2000(labFromLinearRec709(expected), labFromLinearRec709(actual));
                worst = std::max(worst, difference);
                EXPECT_LE(difference, 0.5) << "mode " << state.mode << ", rgb " << rgb[i].x << " " << rgb[i].y << " "
                                           << rgb[i].z;
                expectNear(results[i].first, colourMatchTransferLab(lab[i], parameters), 2e-3, "transferLab");
                if (mode == ColourMatchMode::kPreserve) {
                    dvec3 transferred = colourMatchTransferLab(labFromLinearRec709(glm::clamp(rgb[i], 0.0, 1e4)),
                                                               parameters);
                    transferred.x = std::clamp(transferred.x, 0.0, 100.0);
                    if (colourMatchChromaIntoGamut(transferred) != transferred) ++gamut_mapped;
                }
            }
        }
    }
    EXPECT_GT(gamut_mapped, rgb.size() / 4);  // the bisection is exercised, not only the easy path
    std::printf("worst dE00 GPU against CPU over %zu colours x 6 states: %.4f (%zu gamut-mapped)\n", rgb.size(),
                worst, gamut_mapped);
}

TEST_F(ColourMatchGpu, StatisticsMatchTheCpuOnARealLookingFrame) {
    struct Case {
        uint32_t width, height, stride;
    };
    for (const Case c : {Case{1280, 720, 8}, Case{1280, 720, 3}, Case{640, 360, 4}, Case{333, 187, 5}}) {
        const CameraFrame frame = realLookingFrame(c.width, c.height, c.stride);
        const CameraColourStatistics expected = measureCameraColourStatistics(frame.bytes(), c.width, c.height, c.stride);
        ColourStatisticsPass pass(context(), c.width, c.height, c.stride, 8.0f);
        GpuBuffer camera(context(), frame.words.size() * 4);
        const ColourMatchState state = runFrame(pass, camera, frame);
        const std::string what = std::to_string(c.width) + "x" + std::to_string(c.height) + " stride " +
                                 std::to_string(c.stride);
        EXPECT_EQ(state.frame_valid_samples, expected.valid_samples) << what;
        EXPECT_EQ(state.frame_clipped_samples, expected.clipped_samples) << what;
        EXPECT_EQ(state.frame_total_samples, pass.grid().sampleCount()) << what;
        EXPECT_GT(expected.clipped_samples, pass.grid().sampleCount() / 10) << what;  // the frame has clipping
        // Float Lab per sample and float combination against double: 0.01 Lab (a hundredth of a JND).
        expectNear(toDvec3(state.frame_lab_mean), expected.lab_mean, 0.01, what + " mean");
        expectNear(toDvec3(state.frame_lab_sigma), expected.lab_sigma, 0.01, what + " sigma");
        // The first frame is taken as it is.
        EXPECT_EQ(state.camera_valid, 1u);
        EXPECT_EQ(state.frame_accepted, 1u);
        expectNear(toDvec3(state.camera_lab_mean), toDvec3(state.frame_lab_mean), 0.0, what + " first frame");
        // End to end: the transfer the GLSL computes from the pass's own state buffer against the CPU's from the
        // CPU's statistics (runFrame wrote source (50, 0, 0) / (10, 5, 5), preserve, gain limit 2).
        ColourMatchParameters parameters;
        parameters.mode = ColourMatchMode::kPreserve;
        parameters.source = {glm::vec3(50, 0, 0), glm::vec3(10, 5, 5)};
        parameters.target = smoothColourStatistics({}, expected, pass.minValidSamples(), pass.smoothingWeight());
        parameters.gain_limit = 2.0f;
        std::vector<dvec3> rgb, lab;
        for (int i = 0; i <= 10; ++i) {
            rgb.push_back(dvec3(i / 10.0, 0.5 * i / 10.0, 1.0 - i / 10.0));
            lab.push_back(labFromLinearRec709(rgb.back()));
        }
        const auto results = runProbe(pass.stateBuffer(), rgb, lab);
        for (size_t i = 0; i < rgb.size(); ++i)
            EXPECT_LE(ciede2000(labFromLinearRec709(applyColourMatch(rgb[i], parameters)),
                                labFromLinearRec709(results[i].second)),
                      0.5)
                << what << ", colour " << i;
        std::printf("%s: mean %.4f %.4f %.4f (CPU %.4f %.4f %.4f), sigma %.4f %.4f %.4f (CPU %.4f %.4f %.4f)\n",
                    what.c_str(), state.frame_lab_mean[0], state.frame_lab_mean[1], state.frame_lab_mean[2],
                    expected.lab_mean.x, expected.lab_mean.y, expected.lab_mean.z, state.frame_lab_sigma[0],
                    state.frame_lab_sigma[1], state.frame_lab_sigma[2], expected.lab_sigma.x, expected.lab_sigma.y,
                    expected.lab_sigma.z);
    }
}

TEST_F(ColourMatchGpu, HardFramesGiveFiniteBoundedTransfers) {
    constexpr uint32_t width = 320, height = 180, stride = 4;
    ColourStatisticsPass pass(context(), width, height, stride, 8.0f);
    GpuBuffer camera(context(), size_t(width) * height * 4);
    // Probe colours: a grid plus saturated primaries, so gamut mapping is exercised on every state.
    std::vector<dvec3> rgb;
    for (int i = 0; i <= 4; ++i)
        for (int j = 0; j <= 4; ++j)
            for (int k = 0; k <= 4; ++k) rgb.push_back(dvec3(i, j, k) / 4.0);
    std::vector<dvec3> lab;
    for (const dvec3& colour : rgb) lab.push_back(labFromLinearRec709(colour));

    auto checkTransfer = [&](const ColourMatchState& state, const std::string& what) {
        const ColourMatchParameters parameters = parametersFromState(state);
        const dvec3 variance = parameters.target.lab_variance;
        EXPECT_TRUE(isFinite(parameters.target.lab_mean) && isFinite(variance)) << what;
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(variance, dvec3(0.0)))) << what;
        for (ColourMatchMode mode : {ColourMatchMode::kPaper, ColourMatchMode::kPreserve}) {
            ColourMatchParameters with_mode = parameters;
            with_mode.mode = mode;
            const LabTransfer transfer = makeLabTransfer(
                with_mode.source, {glm::vec3(parameters.target.lab_mean), glm::vec3(glm::sqrt(variance))},
                with_mode.gain_limit);
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(std::isfinite(transfer.gain[c])) << what;
                EXPECT_GE(transfer.gain[c], 0.5f) << what;
                EXPECT_LE(transfer.gain[c], 2.0f) << what;
            }
        }
        // Through the GLSL, on the pass's own state buffer (both modes: the pass wrote preserve; paper below).
        for (const auto& [transferred, out] : runProbe(pass.stateBuffer(), rgb, lab)) {
            EXPECT_TRUE(isFinite(transferred)) << what;
            EXPECT_TRUE(isFinite(out)) << what;
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(out, dvec3(0))) && glm::all(glm::lessThanEqual(out, dvec3(1))))
                << what;
        }
    };

    // A black frame first: every sample clipped, nothing accepted, still no target.
    ColourMatchState state = runFrame(pass, camera, uniformFrame(width, height, 0, 0, 0));
    EXPECT_EQ(state.frame_valid_samples, 0u);
    EXPECT_EQ(state.frame_clipped_samples, pass.grid().sampleCount());
    EXPECT_EQ(state.frame_accepted, 0u);
    EXPECT_EQ(state.camera_valid, 0u);
    {
        const auto results = runProbe(pass.stateBuffer(), rgb, lab);
        for (size_t i = 0; i < rgb.size(); ++i) {
            expectNear(results[i].first, lab[i], 1e-4, "identity before a target (Lab)");
            expectNear(results[i].second, rgb[i], 1e-6, "identity before a target");
        }
    }

    // A flat grey frame: zero variance, accepted; the gain is clamped to 1/g, not 0.
    state = runFrame(pass, camera, uniformFrame(width, height, 128, 128, 128));
    EXPECT_EQ(state.frame_accepted, 1u);
    EXPECT_NEAR(state.frame_lab_sigma[0], 0.0, 1e-3);
    checkTransfer(state, "flat");

    // A clipped white frame: nothing accepted, the state kept as the flat frame left it.
    const ColourMatchState before_white = state;
    state = runFrame(pass, camera, uniformFrame(width, height, 255, 255, 255));
    EXPECT_EQ(state.frame_accepted, 0u);
    EXPECT_EQ(state.frame_clipped_samples, pass.grid().sampleCount());
    EXPECT_EQ(toDvec3(state.camera_lab_mean), toDvec3(before_white.camera_lab_mean));
    EXPECT_EQ(toDvec3(state.camera_lab_variance), toDvec3(before_white.camera_lab_variance));
    checkTransfer(state, "white");

    // A black frame after a target: also kept.
    state = runFrame(pass, camera, uniformFrame(width, height, 0, 0, 0));
    EXPECT_EQ(state.frame_accepted, 0u);
    EXPECT_EQ(toDvec3(state.camera_lab_mean), toDvec3(before_white.camera_lab_mean));

    // A frame of sky only, from a reset: uniform blue with slight noise. Tiny spreads, a strong blue mean.
    pass.reset();
    const CameraFrame sky = uniformFrame(width, height, 90, 150, 220, 2, 7);
    state = runFrame(pass, camera, sky);
    const CameraColourStatistics sky_expected = measureCameraColourStatistics(sky.bytes(), width, height, stride);
    EXPECT_EQ(state.frames_accepted, 1u);
    expectNear(toDvec3(state.camera_lab_mean), sky_expected.lab_mean, 0.01, "sky mean");
    EXPECT_LT(sky_expected.lab_mean.z, -25.0);  // really blue
    checkTransfer(state, "sky");
    // Preserve bounds the cast: the source's mean colour moves by at most the white-balance limit in a, b.
    const ColourMatchParameters sky_parameters = parametersFromState(state);
    const dvec3 moved = colourMatchTransferLab(dvec3(sky_parameters.source.mean), sky_parameters);
    EXPECT_LE(std::hypot(moved.y - sky_parameters.source.mean.y, moved.z - sky_parameters.source.mean.z),
              kColourMatchMaxWhiteBalanceShift + 1e-9);
    ColourMatchState paper_state = state;
    paper_state.mode = COLOUR_MATCH_MODE_PAPER;
    for (const auto& [transferred, out] : runProbe(paper_state, rgb, lab)) {
        EXPECT_TRUE(isFinite(transferred) && isFinite(out));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(out, dvec3(0))) && glm::all(glm::lessThanEqual(out, dvec3(1))));
    }
}

TEST_F(ColourMatchGpu, StepChangeMovesTheMeanByAtMostOneOverSmoothingPerFrame) {
    constexpr uint32_t width = 320, height = 180, stride = 4;
    constexpr float smoothing = 8.0f;
    ColourStatisticsPass pass(context(), width, height, stride, smoothing);
    GpuBuffer camera(context(), size_t(width) * height * 4);
    const CameraFrame dim = realLookingFrame(width, height, 11);
    CameraFrame bright = uniformFrame(width, height, 200, 180, 120, 20, 12);
    for (int k = 0; k < 3; ++k) runFrame(pass, camera, dim);
    ColourMatchState state = pass.readState();
    EXPECT_EQ(state.frames_accepted, 3u);

    // The CPU reference follows the same sequence.
    const uint32_t min_valid = pass.minValidSamples();
    const double alpha = pass.smoothingWeight();
    const CameraColourStatistics dim_stats = measureCameraColourStatistics(dim.bytes(), width, height, stride);
    const CameraColourStatistics bright_stats = measureCameraColourStatistics(bright.bytes(), width, height, stride);
    SmoothedColourStatistics reference;
    for (int k = 0; k < 3; ++k) reference = smoothColourStatistics(reference, dim_stats, min_valid, alpha);
    expectNear(toDvec3(state.camera_lab_mean), reference.lab_mean, 0.01, "before the step");

    const double jump = glm::length(bright_stats.lab_mean - dim_stats.lab_mean);
    ASSERT_GT(jump, 20.0);
    for (int k = 1; k <= 10; ++k) {
        const dvec3 previous = toDvec3(state.camera_lab_mean);
        state = runFrame(pass, camera, bright);
        reference = smoothColourStatistics(reference, bright_stats, min_valid, alpha);
        const dvec3 now = toDvec3(state.camera_lab_mean);
        // Each frame moves 1/T of what is left of the jump, never more: no flash.
        EXPECT_LE(glm::length(now - previous), glm::length(bright_stats.lab_mean - previous) / smoothing + 1e-3)
            << "frame " << k;
        EXPECT_LE(glm::length(now - previous), jump / smoothing + 1e-3) << "frame " << k;
        expectNear(now, reference.lab_mean, 0.01, "frame " + std::to_string(k));
        expectNear(toDvec3(state.camera_lab_variance), reference.lab_variance, 0.05, "variance " + std::to_string(k));
    }

    // Reset: the next frame is taken as it is.
    pass.reset();
    state = runFrame(pass, camera, dim);
    EXPECT_EQ(state.frames_accepted, 1u);
    expectNear(toDvec3(state.camera_lab_mean), dim_stats.lab_mean, 0.01, "after reset");
    expectNear(toDvec3(state.camera_lab_variance), dim_stats.lab_sigma * dim_stats.lab_sigma, 0.05, "after reset");
}

TEST_F(ColourMatchGpu, BadInputIsRefused) {
    EXPECT_THROW(ColourStatisticsPass(context(), 1280, 720, 0, 8.0f), RuntimeError);
    ColourStatisticsPass pass(context(), 64, 32, 4, 8.0f);
    GpuBuffer small(context(), 64 * 4);
    EXPECT_THROW(context().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, small); }), RuntimeError);
    const LabStatistics nan_source{glm::vec3(std::numeric_limits<float>::quiet_NaN()), glm::vec3(1.0f)};
    EXPECT_THROW(context().submitAndWait([&](VkCommandBuffer cmd) {
                     pass.recordSourceUpdate(cmd, nan_source, ColourMatchMode::kPaper, 2.0f);
                 }),
                 RuntimeError);
}

// The statistics pass's time on this device, fence-timed (median of 20 submissions of the two dispatches), at
// the frame sizes and strides the runtime uses; printed, not asserted (the machine is shared). Without
// validation, on a context of its own, so the layer's cost is not measured.
TEST(ColourStatisticsTiming, PrintsMedianTimes) {
    VulkanContextOptions options = vulkanOptionsFromEnvironment();
    options.enable_validation = false;
    VulkanContext vulkan(options);
    struct Case {
        uint32_t width, height, stride;
    };
    for (const Case c : {Case{1280, 720, 8}, Case{1280, 720, 4}, Case{640, 360, 8}, Case{640, 360, 4}}) {
        const CameraFrame frame = realLookingFrame(c.width, c.height, 3);
        ColourStatisticsPass pass(vulkan, c.width, c.height, c.stride, 8.0f);
        GpuBuffer camera(vulkan, frame.words.size() * 4);
        camera.uploadVector(frame.words);
        GpuSubmitter submitter(vulkan);
        std::vector<double> milliseconds;
        for (int run = 0; run < 21; ++run) {
            const auto start = std::chrono::steady_clock::now();
            submitter.submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, camera); });
            const auto end = std::chrono::steady_clock::now();
            if (run > 0) milliseconds.push_back(std::chrono::duration<double, std::milli>(end - start).count());
        }
        std::sort(milliseconds.begin(), milliseconds.end());
        const ColourMatchState state = pass.readState();
        EXPECT_EQ(state.frame_total_samples, pass.grid().sampleCount());
        EXPECT_EQ(state.frames_accepted, 21u);
        std::printf("colour statistics %ux%u stride %u (%llu samples) on %s: median %.3f ms, min %.3f, max %.3f\n",
                    c.width, c.height, c.stride, (unsigned long long)pass.grid().sampleCount(),
                    vulkan.deviceDescription().c_str(), (milliseconds[9] + milliseconds[10]) / 2, milliseconds.front(),
                    milliseconds.back());
    }
}

}  // namespace
}  // namespace gusuku

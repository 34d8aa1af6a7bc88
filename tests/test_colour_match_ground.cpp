// The runtime's ground colour match (gusuku/maths/colour_match.h, mode kGround): the camera's pixels of the real ground
// against what the bake set predicts there. A camera frame is synthesised from the prediction itself (every
// ground pixel = known per-channel gains x predicted radiance, sRGB-encoded to 8 bits), so the gain the match
// must find is known in closed form and the only error left is the 8-bit quantisation, whose bound each test
// derives from the frame. Cases: (a) the GPU estimate (shaders/runtime/colour_statistics_ground*.comp through
// ColourStatisticsPass) against the CPU double reference; (b) the analytic gains, the building's output through
// the GLSL transfer and through the whole runtime equal to gains x its unmatched colour; (c) a frame of sky keeps
// the previous gain (identity before any); (d) clipped ground pixels are counted and left out; and a bake set
// without ground albedo refuses the mode with a clear error.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "checker_ground_albedo.h"
#include "colour_match_interface.h"
#include "colour_match_probe_comp_spv.h"
#include "colour_statistics_pass.h"
#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using glm::dvec3;
using shader_interface::ColourMatchState;

constexpr uint32_t kWidth = 640, kHeight = 360, kStatisticsStride = 8;
// The ground kernel's stride for this frame (7: groundMatchStride, pinned below).
const uint32_t kStride = groundMatchStride(kWidth, kHeight, kStatisticsStride);
const dvec3 kSkyLinear(0.35, 0.45, 0.8);

dvec3 toDvec3(const shader_interface::vec4& v) { return dvec3(v[0], v[1], v[2]); }
dvec3 toDvec3(const shader_interface::vec3& v) { return dvec3(v[0], v[1], v[2]); }

// The synthetic bake set (flat ground at z = 0, E_without 2 grey) with a ground albedo of two colours in a
// checker of 1 m squares, so cells differ.
BakeSetData bakeSetWithGroundAlbedo() {
    BakeSetData bake_set = testing::makeSyntheticBakeSet();
    testing::paintCheckerGroundAlbedo(bake_set);
    return bake_set;
}

CameraIntrinsics intrinsics() { return CameraIntrinsics::fromFieldOfView(kWidth, kHeight, 70.0); }

GroundMatchView viewFor(const CameraPose& pose) {
    const CameraIntrinsics k = intrinsics();
    GroundMatchView view;
    view.fx = k.fx;
    view.fy = k.fy;
    view.cx = k.cx;
    view.cy = k.cy;
    view.camera_position_enu = pose.position_enu;
    view.camera_to_enu = pose.camera_to_enu;
    view.sun_direction_enu = glm::normalize(dvec3(0.3, -0.4, 0.8));
    view.sun_shines = true;
    view.sun_irradiance_rgb = dvec3(5.0, 4.8, 4.5);
    view.exposure = 0.25;
    view.slots[0] = 1;
    view.weights[0] = 1.0f;
    return view;
}

// The view the runtime drew a frame with, from what its FrameInfo reports: the sun, the exposure and the slots
// with their blend weights.
GroundMatchView viewReportedBy(const CameraPose& pose, const FrameInfo& info, double exposure) {
    GroundMatchView view = viewFor(pose);
    view.sun_direction_enu = info.sun_direction_enu;
    view.sun_irradiance_rgb = info.sun_irradiance_rgb;
    view.exposure = exposure;
    view.slots[0] = info.slot_a;
    view.weights[0] = info.slot_b >= 0 ? 1.0f - info.slot_b_weight : 1.0f;
    view.slots[1] = info.slot_b;
    view.weights[1] = info.slot_b >= 0 ? info.slot_b_weight : 0.0f;
    return view;
}

// A camera 3 m up looking north and down: the ground fills the lower part, sky the upper.
CameraPose groundPose() { return CameraPose::lookingAt({0.3, -9.0, 3.0}, {0.0, 2.0, 0.0}); }
// The same camera looking at the sky: no ray reaches the ground.
CameraPose skyPose() { return CameraPose::lookingAt({0.3, -9.0, 3.0}, {0.0, 2.0, 12.0}); }

uint8_t encode8(double linear) {
    return uint8_t(std::lround(std::clamp(srgbEncode(std::clamp(linear, 0.0, 1.0)), 0.0, 1.0) * 255.0));
}

struct SynthesisedFrame {
    std::vector<uint8_t> rgba;
    uint64_t ground_pixels = 0;
    /// Derived bound of the estimate's relative error per channel: over the ground samples, the largest
    /// (decode(code + 1/2 step) - decode(code)) / exact, the most 8-bit rounding can move one sample's linear
    /// value relative to its exact one; a ratio of sums of such samples moves by no more.
    dvec3 relative_quantisation_bound{0.0};
};

// Every ground pixel = gains x predicted radiance (8-bit sRGB); other pixels a sky colour.
SynthesisedFrame synthesise(const GroundMatchScene& scene, const GroundMatchView& view, const dvec3& gains) {
    SynthesisedFrame frame;
    frame.rgba.assign(size_t(kWidth) * kHeight * 4, 255);
    const ColourStatisticsGrid grid = colourStatisticsGrid(kWidth, kHeight, kStride);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            uint8_t* pixel = &frame.rgba[(size_t(y) * kWidth + x) * 4];
            const std::optional<size_t> cell = groundMatchCellOfPixel(scene, view, x, y);
            const dvec3 linear = cell ? gains * groundMatchPredictedRadiance(scene, view, *cell) : kSkyLinear;
            for (int c = 0; c < 3; ++c) pixel[c] = encode8(linear[c]);
            if (!cell) continue;
            ++frame.ground_pixels;
            const bool sampled = x % kStride == grid.offset && y % kStride == grid.offset;
            if (!sampled) continue;
            for (int c = 0; c < 3; ++c) {
                const double step = srgbDecode(std::min(1.0, (pixel[c] + 0.5) / 255.0)) - srgbDecode(pixel[c] / 255.0);
                frame.relative_quantisation_bound[c] =
                    std::max(frame.relative_quantisation_bound[c], step / linear[c]);
            }
        }
    return frame;
}

void expectNear(const dvec3& actual, const dvec3& expected, const dvec3& tolerance, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance[c]) << what << " channel " << c;
}

class GroundMatchTest : public ::testing::Test {
protected:
    void SetUp() override {
        bake_set_ = bakeSetWithGroundAlbedo();
        std::optional<GroundMatchScene> scene = groundMatchSceneFrom(bake_set_);
        ASSERT_TRUE(scene);
        scene_ = std::move(*scene);
    }
    BakeSetData bake_set_;
    GroundMatchScene scene_;
};

// ---- CPU reference ------------------------------------------------------------------------------------------

TEST(GroundMatchReference, StrideGivesEnoughSamples) {
    EXPECT_EQ(groundMatchStride(1280, 720, 8), 8u);  // sqrt(921600 / 4096) = 15, never coarser than the stride
    EXPECT_EQ(groundMatchStride(640, 360, 8), 7u);   // 7.5
    EXPECT_EQ(groundMatchStride(96, 54, 8), 1u);     // every pixel of a small frame
    EXPECT_EQ(groundMatchStride(3840, 2160, 8), 8u);  // never coarser than the statistics stride
    EXPECT_EQ(groundMatchStride(3840, 2160, 4), 4u);
}

TEST_F(GroundMatchTest, RayFindsTheGroundCellUnderThePixel) {
    const GroundMatchView view = viewFor(groundPose());
    // The image centre looks at (0, 2, 0) (lookingAt's target): pixel (160, 90)'s centre is (160.5, 90.5), a
    // hair off the axis; its cell must be the one holding a point within a cell of the target.
    const std::optional<size_t> cell = groundMatchCellOfPixel(scene_, view, kWidth / 2 - 1, kHeight / 2 - 1);
    ASSERT_TRUE(cell);
    const glm::dvec2 centre = groundCellCentreEnu(scene_.grid, groundCellFromIndex(scene_.grid, *cell));
    EXPECT_LE(glm::length(centre - glm::dvec2(0.0, 2.0)), 0.5);
    EXPECT_FALSE(groundMatchCellOfPixel(scene_, view, kWidth / 2, 0));  // the top row sees sky
    // Predicted radiance by hand for that cell: exposure albedo / pi (E_without + E_sun cos).
    const GroundMatchCell& ground = scene_.cells[*cell];
    const double cosine = view.sun_direction_enu.z;  // flat ground, normal up
    const dvec3 expected = 0.25 * dvec3(ground.albedo) / 3.14159265358979323846 * (2.0 + view.sun_irradiance_rgb * cosine);
    expectNear(groundMatchPredictedRadiance(scene_, view, *cell), expected, dvec3(1e-6), "prediction");
}

TEST_F(GroundMatchTest, AnalyticGainsAreRecoveredWithinTheQuantisationBound) {
    const GroundMatchView view = viewFor(groundPose());
    // White balance (1.1, 1, 0.8) and an exposure 25 % off: the gains the match must find.
    const dvec3 gains = 1.25 * dvec3(1.1, 1.0, 0.8);
    const SynthesisedFrame frame = synthesise(scene_, view, gains);
    ASSERT_GT(frame.ground_pixels, uint64_t(kWidth) * kHeight / 4);
    const GroundColourEstimate estimate = measureGroundColourGain(frame.rgba, kWidth, kHeight, kStride, scene_, view, 2.0f);
    ASSERT_TRUE(estimate.accepted);
    EXPECT_EQ(estimate.kept_samples, estimate.ground_samples);  // one ratio: every sample in the window
    EXPECT_EQ(estimate.clipped_samples, 0u);
    std::printf("CPU gains %.5f %.5f %.5f (exact %.5f %.5f %.5f), quantisation bound %.5f %.5f %.5f\n",
                estimate.gain.r, estimate.gain.g, estimate.gain.b, gains.r, gains.g, gains.b,
                frame.relative_quantisation_bound.r, frame.relative_quantisation_bound.g,
                frame.relative_quantisation_bound.b);
    expectNear(estimate.gain, gains, gains * frame.relative_quantisation_bound, "gain");
    // The transfer: the building's exposed colour times the gains.
    ColourMatchParameters parameters;
    parameters.mode = ColourMatchMode::kGround;
    parameters.ground = smoothGroundGain({}, estimate, 1.0 / 8.0);
    for (double v : {0.05, 0.2, 0.4}) {
        const dvec3 colour(v, 0.8 * v, 0.6 * v);
        expectNear(applyColourMatch(colour, parameters), colour * estimate.gain, dvec3(1e-7),  // float gain on the GPU
                   "transfer");
    }
}

TEST_F(GroundMatchTest, SkyFrameKeepsThePreviousGainAndClippedPixelsAreLeftOut) {
    const GroundMatchView sky_view = viewFor(skyPose());
    const SynthesisedFrame sky = synthesise(scene_, sky_view, dvec3(1.0));
    EXPECT_EQ(sky.ground_pixels, 0u);
    const GroundColourEstimate none = measureGroundColourGain(sky.rgba, kWidth, kHeight, kStride, scene_, sky_view, 2.0f);
    EXPECT_FALSE(none.accepted);
    EXPECT_EQ(none.ground_samples, 0u);
    const SmoothedGroundGain identity = smoothGroundGain({}, none, 0.125);
    EXPECT_FALSE(identity.valid);
    SmoothedGroundGain previous;
    previous.valid = true;
    previous.frames_accepted = 3;
    previous.gain = dvec3(1.2, 0.9, 0.7);
    const SmoothedGroundGain kept = smoothGroundGain(previous, none, 0.125);
    EXPECT_EQ(kept.gain, previous.gain);
    EXPECT_EQ(kept.frames_accepted, 3u);

    // Clipped: every other sampled ground pixel saturated (255 in red): counted, left out, gain unmoved.
    const GroundMatchView view = viewFor(groundPose());
    const dvec3 gains(1.1, 1.0, 0.9);
    SynthesisedFrame frame = synthesise(scene_, view, gains);
    const GroundColourEstimate clean = measureGroundColourGain(frame.rgba, kWidth, kHeight, kStride, scene_, view, 2.0f);
    uint64_t saturated = 0;
    const ColourStatisticsGrid grid = colourStatisticsGrid(kWidth, kHeight, kStride);
    for (uint32_t j = 0; j < grid.samples_y; ++j)
        for (uint32_t i = 0; i < grid.samples_x; i += 2) {
            const uint32_t x = grid.offset + i * kStride, y = grid.offset + j * kStride;
            if (!groundMatchCellOfPixel(scene_, view, x, y)) continue;
            frame.rgba[(size_t(y) * kWidth + x) * 4] = 255;
            ++saturated;
        }
    const GroundColourEstimate clipped = measureGroundColourGain(frame.rgba, kWidth, kHeight, kStride, scene_, view, 2.0f);
    EXPECT_EQ(clipped.clipped_samples, saturated);
    EXPECT_EQ(clipped.ground_samples + saturated, clean.ground_samples);
    ASSERT_TRUE(clipped.accepted);
    expectNear(clipped.gain, gains, gains * frame.relative_quantisation_bound, "gain with clipped pixels");
}

// ---- GPU ------------------------------------------------------------------------------------------------------

class GroundMatchGpu : public testing::GpuTest {
protected:
    void SetUp() override {
        testing::GpuTest::SetUp();
        bake_set_ = bakeSetWithGroundAlbedo();
        scene_ = *groundMatchSceneFrom(bake_set_);
    }

    /// The runtime tests' options: the test frame's size, one sample a pixel (a multisampled edge pixel mixes
    /// building and camera, which a gain does not scale: the building part alone it does).
    static RuntimeOptions runtimeOptions(uint32_t shadow_map_size = 512) {
        RuntimeOptions options;
        options.frame_width = kWidth;
        options.frame_height = kHeight;
        options.shadow_map_size = shadow_map_size;
        options.msaa_samples = 1;
        return options;
    }

    /// The runtime tests' frame: the view at 10:30 in sun, exposure 0.3, colour match off (no camera set).
    static FrameInput runtimeFrame() {
        FrameInput frame;
        frame.intrinsics = intrinsics();
        frame.pose = CameraPose::lookingAt({0.3, -9.0, 3.0}, {0.0, 0.0, 1.0});
        frame.utc_unix_seconds = testing::syntheticLocalTime(10, 30);
        frame.weather = Weather::sunny();
        frame.exposure = 0.3f;
        frame.colour_match = ColourMatch::kOff;
        return frame;
    }

    ColourMatchState runFrame(ColourStatisticsPass& pass, GpuBuffer& camera, const std::vector<uint8_t>& rgba,
                              const GroundMatchView& view) {
        camera.upload(rgba.data(), rgba.size());
        context().submitAndWait([&](VkCommandBuffer cmd) {
            pass.recordSourceUpdate(cmd, LabStatistics{}, ColourMatchMode::kGround, 2.0f);
            pass.recordGround(cmd, camera, view);
        });
        return pass.readState();
    }

    /// applyColourMatch of the GLSL (shaders/tests/colour_match_probe.comp) with the pass's state.
    std::vector<dvec3> probe(const GpuBuffer& state_buffer, const std::vector<dvec3>& rgb) {
        const uint32_t count = uint32_t(rgb.size());
        std::vector<glm::vec4> inputs;
        for (const dvec3& colour : rgb) {
            inputs.push_back(glm::vec4(glm::vec3(colour), 0.0f));
            inputs.push_back(glm::vec4(0.0f));
        }
        GpuBuffer input_buffer(context(), inputs.size() * sizeof(glm::vec4));
        input_buffer.uploadVector(inputs);
        GpuBuffer output_buffer(context(), inputs.size() * sizeof(glm::vec4));
        ComputePipeline pipeline(context(), kColourMatchProbeCompSpirv, sizeof kColourMatchProbeCompSpirv, 3,
                                 sizeof(uint32_t));
        pipeline.bindBuffers({&state_buffer, &input_buffer, &output_buffer});
        pipeline.dispatchAndWait(&count, (count + 63) / 64);
        const std::vector<glm::vec4> outputs = output_buffer.downloadVector<glm::vec4>(inputs.size());
        std::vector<dvec3> results;
        for (uint32_t i = 0; i < count; ++i) results.push_back(dvec3(glm::vec3(outputs[2 * i + 1])));
        return results;
    }

    BakeSetData bake_set_;
    GroundMatchScene scene_;
};

TEST_F(GroundMatchGpu, EstimateMatchesTheCpuReferenceOnANoisyFrameWithShadowAndClipping) {
    const GroundMatchView view = viewFor(groundPose());
    SynthesisedFrame frame = synthesise(scene_, view, dvec3(1.3, 1.05, 0.75));
    // Make it hard: noise on every byte, a real shadow (a third of the ground at 30 %), some clipped pixels.
    std::mt19937 random(5);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            uint8_t* pixel = &frame.rgba[(size_t(y) * kWidth + x) * 4];
            const bool shadow = x < kWidth / 3;
            for (int c = 0; c < 3; ++c) {
                double value = pixel[c];
                if (shadow) value = 255.0 * srgbEncode(0.3 * srgbDecode(value / 255.0));
                value += double(int(random() % 9) - 4);
                pixel[c] = uint8_t(std::clamp(std::lround(value), 0L, 255L));
            }
            if (random() % 50 == 0) pixel[1] = 255;
        }
    const GroundColourEstimate expected = measureGroundColourGain(frame.rgba, kWidth, kHeight, kStride, scene_, view, 2.0f);
    ASSERT_TRUE(expected.accepted);
    ASSERT_GT(expected.clipped_samples, 0u);
    ASSERT_LT(expected.kept_samples, expected.ground_samples);  // the shadowed third is trimmed away

    ColourStatisticsPass pass(context(), kWidth, kHeight, kStatisticsStride, 8.0f, &scene_);
    EXPECT_EQ(pass.groundGrid().stride, kStride);
    GpuBuffer camera(context(), frame.rgba.size());
    const ColourMatchState state = runFrame(pass, camera, frame.rgba, view);
    std::printf("GPU gain %.5f %.5f %.5f, CPU %.5f %.5f %.5f; samples %u/%llu kept %u/%llu clipped %u/%llu\n",
                state.frame_ground_gain[0], state.frame_ground_gain[1], state.frame_ground_gain[2],
                expected.gain.r, expected.gain.g, expected.gain.b, state.frame_ground_samples,
                (unsigned long long)expected.ground_samples, state.frame_ground_kept,
                (unsigned long long)expected.kept_samples, state.frame_ground_clipped,
                (unsigned long long)expected.clipped_samples);
    // Float rays and log2 against double may move a sample at a cell or bin edge: a few samples at most.
    EXPECT_NEAR(double(state.frame_ground_samples), double(expected.ground_samples), 3.0);
    EXPECT_NEAR(double(state.frame_ground_kept), double(expected.kept_samples), 3.0);
    EXPECT_NEAR(double(state.frame_ground_clipped), double(expected.clipped_samples), 3.0);
    EXPECT_EQ(int(state.frame_ground_median_bin), expected.median_bin);
    EXPECT_EQ(state.frame_ground_accepted, 1u);
    EXPECT_EQ(state.ground_valid, 1u);
    // A few samples of ~1/kept weight each, and float sums: 0.5 % of the gain.
    expectNear(toDvec3(state.frame_ground_gain), expected.gain, expected.gain * 0.005, "GPU gain");
    expectNear(toDvec3(state.ground_gain), toDvec3(state.frame_ground_gain), dvec3(0.0), "first frame taken");
}

TEST_F(GroundMatchGpu, AnalyticGainsSkyFramesAndTheBuildingsColour) {
    const GroundMatchView view = viewFor(groundPose());
    const dvec3 gains = 0.8 * dvec3(1.15, 1.0, 0.8);  // warm white balance, exposure 20 % low
    const SynthesisedFrame frame = synthesise(scene_, view, gains);
    ColourStatisticsPass pass(context(), kWidth, kHeight, kStatisticsStride, 8.0f, &scene_);
    GpuBuffer camera(context(), frame.rgba.size());
    const ColourMatchState state = runFrame(pass, camera, frame.rgba, view);
    ASSERT_EQ(state.ground_valid, 1u);
    EXPECT_EQ(state.frame_ground_kept, state.frame_ground_samples);
    // The quantisation bound plus float sums (1e-4 relative).
    expectNear(toDvec3(state.ground_gain), gains, gains * (frame.relative_quantisation_bound + 1e-4), "GPU gain");
    // The building's output through the GLSL: gains x its unmatched (exposed) colour.
    const std::vector<dvec3> colours = {dvec3(0.1, 0.1, 0.1), dvec3(0.3, 0.2, 0.1), dvec3(0.5, 0.45, 0.6)};
    const std::vector<dvec3> matched = probe(pass.stateBuffer(), colours);
    for (size_t i = 0; i < colours.size(); ++i)
        expectNear(matched[i], glm::min(colours[i] * toDvec3(state.ground_gain), dvec3(1.0)), dvec3(1e-6),
                   "building colour " + std::to_string(i));

    // (c) Sky only: the frame is not accepted, the gain stays.
    const GroundMatchView sky_view = viewFor(skyPose());
    const SynthesisedFrame sky = synthesise(scene_, sky_view, dvec3(1.0));
    const ColourMatchState after_sky = runFrame(pass, camera, sky.rgba, sky_view);
    EXPECT_EQ(after_sky.frame_ground_samples, 0u);
    EXPECT_EQ(after_sky.frame_ground_accepted, 0u);
    EXPECT_EQ(after_sky.ground_valid, 1u);
    expectNear(toDvec3(after_sky.ground_gain), toDvec3(state.ground_gain), dvec3(0.0), "gain kept under sky");
    // After a reset, a sky frame leaves no gain: the identity (the unmatched colour).
    pass.reset();
    const ColourMatchState reset = runFrame(pass, camera, sky.rgba, sky_view);
    EXPECT_EQ(reset.ground_valid, 0u);
    const std::vector<dvec3> unmatched = probe(pass.stateBuffer(), colours);
    for (size_t i = 0; i < colours.size(); ++i) expectNear(unmatched[i], colours[i], dvec3(1e-7), "identity");
}

TEST_F(GroundMatchGpu, RuntimeDrawsTheBuildingAtGainsTimesItsUnmatchedColour) {
    // One sample a pixel (runtimeOptions): the test compares each building pixel with and without the match.
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), bake_set_, runtimeOptions());
    FrameInput frame = runtimeFrame();
    const CameraPose pose = frame.pose;
    frame.ground_ratio = false;  // the camera's ground pixels stay as they are; only the building differs
    std::vector<uint8_t> placeholder(size_t(kWidth) * kHeight * 4, 128);
    frame.camera_rgba8 = placeholder.data();
    std::vector<uint8_t> unmatched(placeholder.size()), matched(placeholder.size());
    const FrameInfo info = runtime->renderFrame(frame, unmatched.data());
    ASSERT_TRUE(info.sun_above_horizon);
    // The runtime's own view and light, from what it reports.
    const GroundMatchView view = viewReportedBy(pose, info, frame.exposure);
    const dvec3 gains(1.2, 1.0, 0.75);
    const SynthesisedFrame camera = synthesise(scene_, view, gains);
    frame.camera_rgba8 = camera.rgba.data();
    runtime->renderFrame(frame, unmatched.data());
    frame.colour_match = ColourMatch::kGround;
    runtime->resetColourStatistics();
    runtime->renderFrame(frame, matched.data());
    // Building pixels: where the two composites differ from the camera. Compare in linear, away from 8-bit
    // floors and from clipping: matched = gains x unmatched within both values' half steps.
    uint64_t compared = 0;
    for (size_t p = 0; p < matched.size() / 4; ++p) {
        const uint8_t* off = &unmatched[p * 4];
        const uint8_t* on = &matched[p * 4];
        const uint8_t* cam = &camera.rgba[p * 4];
        if (off[0] == cam[0] && off[1] == cam[1] && off[2] == cam[2]) continue;  // not the building
        for (int c = 0; c < 3; ++c) {
            if (off[c] < 40 || on[c] > 250) continue;
            const double off_linear = srgbDecode(off[c] / 255.0), on_linear = srgbDecode(on[c] / 255.0);
            const double off_step = srgbDecode((off[c] + 0.5) / 255.0) - off_linear;
            const double on_step = srgbDecode(std::min(1.0, (on[c] + 0.5) / 255.0)) - on_linear;
            // Gain within its quantisation bound (plus 1e-3 for float sums) times the unmatched colour.
            const double gain_error = gains[c] * (camera.relative_quantisation_bound[c] + 1e-3);
            EXPECT_NEAR(on_linear, gains[c] * off_linear,
                        on_step + gains[c] * off_step + gain_error * (off_linear + off_step))
                << "pixel " << p << " channel " << c;
            ++compared;
        }
    }
    uint64_t differing = 0;
    for (size_t p = 0; p < matched.size() / 4; ++p)
        differing += unmatched[p * 4] != camera.rgba[p * 4] || unmatched[p * 4 + 1] != camera.rgba[p * 4 + 1];
    const size_t centre = (size_t(kHeight / 2) * kWidth + kWidth / 2) * 4;
    std::printf("building pixels %llu, compared %llu; centre off %d %d %d on %d %d %d camera %d %d %d\n",
                (unsigned long long)differing, (unsigned long long)compared, unmatched[centre], unmatched[centre + 1],
                unmatched[centre + 2], matched[centre], matched[centre + 1], matched[centre + 2],
                camera.rgba[centre], camera.rgba[centre + 1], camera.rgba[centre + 2]);
    EXPECT_GT(compared, 300u);
}

// The ground statistics' cost on this device (docs/runtime.md "Colour match" quotes it): the pass's dispatches
// alone, fence-timed, median of 20 after a warm-up, on the synthesised ground frame.
TEST_F(GroundMatchGpu, TimingPrintsTheMedianCostOfTheGroundStatistics) {
    const GroundMatchView view = viewFor(groundPose());
    const SynthesisedFrame frame = synthesise(scene_, view, dvec3(1.1, 1.0, 0.9));
    ColourStatisticsPass pass(context(), kWidth, kHeight, kStatisticsStride, 8.0f, &scene_);
    GpuBuffer camera(context(), frame.rgba.size());
    camera.upload(frame.rgba.data(), frame.rgba.size());
    std::vector<double> milliseconds;
    for (int run = 0; run < 21; ++run) {
        const auto start = std::chrono::steady_clock::now();
        context().submitAndWait([&](VkCommandBuffer cmd) {
            pass.recordSourceUpdate(cmd, LabStatistics{}, ColourMatchMode::kGround, 2.0f);
            pass.recordGround(cmd, camera, view);
        });
        const auto end = std::chrono::steady_clock::now();
        if (run > 0) milliseconds.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    }
    std::sort(milliseconds.begin(), milliseconds.end());
    const ColourMatchState state = pass.readState();
    EXPECT_EQ(state.ground_frames_accepted, 21u);
    std::printf("ground statistics %ux%u stride %u (%llu samples, %u on the ground): median %.3f ms, min %.3f, "
                "max %.3f\n",
                kWidth, kHeight, pass.groundGrid().stride, (unsigned long long)pass.groundGrid().sampleCount(),
                state.frame_ground_samples, (milliseconds[9] + milliseconds[10]) / 2, milliseconds.front(),
                milliseconds.back());
}

// kColourStatisticsInterval and the smoothing: after a step in the camera's gains (gA, then gB from frame 1 on),
// the building keeps frame 0's colour on frames 1-3 (no measurement) and on frame 4, the next measurement, moves
// by the smoothing weight of statistics_smoothing_frames / interval measurements (8 / 4: a half) towards gB:
// gain gA + (gB - gA) / 2, the time constant still 8 frames. Read on the building's centre pixel, in linear.
TEST_F(GroundMatchGpu, TheCameraIsMeasuredOneFrameInTheIntervalWithTheSmoothingInFrames) {
    ASSERT_EQ(kColourStatisticsInterval, 4u);
    const RuntimeOptions options = runtimeOptions();
    ASSERT_EQ(options.statistics_smoothing_frames, 8.0f);
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), bake_set_, options);
    FrameInput frame = runtimeFrame();
    const CameraPose pose = frame.pose;
    std::vector<uint8_t> placeholder(size_t(kWidth) * kHeight * 4, 128), output(placeholder.size());
    frame.camera_rgba8 = placeholder.data();
    const FrameInfo info = runtime->renderFrame(frame, output.data());
    const GroundMatchView view = viewReportedBy(pose, info, frame.exposure);  // the runtime's own view and light
    const dvec3 gain_a(1.0), gain_b(1.2, 1.0, 0.8);
    const SynthesisedFrame camera_a = synthesise(scene_, view, gain_a), camera_b = synthesise(scene_, view, gain_b);
    frame.colour_match = ColourMatch::kGround;
    runtime->resetColourStatistics();
    const size_t centre = (size_t(kHeight / 2) * kWidth + kWidth / 2) * 4;
    std::vector<std::array<uint8_t, 3>> building;
    for (int index = 0; index < 5; ++index) {
        frame.camera_rgba8 = index == 0 ? camera_a.rgba.data() : camera_b.rgba.data();
        runtime->renderFrame(frame, output.data());
        building.push_back({output[centre], output[centre + 1], output[centre + 2]});
    }
    for (int index = 1; index < 4; ++index) EXPECT_EQ(building[index], building[0]) << "frame " << index;
    const dvec3 expected_gain = gain_a + 0.5 * (gain_b - gain_a);
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(building[0][c], 40) << "the centre pixel is the building, away from the 8-bit floor";
        const double first = srgbDecode(building[0][c] / 255.0), fifth = srgbDecode(building[4][c] / 255.0);
        const double first_step = srgbDecode((building[0][c] + 0.5) / 255.0) - first;
        const double fifth_step = srgbDecode(std::min(1.0, (building[4][c] + 0.5) / 255.0)) - fifth;
        // Both gains within their frames' quantisation bounds (plus 1e-3 for float sums).
        const double gain_error = expected_gain[c] * (std::max(camera_a.relative_quantisation_bound[c],
                                                               camera_b.relative_quantisation_bound[c]) + 1e-3);
        EXPECT_NEAR(fifth, expected_gain[c] / gain_a[c] * first,
                    fifth_step + expected_gain[c] * first_step + 2.0 * gain_error * (first + first_step))
            << "channel " << c;
    }
}

// The default, kAuto: on a bake set with ground albedo each frame is exactly kGround's (the same bytes, frame after
// frame, from a fresh runtime each); on one without, exactly kOff's, and it never fails the frame.
TEST_F(GroundMatchGpu, AutoIsTheGroundMatchWithGroundAlbedoAndOffWithout) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    const GroundMatchView view = viewFor(groundPose());
    const SynthesisedFrame camera = synthesise(scene_, view, dvec3(1.2, 1.0, 0.75));
    FrameInput frame;
    EXPECT_EQ(frame.colour_match, ColourMatch::kAuto);
    frame.camera_rgba8 = camera.rgba.data();
    frame.intrinsics = intrinsics();
    frame.pose = CameraPose::lookingAt({0.3, -9.0, 3.0}, {0.0, 0.0, 1.0});
    frame.utc_unix_seconds = testing::syntheticLocalTime(10, 30);
    frame.weather = Weather::sunny();
    frame.exposure = 0.3f;
    auto render = [&](const BakeSetData& bake_set, ColourMatch match) {
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), bake_set, options);
        frame.colour_match = match;
        std::vector<std::vector<uint8_t>> outputs(6, std::vector<uint8_t>(camera.rgba.size()));
        for (std::vector<uint8_t>& output : outputs) {
            runtime->renderFrame(frame, output.data());
            frame.utc_unix_seconds += 2.0;  // the light moves: frames between measurements differ too
        }
        frame.utc_unix_seconds -= 12.0;
        return outputs;
    };
    const std::vector<std::vector<uint8_t>> ground = render(bake_set_, ColourMatch::kGround);
    EXPECT_EQ(render(bake_set_, ColourMatch::kAuto), ground);
    EXPECT_NE(render(bake_set_, ColourMatch::kOff), ground);  // the match changes the building
    const BakeSetData without_albedo = testing::makeSyntheticBakeSet();
    EXPECT_EQ(render(without_albedo, ColourMatch::kAuto), render(without_albedo, ColourMatch::kOff));
}

TEST(GroundMatchBakeSet, ManifestFieldRoundTripsAndIsOptional) {
    BakeSetData bake_set = bakeSetWithGroundAlbedo();
    EXPECT_EQ(findBakeSetProblem(bake_set), std::nullopt);
    const std::string text = bakeSetManifestJson(bake_set.manifest);
    EXPECT_NE(text.find("\"albedo\": \"ground_albedo.exr\""), std::string::npos);
    EXPECT_EQ(parseBakeSetManifest("manifest.json", text).ground_grid.albedo, "ground_albedo.exr");
    // An older manifest: no field, loads with an empty name.
    const BakeSetData old_set = testing::makeSyntheticBakeSet();
    const std::string old_text = bakeSetManifestJson(old_set.manifest);
    EXPECT_EQ(old_text.find("albedo"), std::string::npos);
    EXPECT_TRUE(parseBakeSetManifest("manifest.json", old_text).ground_grid.albedo.empty());
    // The manifest and the data must agree; a negative albedo is refused naming the texel.
    BakeSetData no_image = bake_set;
    no_image.ground_albedo = {};
    EXPECT_NE(findBakeSetProblem(no_image).value_or("").find("ground_albedo: missing"), std::string::npos);
    bake_set.ground_albedo.rgba[5] = -0.5f;
    EXPECT_NE(findBakeSetProblem(bake_set).value_or("").find("ground_albedo: texel (1, 0) channel G"),
              std::string::npos)
        << findBakeSetProblem(bake_set).value_or("");
}

TEST(GroundMatchBakeSet, WithoutAlbedoTheModeIsRefusedAndOthersRun) {
    const BakeSetData old_set = testing::makeSyntheticBakeSet();
    EXPECT_FALSE(groundMatchSceneFrom(old_set));
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    std::unique_ptr<Runtime> runtime = Runtime::openHeadless(old_set, options);
    std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, 100), output(camera.size());
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = intrinsics();
    frame.pose = groundPose();
    frame.utc_unix_seconds = testing::syntheticLocalTime(12, 0);
    frame.colour_match = ColourMatch::kGround;
    try {
        runtime->renderFrame(frame, output.data());
        ADD_FAILURE() << "kGround ran on a bake set without ground albedo";
    } catch (const RuntimeError& error) {
        EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
        EXPECT_NE(std::string(error.what()).find("ground_grid.albedo"), std::string::npos) << error.what();
    }
    frame.colour_match = ColourMatch::kPreserve;
    EXPECT_NO_THROW(runtime->renderFrame(frame, output.data()));
}

}  // namespace
}  // namespace gusuku

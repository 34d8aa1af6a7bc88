// Anti-aliasing by multisampling (RuntimeOptions::msaa_samples), on lavapipe with validation on, against the
// closed-form bake set (gusuku/synthetic/synthetic_bakeset.h):
//   - the option's checks: a count that is not 1, 2, 4 or 8 is refused by name, one the device lacks as kDevice;
//   - the box's silhouette at msaa 4 is much nearer a 4 x 4 supersampled reference (the same frame at 4 times
//     the resolution and msaa 1, box-filtered in linear light) than msaa 1 is;
//   - camera pixels nothing but the camera draw touches resolve to the camera's own bytes, for every one of the
//     256 codes in every channel (an sRGB resolve of identical samples), with and without the building in view;
//   - the profiling frame (the pass split in three, the multisampled attachments stored and loaded between them,
//     resolved once at the end) gives renderFrame's composite byte for byte.
// msaa 1 drawing exactly what it drew before the option is the goldens' job (test_runtime_golden.cpp pins it).

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr double kFocal = 120.0;

RuntimeOptions optionsAt(uint32_t samples, uint32_t scale = 1) {
    RuntimeOptions options;
    options.frame_width = kWidth * scale;
    options.frame_height = kHeight * scale;
    options.shadow_map_size = 512;
    options.msaa_samples = samples;
    return options;
}

// The frame at `scale` times the resolution: the intrinsics scaled with it, so the pixel (x, y) of the small
// frame is exactly the scale x scale block of pixels from (scale x, scale y) of the large one.
FrameInput frameAt(const std::vector<uint8_t>& camera, const CameraPose& pose, double utc_seconds,
                   uint32_t scale = 1) {
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    const double s = scale;
    frame.intrinsics = {kFocal * s, kFocal * s, kWidth * s / 2.0, kHeight * s / 2.0, kWidth * scale, kHeight * scale};
    frame.pose = pose;
    frame.utc_unix_seconds = utc_seconds;
    frame.weather = Weather::sunny();
    frame.exposure = 0.5f;
    frame.colour_match = ColourMatch::kOff;
    return frame;
}

std::vector<uint8_t> render(Runtime& runtime, const FrameInput& frame, size_t pixels) {
    std::vector<uint8_t> output(pixels * 4);
    runtime.renderFrame(frame, output.data());
    return output;
}

// Every pixel's code: each of the 256 codes in each channel many times over the frame, the channels apart.
std::vector<uint8_t> cameraRamp() {
    std::vector<uint8_t> image(size_t(kWidth) * kHeight * 4);
    for (size_t pixel = 0; pixel < size_t(kWidth) * kHeight; ++pixel) {
        const uint32_t code = uint32_t(pixel % 256), turn = uint32_t(pixel / 256);
        image[pixel * 4 + 0] = uint8_t(code);
        image[pixel * 4 + 1] = uint8_t(255 - code);
        image[pixel * 4 + 2] = uint8_t(code * 37 + turn);
        image[pixel * 4 + 3] = uint8_t(code * 11 + 3 * turn);
    }
    return image;
}

class RuntimeMsaa : public testing::GpuTest {};

TEST_F(RuntimeMsaa, ACountThatIsNoPowerOfTwoUpToEightIsRefusedByName) {
    for (uint32_t samples : {0u, 3u, 16u}) {
        try {
            Runtime::open(context(), makeSyntheticBakeSet(), optionsAt(samples));
            ADD_FAILURE() << "msaa_samples " << samples << " was accepted";
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
            EXPECT_EQ(std::string(error.what()),
                      "options.msaa_samples: " + std::to_string(samples) + " is not 1, 2, 4 or 8");
        }
    }
}

TEST_F(RuntimeMsaa, ACountTheDeviceLacksIsRefusedAsADeviceError) {
    const VkPhysicalDeviceLimits& limits = context().gpu().limits();
    const VkSampleCountFlags both = limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
    uint32_t lacking = 0;
    for (uint32_t samples : {8u, 2u, 4u})
        if ((both & samples) == 0) lacking = samples;
    if (lacking == 0) GTEST_SKIP() << "this device draws 2, 4 and 8 samples: no count to refuse";
    try {
        Runtime::open(context(), makeSyntheticBakeSet(), optionsAt(lacking));
        ADD_FAILURE() << "msaa_samples " << lacking << " was accepted on a device without it";
    } catch (const RuntimeError& error) {
        EXPECT_EQ(error.code(), RuntimeErrorCode::kDevice);
        EXPECT_NE(std::string(error.what()).find("options.msaa_samples = " + std::to_string(lacking)),
                  std::string::npos)
            << error.what();
    }
}

// The box on a black camera (so any drawn sample shows), seen corner on: its silhouette's edges slant across
// the pixel grid. The reference is the same frame at 4 x 4 the pixels and one sample each, averaged over each
// 4 x 4 block in linear light; silhouette pixels are those whose block holds both box and camera.
TEST_F(RuntimeMsaa, SilhouetteEdgesComeCloseToA4x4SupersampledReference) {
    const BakeSetData bake_set = makeSyntheticBakeSet();
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, 0);
    const std::vector<uint8_t> large_camera(camera.size() * 16, 0);
    const CameraPose pose = CameraPose::lookingAt({6, -9, 3.5}, {0, 0, 1.2});
    const double time = syntheticLocalTime(15, 0);
    auto drawnAt = [&](uint32_t samples) {
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), bake_set, optionsAt(samples));
        FrameInput frame = frameAt(camera, pose, time);
        frame.ground_ratio = false;
        return render(*runtime, frame, camera.size() / 4);
    };
    const std::vector<uint8_t> single = drawnAt(1), multi = drawnAt(4);
    std::unique_ptr<Runtime> large_runtime = Runtime::open(context(), bake_set, optionsAt(1, 4));
    FrameInput large_frame = frameAt(large_camera, pose, time, 4);
    large_frame.ground_ratio = false;
    const std::vector<uint8_t> large = render(*large_runtime, large_frame, large_camera.size() / 4);

    size_t edge_pixels = 0, intermediate = 0;
    double single_error = 0.0, multi_error = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            int box_samples = 0;
            double linear[3] = {0.0, 0.0, 0.0};
            for (uint32_t dy = 0; dy < 4; ++dy)
                for (uint32_t dx = 0; dx < 4; ++dx) {
                    const uint8_t* texel = &large[((size_t(4 * y + dy)) * kWidth * 4 + 4 * x + dx) * 4];
                    box_samples += texel[0] + texel[1] + texel[2] > 0;
                    for (int c = 0; c < 3; ++c) linear[c] += srgbDecode(texel[c] / 255.0) / 16.0;
                }
            if (box_samples == 0 || box_samples == 16) continue;
            ++edge_pixels;
            const size_t at = (size_t(y) * kWidth + x) * 4;
            for (int c = 0; c < 3; ++c) {
                const double reference = 255.0 * srgbEncode(linear[c]);
                single_error += std::abs(single[at + c] - reference) / 3.0;
                multi_error += std::abs(multi[at + c] - reference) / 3.0;
            }
            // One sample a pixel shows the box or the camera whole; four blend them where the edge crosses.
            intermediate += multi[at] != single[at];
        }
    ASSERT_GT(edge_pixels, 80u) << "the box's silhouette should cross a hundred pixels and more";
    single_error /= double(edge_pixels);
    multi_error /= double(edge_pixels);
    std::printf("silhouette: %zu pixels; mean |difference| from the 4x4 reference: msaa 1 %.2f, msaa 4 %.2f "
                "(8-bit codes); %zu of them change from msaa 1's value\n",
                edge_pixels, single_error, multi_error, intermediate);
    EXPECT_LT(multi_error, 0.3 * single_error);  // measured 3.1 against 37 on lavapipe
    EXPECT_GT(intermediate, edge_pixels / 4);
}

// Nothing in view but the camera (looking up at the sky): every sample of every pixel holds the camera's one
// value, and the resolve must give back its bytes, all 256 codes of all four channels.
TEST_F(RuntimeMsaa, CameraAloneResolvesToItsOwnBytesForEveryCode) {
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), optionsAt(4));
    const std::vector<uint8_t> camera = cameraRamp();
    const CameraPose pose = CameraPose::lookingAt({0, -12, 1.5}, {0, -11, 40});
    const std::vector<uint8_t> output = render(*runtime, frameAt(camera, pose, syntheticLocalTime(15, 0)),
                                               camera.size() / 4);
    for (size_t index = 0; index < camera.size(); ++index)
        ASSERT_EQ(int(output[index]), int(camera[index]))
            << "pixel " << index / 4 % kWidth << "," << index / 4 / kWidth << " channel " << index % 4;
}

// The building and its shadow in view at msaa 4: the camera pixels outside their reach (their ray misses the
// box, and the ground point it meets sees the sun past the box: tested on the CPU) come through bit for bit,
// and the codes checked cover all 256 in each channel.
TEST_F(RuntimeMsaa, CameraPixelsAwayFromTheBuildingPassThroughBitForBit) {
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), optionsAt(4));
    const std::vector<uint8_t> camera = cameraRamp();
    const CameraPose pose = CameraPose::lookingAt({3, -14, 4}, {0, 0, 1});
    std::vector<uint8_t> output(camera.size());
    const FrameInfo info = runtime->renderFrame(frameAt(camera, pose, syntheticLocalTime(15, 0)), output.data());
    ASSERT_TRUE(info.sun_above_horizon);
    const glm::dvec3 sun = info.sun_direction_enu;
    std::set<int> codes_checked[4];
    size_t checked = 0, changed_in_reach = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::dvec3 ray = pose.camera_to_enu * glm::dvec3((x + 0.5 - kWidth / 2.0) / kFocal,
                                                                   (y + 0.5 - kHeight / 2.0) / kFocal, 1.0);
            // A margin of a pixel and more around the box: its edge pixels blend it with the camera.
            const bool near_building = testing::mayShowTheBoxOrItsShadow(pose.position_enu, ray, sun, 0.4);
            const size_t at = (size_t(y) * kWidth + x) * 4;
            bool same = true;
            for (int c = 0; c < 4; ++c) same &= output[at + c] == camera[at + c];
            if (near_building) {
                changed_in_reach += !same;
                continue;
            }
            ++checked;
            ASSERT_TRUE(same) << "pixel " << x << "," << y << " changed outside the building's reach";
            for (int c = 0; c < 4; ++c) codes_checked[c].insert(camera[at + c]);
        }
    EXPECT_GT(checked, size_t(kWidth) * kHeight / 2);
    EXPECT_GT(changed_in_reach, 100u);  // the building and its shadow were drawn
    for (int c = 0; c < 4; ++c) EXPECT_EQ(codes_checked[c].size(), 256u) << "channel " << c;
}

// The profiling frame splits the main pass in three (occluder, building, ground): multisampled, the colour and
// depth samples are stored after each and loaded by the next, and only the last resolves into the composite.
TEST_F(RuntimeMsaa, ProfiledFrameGivesRenderFramesCompositeByteForByte) {
    for (uint32_t samples : {4u, 1u}) {
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), optionsAt(samples));
        const std::vector<uint8_t> camera = cameraRamp();
        const FrameInput frame =
            frameAt(camera, CameraPose::lookingAt({4, -10, 3}, {0, 0, 1}), syntheticLocalTime(16, 0));
        std::vector<uint8_t> whole(camera.size()), profiled(camera.size());
        runtime->renderFrame(frame, whole.data());
        PassTimings timings;
        runtime->renderFrameProfiled(frame, profiled.data(), timings);
        size_t differing = 0;
        for (size_t index = 0; index < whole.size(); ++index) differing += whole[index] != profiled[index];
        EXPECT_EQ(differing, 0u) << "msaa " << samples << ": bytes differ between renderFrame and the profiled frame";
        EXPECT_GT(timings.building_ms, 0.0);
        size_t changed = 0;
        for (size_t index = 0; index < whole.size(); ++index) changed += whole[index] != camera[index];
        EXPECT_GT(changed, 1000u) << "the frame should show the building and its shadow";
    }
}

}  // namespace
}  // namespace gusuku

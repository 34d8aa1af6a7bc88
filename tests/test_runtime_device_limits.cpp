// The runtime at the spec's minimum limits (issue 43 item 2): every limit it reads comes from GpuDevice::limits(),
// so lowering them there (gusuku/gpu/device_limits.h, the mechanism GUSUKU_CLAMP_LIMITS drives) runs the whole
// runtime as a smaller device would. Checked against:
// - the sample's bake set (`gusuku-bake sample`, baked at 4 samples) and, when ../shared/data is there, the shrine's
//   (scripts/write-bench-site.py, one slot baked at 1 sample), each opened and drawn at Vulkan 1.0's required minimum of
//   every limit and at the Android Baseline 2022 profile's values, validation on: the frame must be the unclamped
//   frame (no limit the frame reads changes what it draws at these options: anisotropy 1, colour match off);
// - refusals by name: a bake set beyond a limit (checkBakeSetLimits) and a fixed need beyond one (open).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bake_command.h"
#include "device_requirements.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/gpu/device_limits.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::CommandResult;
using gusuku::testing::runBakeCommand;

constexpr uint32_t kWidth = 128, kHeight = 96;

// One bake set per site for the whole binary: baking is most of the test's cost.
const BakeSetData& bakedSite(const std::string& site) {
    static std::string folder = gusuku::testing::makeTemporaryDirectory("runtime_device_limits");
    static std::vector<std::pair<std::string, BakeSetData>> baked;
    for (const auto& [name, data] : baked)
        if (name == site) return data;
    const std::string sample_dir = folder + "/sample";
    if (!fs::exists(sample_dir + "/site.json")) {
        const CommandResult sample = runBakeCommand({"sample", sample_dir}, folder);
        EXPECT_EQ(sample.exit_code, 0) << sample.stderr_text;
    }
    std::string site_json = sample_dir + "/site.json";
    if (site == "shrine") {
        site_json = folder + "/shrine/site.json";
        fs::create_directories(folder + "/shrine");
        const fs::path repository = fs::path(GUSUKU_GOLDEN_DIR).parent_path().parent_path();
        const std::string write = "python3 " + (repository / "scripts/write-bench-site.py").string() + " " +
                                  sample_dir + "/site.json " + gusuku::testing::sharedDataDir() + " shrine " +
                                  site_json;
        EXPECT_EQ(std::system(write.c_str()), 0) << write;
    }
    const std::string output = folder + "/" + site + "_bakeset";
    if (site == "sample") {
        const CommandResult bake = runBakeCommand({"bake", site_json, "-o", output, "--samples", "4", "--quiet"}, folder);
        EXPECT_EQ(bake.exit_code, 0) << bake.stderr_text;
        baked.emplace_back(site, loadBakeSet(output));
        return baked.back().second;
    }
    // The shrine's frame limits, not its light, are under test: one slot at one sample, as a partial set (no
    // runtime pack, whose ASTC encoding of the shrine's textures would take a minute), opened as a whole one;
    // textures at 512 (the limits hold them at 4096): three opens of 2048-texel ones cost about 25 s more.
    const CommandResult bake = runBakeCommand(
        {"bake", site_json, "-o", output, "--samples", "1", "--slot", "sunny_1200", "--texture-size", "512", "--quiet"},
        folder);
    EXPECT_EQ(bake.exit_code, 0) << bake.stderr_text;
    BakeSetData data = loadPartialBakeSet(output);
    data.manifest.partial.reset();
    baked.emplace_back(site, std::move(data));
    return baked.back().second;
}

// A pose that sees the whole building: from the south-west and above, at twice its bounds' half-diagonal.
CameraPose viewOfBuilding(const BakeSetData& bake_set) {
    glm::dvec3 low(1e30), high(-1e30);
    for (const glm::vec3& position : bake_set.building.positions) {
        low = glm::min(low, glm::dvec3(position));
        high = glm::max(high, glm::dvec3(position));
    }
    const glm::dvec3 centre = 0.5 * (low + high);
    const double distance = 2.0 * glm::length(high - low) * 0.5;
    return CameraPose::lookingAt(centre + distance * glm::normalize(glm::dvec3(-1.0, -1.0, 0.6)), centre);
}

// Three frames (the last one kept) of the building over a flat grey camera.
std::vector<uint8_t> drawFrames(const GpuDevice& gpu, const BakeSetData& bake_set) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 512;
    std::unique_ptr<Runtime> runtime = Runtime::open(gpu, bake_set, options);
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, 128);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {90.0, 90.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = viewOfBuilding(bake_set);
    frame.utc_unix_seconds = testing::syntheticLocalTime(11, 0);
    frame.colour_match = ColourMatch::kOff;
    std::vector<uint8_t> output(camera.size());
    for (int index = 0; index < 3; ++index) runtime->renderFrame(frame, output.data());
    return output;
}

class RuntimeDeviceLimits : public testing::GpuTest, public ::testing::WithParamInterface<const char*> {};

// Opens, draws and matches the unclamped frame at each profile's limits; the building covers part of the frame.
void expectSameFrameAtEveryProfile(const GpuDevice& device, const BakeSetData& bake_set, const char* site) {
    const std::vector<uint8_t> unclamped = drawFrames(device, bake_set);
    size_t building_pixels = 0;
    for (size_t pixel = 0; pixel < unclamped.size() / 4; ++pixel) building_pixels += unclamped[pixel * 4 + 3] == 255;
    EXPECT_GT(building_pixels, unclamped.size() / 4 / 50) << site << ": the building is not in view";
    for (const char* profile : {"vulkan10", "android2022"}) {
        GpuDevice clamped = device;
        clampDeviceLimits(clamped.properties.limits, profile);
        std::vector<uint8_t> drawn;
        try {
            drawn = drawFrames(clamped, bake_set);
        } catch (const std::exception& error) {
            ADD_FAILURE() << site << " at " << profile << ": " << error.what();
            continue;
        }
        size_t differing = 0;
        for (size_t index = 0; index < drawn.size(); ++index) differing += drawn[index] != unclamped[index];
        std::printf("%s at %s: %zu of %zu bytes differ from the unclamped frame\n", site, profile, differing,
                    drawn.size());
        EXPECT_EQ(differing, 0u) << site << " at " << profile;
    }
}

TEST_F(RuntimeDeviceLimits, TheSampleDrawsTheSameAtVulkan10AndAndroid2022Limits) {
    expectSameFrameAtEveryProfile(context(), bakedSite("sample"), "sample");
}

TEST_F(RuntimeDeviceLimits, TheShrineDrawsTheSameAtVulkan10AndAndroid2022Limits) {
    GUSUKU_REQUIRE_SHARED_DATA();
    if (!fs::exists(gusuku::testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf"))
        GTEST_SKIP() << "the shrine's model is not in ../shared/data";
    expectSameFrameAtEveryProfile(context(), bakedSite("shrine"), "shrine");
}

// What the runtime's fixed parts need (device_requirements.cpp) is within Vulkan 1.0's minimum; a device below it
// is refused by the limit's name, with the figure it has and the one needed.
TEST_F(RuntimeDeviceLimits, AFixedNeedBelowItsLimitIsRefusedByName) {
    GpuDevice device = context();
    clampDeviceLimits(device.properties.limits, "maxBoundDescriptorSets=1");
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    try {
        Runtime::open(device, testing::makeSyntheticBakeSet({}), options);
        FAIL() << "opened with one descriptor set";
    } catch (const RuntimeError& error) {
        EXPECT_EQ(error.code(), RuntimeErrorCode::kDevice);
        EXPECT_NE(std::string(error.what()).find("maxBoundDescriptorSets is 1, below the 2"), std::string::npos)
            << error.what();
    }
}

// docs/runtime.md's table of the fixed needs ("Device requirements", Limits), pinned: each figure passes, one
// less is refused naming the limit, what the device has and the figure.
TEST_F(RuntimeDeviceLimits, TheDocumentedFixedNeedsAreTheChecksFigures) {
    const struct {
        const char* limit;
        uint32_t needed;
    } documented[] = {
        {"maxBoundDescriptorSets", 2},
        {"maxPerStageDescriptorSamplers", 8},
        {"maxPerStageDescriptorSampledImages", 8},
        {"maxDescriptorSetSamplers", 8},
        {"maxDescriptorSetSampledImages", 8},
        {"maxPerStageDescriptorUniformBuffers", 1},
        {"maxDescriptorSetUniformBuffers", 1},
        {"maxUniformBufferRange", 296},
        {"maxPerStageDescriptorStorageBuffers", 1},
        {"maxPerStageResources", 11},
        {"maxFragmentCombinedOutputResources", 2},
        {"maxPushConstantsSize", 84},
        {"maxVertexInputAttributes", 4},
        {"maxVertexInputBindingStride", 40},
        {"maxComputeWorkGroupInvocations", 64},
        {"maxComputeWorkGroupSize[0]", 8},
        {"maxComputeWorkGroupSize[1]", 8},
    };
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.lightmap_format = LightmapFormat::kE5b9g9r9;  // as open resolves kAuto before the check
    for (const auto& need : documented) {
        const std::string name = need.limit;
        GpuDevice device = context();
        clampDeviceLimits(device.properties.limits, name + "=" + std::to_string(need.needed));
        EXPECT_NO_THROW(runtime_detail::checkDeviceRequirements(device, options)) << name;
        clampDeviceLimits(device.properties.limits, name + "=" + std::to_string(need.needed - 1));
        try {
            runtime_detail::checkDeviceRequirements(device, options);
            ADD_FAILURE() << name << " below " << need.needed << " passed";
        } catch (const RuntimeError& error) {
            EXPECT_NE(std::string(error.what()).find(name + " is " + std::to_string(need.needed - 1) + ", below the " +
                                                     std::to_string(need.needed) + " that "),
                      std::string::npos)
                << error.what();
        }
    }
}

TEST_F(RuntimeDeviceLimits, ABakeSetBeyondALimitIsRefusedWithWhatToBakeDifferently) {
    const BakeSetData bake_set = testing::makeSyntheticBakeSet({});
    GpuDevice device = context();
    const int lightmap = bake_set.manifest.building.lightmap_resolution;
    ASSERT_GT(lightmap, 2);
    clampDeviceLimits(device.properties.limits, "maxImageDimension2D=" + std::to_string(lightmap - 1));
    try {
        runtime_detail::checkBakeSetLimits(device, bake_set);
        FAIL() << "a lightmap beyond maxImageDimension2D passed";
    } catch (const RuntimeError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "bake set: building.lightmap_resolution: " + std::to_string(lightmap) + " is larger than this "
                  "device's (" + device.properties.deviceName + ") maxImageDimension2D of " +
                      std::to_string(lightmap - 1) + ": bake with a smaller lightmap (site.json bake.texels_per_metre)");
    }
    device = context();
    clampDeviceLimits(device.properties.limits, "maxImageArrayLayers=1");
    try {
        runtime_detail::checkBakeSetLimits(device, bake_set);
        FAIL() << "slots beyond maxImageArrayLayers passed";
    } catch (const RuntimeError& error) {
        EXPECT_NE(std::string(error.what()).find("maxImageArrayLayers of 1: bake fewer slots"), std::string::npos)
            << error.what();
    }
    device = context();
    EXPECT_NO_THROW(runtime_detail::checkBakeSetLimits(device, bake_set));
}

}  // namespace
}  // namespace gusuku

// The trace kernels' two ways of reading the scene (gusuku_bake/trace_input_kind.h): texel buffers where the
// device's maxTexelBufferElements holds every buffer the bake may upload, storage buffers elsewhere (65536, the
// Vulkan minimum, on SwiftShader and many phones). Checked against:
// - the rule, on limits written by hand (lavapipe's, SwiftShader's, a desktop GPU's);
// - the same bits: one driver, the same scene, seed and view traced both ways (the storage kernel forced by a
//   lower maxTexelBufferElements) gives byte-identical frames, so a bake is the same whichever the device picks;
// - a second driver: the sample site baked on SwiftShader (where the texel kernel could not even bind its
//   81920-texel BVH) matches lavapipe's bake within the bake's own noise, measured as the difference between
//   lavapipe's bake and one at four times the samples (the drivers differ by a tenth of it at most). Skipped where SwiftShader is not installed.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bake_command.h"
#include "gpu_test_support.h"
#include "gusuku/assets/image.h"
#include "gusuku/gpu/device_limits.h"
#include "gusuku_bake/camera_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_input_kind.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::CommandResult;
using gusuku::testing::runBakeCommand;

constexpr const char* kSwiftShaderIcd = "/usr/lib/chromium/vk_swiftshader_icd.json";

GpuDevice deviceWith(uint32_t max_texel_buffer_elements, uint32_t max_storage_buffer_range) {
    GpuDevice device;
    device.properties.limits.maxTexelBufferElements = max_texel_buffer_elements;
    device.properties.limits.maxStorageBufferRange = max_storage_buffer_range;
    return device;
}

TEST(TraceInputKinds, TheDevicesLimitsChoose) {
    // lavapipe: 128 Mi texels, 128 MiB storage buffers: every buffer's 4-byte texels fit.
    EXPECT_EQ(traceInputKind(deviceWith(1u << 27, 1u << 27)), TraceInputKind::TexelBuffers);
    // SwiftShader and the Vulkan minimum: 65536 texels.
    EXPECT_EQ(traceInputKind(deviceWith(65536, 1u << 27)), TraceInputKind::StorageBuffers);
    // A desktop GPU with 4 GiB storage buffers and 128 Mi texels: a buffer could outgrow the texels.
    EXPECT_EQ(traceInputKind(deviceWith(1u << 27, 0xffffffffu)), TraceInputKind::StorageBuffers);
    EXPECT_STREQ(traceInputKindName(TraceInputKind::StorageBuffers), "storage buffers");
    EXPECT_TRUE(traceInputTexelBindings(TraceInputKind::StorageBuffers).empty());
    EXPECT_EQ(traceInputTexelBindings(TraceInputKind::TexelBuffers).size(), 7u);
}

class TraceInputKindsOnDevice : public gusuku::testing::GpuTest {};

TEST_F(TraceInputKindsOnDevice, StorageBuffersTraceTheSameBitsAsTexelBuffers) {
    // A sunlit box on a plane under an uneven sky, both sky estimators, bounces: every input read.
    const TriangleMesh box = gusuku::testing::closedBox({-1.0f, 3.0f, 0.0f}, {1.0f, 5.0f, 2.0f}, false,
                                                        glm::vec3(0.6f, 0.5f, 0.4f));
    const TriangleMesh ground = gusuku::testing::horizontalPlane(200.0f, 0.0f, glm::vec3(0.3f));
    const TraceScene scene = makeTraceScene(box, &ground);
    ImageRGBA map = gusuku::testing::uniformSky(64, 32, glm::vec3(0.0f));
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            float* texel = map.texel(x, y);
            texel[0] = 0.1f + float(x) / 64.0f;
            texel[1] = 0.1f + float(y) / 32.0f;
            texel[2] = 0.3f + 0.2f * float((x * 7 + y * 3) % 5);
        }
    const SkySamplingTables sky = buildSkySamplingTables(map, 0.0);
    SunLight sun;
    sun.present = true;
    sun.direction_enu = glm::normalize(glm::dvec3(-0.4, 0.5, 0.7));
    sun.irradiance_rgb = glm::dvec3(6.0, 5.5, 5.0);
    CameraIntrinsics intrinsics;
    intrinsics.fx = intrinsics.fy = 45.0;
    intrinsics.cx = 32.0;
    intrinsics.cy = 24.0;
    intrinsics.width = 64;
    intrinsics.height = 48;
    CameraPose pose;
    pose.position_enu = {0.5, -3.0, 1.6};
    const glm::dvec3 forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.25));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0.0, 0.0, 1.0)));
    pose.camera_to_enu = glm::dmat3(right, glm::cross(forward, right), forward);
    CameraRenderOptions options;
    options.samples_per_pixel = 8;
    options.include_building = true;

    const GpuDevice& texel_device = context();
    ASSERT_EQ(traceInputKind(texel_device), TraceInputKind::TexelBuffers) << "lavapipe reads texel buffers";
    GpuDevice storage_device = context();
    clampDeviceLimits(storage_device.properties.limits, "maxTexelBufferElements=65536");
    ASSERT_EQ(traceInputKind(storage_device), TraceInputKind::StorageBuffers);
    for (SkySampling sampling : {SkySampling::CosineAndMap, SkySampling::CosineOnly}) {
        options.sky_sampling = sampling;
        CameraTracer texel_tracer(texel_device, scene);
        CameraTracer storage_tracer(storage_device, scene);
        const CameraRender texel = texel_tracer.render({&sky, sun}, intrinsics, pose, options);
        const CameraRender storage = storage_tracer.render({&sky, sun}, intrinsics, pose, options);
        ASSERT_EQ(texel.radiance.texels.size(), storage.radiance.texels.size());
        EXPECT_EQ(std::memcmp(texel.radiance.texels.data(), storage.radiance.texels.data(),
                              texel.radiance.texels.size() * sizeof(float)),
                  0);
        EXPECT_EQ(texel.rays_traced, storage.rays_traced);
    }
}

// Relative RMS difference of two lightmaps over the texels both traced (alpha 1), RGB.
double relativeRmsDifference(const ImageRGBA& a, const ImageRGBA& b) {
    double squared_difference = 0.0, squared_value = 0.0;
    for (size_t texel = 0; texel < a.texels.size() / 4; ++texel) {
        if (a.texels[texel * 4 + 3] < 1.0f || b.texels[texel * 4 + 3] < 1.0f) continue;
        for (size_t channel = 0; channel < 3; ++channel) {
            const double x = a.texels[texel * 4 + channel], y = b.texels[texel * 4 + channel];
            squared_difference += (x - y) * (x - y);
            squared_value += x * x;
        }
    }
    return std::sqrt(squared_difference / squared_value);
}

// Sets an environment variable for one child process (unset: empty value), restoring it after.
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
        if (const char* before = std::getenv(name)) saved_ = before;
        if (!value.empty()) setenv(name, value.c_str(), 1);
    }
    ~ScopedEnvironment() {
        if (saved_) setenv(name_, saved_->c_str(), 1);
        else unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> saved_;
};

// Bakes the sample's sunny_1200 slot (unfiltered, uniform samples) with `icd` as the Vulkan driver (empty: the
// environment's) and `clamp` as GUSUKU_CLAMP_LIMITS; the command's result, the set in folder/name.
CommandResult bakeSlotRun(const std::string& folder, const std::string& name, const std::string& samples,
                          const std::string& icd, const std::string& clamp = "") {
    const ScopedEnvironment driver("VK_ICD_FILENAMES", icd);
    const ScopedEnvironment limits("GUSUKU_CLAMP_LIMITS", clamp);
    return runBakeCommand({"bake", folder + "/sample/site.json", "-o", folder + "/" + name, "--samples", samples,
                           "--slot", "sunny_1200", "--no-denoise", "--uniform-sampling", "--quiet"},
                          folder);
}

std::string bakeSlot(const std::string& folder, const std::string& name, const std::string& samples,
                     const std::string& icd, const std::string& clamp = "") {
    const CommandResult bake = bakeSlotRun(folder, name, samples, icd, clamp);
    EXPECT_EQ(bake.exit_code, 0) << name << ": " << bake.stderr_text;
    if (!icd.empty())
        EXPECT_NE(bake.stderr_text.find("device SwiftShader"), std::string::npos) << bake.stderr_text;
    return folder + "/" + name;
}

std::string fileBytes(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// On one driver the storage kernel is the texel kernel's arithmetic: the Android Baseline 2022 profile's limits
// (65536 texels, 35 storage buffers) bake the same bytes; Vulkan 1.0's 4 storage buffers a stage cannot bind the
// storage kernel, and the bake says so before its geometry.
TEST(TraceInputKindsOnOneDriver, Android2022LimitsBakeTheSameBytesAndVulkan10IsRefusedByName) {
    const std::string folder = gusuku::testing::makeTemporaryDirectory("trace_input_kinds_one_driver");
    const CommandResult sample = runBakeCommand({"sample", folder + "/sample"}, folder);
    ASSERT_EQ(sample.exit_code, 0) << sample.stderr_text;
    const std::string texel = bakeSlot(folder, "texel", "2", "");
    const std::string storage = bakeSlot(folder, "android2022", "2", "", "android2022");
    for (const char* file : {"building_sunny_1200.exr", "ground_sunny_1200_with.exr", "ground_sunny_1200_without.exr"})
        EXPECT_EQ(fileBytes(texel + "/" + file), fileBytes(storage + "/" + file)) << file;
    const CommandResult refused = bakeSlotRun(folder, "vulkan10", "2", "", "vulkan10");
    EXPECT_EQ(refused.exit_code, 1) << refused.stderr_text;
    EXPECT_NE(refused.stderr_text.find("the trace kernels need maxPerStageDescriptorStorageBuffers >= 10, their "
                                       "storage buffers (storage buffers, as maxTexelBufferElements of 65536 is "
                                       "below what a bake may upload); this device's ("),
              std::string::npos)
        << refused.stderr_text;
    EXPECT_FALSE(fs::exists(folder + "/vulkan10/manifest.json"));
    fs::remove_all(folder);
}

TEST(TraceInputKindsAcrossDrivers, SwiftShaderBakesTheSampleAsLavapipeDoesWithinTheNoise) {
    if (!fs::exists(kSwiftShaderIcd))
        GTEST_SKIP() << kSwiftShaderIcd << " is absent: SwiftShader (Debian's chromium package) is not installed";
    const std::string folder = gusuku::testing::makeTemporaryDirectory("trace_input_kinds");
    const CommandResult sample = runBakeCommand({"sample", folder + "/sample"}, folder);
    ASSERT_EQ(sample.exit_code, 0) << sample.stderr_text;
    const std::string lavapipe = bakeSlot(folder, "lavapipe", "4", "");
    const std::string reference = bakeSlot(folder, "lavapipe_x4", "16", "");
    const std::string swiftshader = bakeSlot(folder, "swiftshader", "4", kSwiftShaderIcd);
    for (const char* file : {"building_sunny_1200.exr", "ground_sunny_1200_with.exr", "ground_sunny_1200_without.exr"}) {
        const ImageRGBA a = readFloatRgbaExr(lavapipe + "/" + file);
        const ImageRGBA b = readFloatRgbaExr(swiftshader + "/" + file);
        const ImageRGBA r = readFloatRgbaExr(reference + "/" + file);
        ASSERT_EQ(a.texels.size(), b.texels.size()) << file;
        const double drivers = relativeRmsDifference(a, b);
        const double noise = relativeRmsDifference(a, r);
        std::printf("%s: SwiftShader vs lavapipe %.5f relative RMS; the 4-sample bake's noise (vs 16) %.5f\n", file,
                    drivers, noise);
        // Measured: 0.0004-0.0012 between the drivers (the same random streams; only their float rounding
        // differs) against 0.13-0.19 of noise. A tenth of the noise leaves room for another LLVM.
        EXPECT_LT(drivers, 0.1 * noise) << file;
    }
    fs::remove_all(folder);
}

}  // namespace
}  // namespace gusuku::bake

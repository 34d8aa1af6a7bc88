// The C API's loaded path (gusuku_loader.h) and its app-device open (gusuku_runtime_open), on a real bake of the
// mini site (2 samples): gusuku_bakeset_load's handle opens a runtime on the test's own Vulkan device (validation
// on) whose frame is byte for byte the C++ API's frame from loadBakeSet on the same device, with the building
// drawn; a folder that is not a bake set is refused with the C API's code and the loader's one-line message.
// (tests/test_c_api.c covers the C structs path, from C.)

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku/loader/gusuku_loader.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 72;

class CApiLoaderTest : public testing::GpuTest {
protected:
    /// The mini site baked once per test binary (2 samples), its bake set folder.
    const std::string& bakedSet() {
        static const std::string folder = [&] {
            const std::string dir = testing::makeTemporaryDirectory("gusuku-c-api-loader");
            testing::MiniSiteOptions site_options;
            site_options.samples_per_texel = 2;
            bake::BakeOptions options;
            options.output_dir = dir + "/bakeset";
            options.show_progress = false;
            const bake::BakeReport report =
                bake::runBake(context(), loadSiteConfig(testing::writeMiniSite(dir, site_options)), options);
            EXPECT_TRUE(report.completed);
            return options.output_dir;
        }();
        return folder;
    }

    gusuku_vulkan_device device() {
        return {sizeof(gusuku_vulkan_device), context().instance(), context().physicalDevice(), context().device(),
                context().queue(), context().queueFamily()};
    }
};

TEST_F(CApiLoaderTest, LoadedBakeSetRendersOnTheAppsDeviceAsTheCppApiDoes) {
    gusuku_bakeset* bake_set = nullptr;
    ASSERT_EQ(gusuku_bakeset_load(bakedSet().c_str(), &bake_set), GUSUKU_OK) << gusuku_last_error_message();
    ASSERT_NE(bake_set, nullptr);

    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime* runtime = nullptr;
    ASSERT_EQ(gusuku_runtime_open(&vulkan, bake_set, &options, &runtime), GUSUKU_OK) << gusuku_last_error_message();
    EXPECT_EQ(gusuku_bakeset_free(bake_set), GUSUKU_OK);

    // A camera 8 m south of the house at 1 m, looking north (row-major: camera x = east, y = down, z = north).
    std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4);
    for (size_t i = 0; i < camera.size(); ++i) camera[i] = i % 4 == 3 ? 255 : uint8_t(60 + (i * 13) % 120);
    gusuku_frame_input frame;
    ASSERT_EQ(gusuku_frame_input_default(&frame), GUSUKU_OK);
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {80.0, 80.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose.position_enu[1] = -8.0;
    frame.pose.position_enu[2] = 1.0;
    const double camera_to_enu[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
    std::memcpy(frame.pose.camera_to_enu, camera_to_enu, sizeof camera_to_enu);
    frame.utc_unix_seconds = 1782010800.0;  // 2026-06-21T03:00:00Z, noon at UTC+9
    frame.exposure = 0.2f;
    frame.colour_match = GUSUKU_COLOUR_MATCH_OFF;
    std::vector<uint8_t> from_c(camera.size());
    gusuku_frame_info info{};
    info.struct_size = sizeof info;
    ASSERT_EQ(gusuku_runtime_render(runtime, &frame, from_c.data(), &info), GUSUKU_OK)
        << gusuku_runtime_last_error(runtime);
    EXPECT_TRUE(info.sun_above_horizon);
    EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);

    // The same frame through the C++ API on the same device.
    const std::unique_ptr<Runtime> cpp = Runtime::open(context().gpu(), loadBakeSet(bakedSet()), [] {
        RuntimeOptions o;
        o.frame_width = kWidth;
        o.frame_height = kHeight;
        o.shadow_map_size = 256;
        return o;
    }());
    FrameInput cpp_frame;
    cpp_frame.camera_rgba8 = camera.data();
    cpp_frame.intrinsics = {80.0, 80.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    cpp_frame.pose.position_enu = {0.0, -8.0, 1.0};
    cpp_frame.pose.camera_to_enu = glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
    cpp_frame.utc_unix_seconds = frame.utc_unix_seconds;
    cpp_frame.exposure = frame.exposure;
    cpp_frame.colour_match = ColourMatch::kOff;
    std::vector<uint8_t> from_cpp(camera.size());
    const FrameInfo cpp_info = cpp->renderFrame(cpp_frame, from_cpp.data());
    EXPECT_EQ(info.sun_azimuth_deg, cpp_info.sun_azimuth_deg);
    EXPECT_EQ(info.slot_a, cpp_info.slot_a);
    EXPECT_TRUE(from_c == from_cpp) << "the C API's frame differs from the C++ API's";
    size_t changed = 0;
    for (size_t i = 0; i < camera.size(); ++i) changed += from_c[i] != camera[i];
    EXPECT_GT(changed, size_t(kWidth) * kHeight / 20) << "the house was not drawn";
}

TEST_F(CApiLoaderTest, FolderWithoutABakeSetIsRefusedWithTheLoadersMessage) {
    const std::string folder = testing::makeTemporaryDirectory("gusuku-c-api-empty");
    gusuku_bakeset* bake_set = reinterpret_cast<gusuku_bakeset*>(this);  // must be overwritten with null
    EXPECT_EQ(gusuku_bakeset_load(folder.c_str(), &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
    EXPECT_EQ(bake_set, nullptr);
    const std::string message = gusuku_last_error_message();
    EXPECT_EQ(message.rfind("gusuku_bakeset_load: " + folder + "/manifest.json: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
    EXPECT_EQ(gusuku_bakeset_load(nullptr, &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(gusuku_bakeset_load(folder.c_str(), nullptr), GUSUKU_ERROR_INVALID_ARGUMENT);
}

TEST(CApiLoader, AnEmptyFolderNameIsRefusedNotReadAsTheRoot) {
    // "" + "/manifest.json" is the file system's root: both loaders refuse the empty name itself.
    using Load = gusuku_result (*)(const char*, gusuku_bakeset**);
    const std::pair<Load, std::string> loaders[] = {{gusuku_bakeset_load, "gusuku_bakeset_load"},
                                                    {gusuku_bakeset_load_pack, "gusuku_bakeset_load_pack"}};
    for (const auto& [load, name] : loaders) {
        gusuku_bakeset* bake_set = reinterpret_cast<gusuku_bakeset*>(this);  // must be overwritten with null
        EXPECT_EQ(load("", &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT) << name;
        EXPECT_EQ(bake_set, nullptr);
        EXPECT_EQ(std::string(gusuku_last_error_message()), name + ": folder: is empty");
        EXPECT_EQ(load(nullptr, &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT) << name;
        EXPECT_EQ(std::string(gusuku_last_error_message()), name + ": folder: is NULL");
    }
}

TEST_F(CApiLoaderTest, AFrameTheDeviceCannotHoldIsRefusedNamingTheFrameSize) {
    // 8192 x 8192 is inside options' [1, 8192], but the colour statistics' camera copy is a 256 MiB storage
    // buffer: a device whose maxStorageBufferRange is smaller (lavapipe's 128 MiB) refuses it at open, naming
    // options.frame_width/height and the limit, not a GpuBuffer. A device that holds it opens.
    gusuku_bakeset* bake_set = nullptr;
    ASSERT_EQ(gusuku_bakeset_load(bakedSet().c_str(), &bake_set), GUSUKU_OK) << gusuku_last_error_message();
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    options.frame_width = options.frame_height = 8192;
    options.msaa_samples = 1;
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime* runtime = nullptr;
    const gusuku_result result = gusuku_runtime_open(&vulkan, bake_set, &options, &runtime);
    EXPECT_EQ(gusuku_bakeset_free(bake_set), GUSUKU_OK);
    const uint64_t packed_bytes = uint64_t(8192) * 8192 * 4;
    if (packed_bytes <= context().gpu().limits().maxStorageBufferRange) {
        EXPECT_EQ(result, GUSUKU_OK) << gusuku_last_error_message();
        EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
        GTEST_SKIP() << "this device holds an 8192 x 8192 frame's buffers";
    }
    EXPECT_EQ(result, GUSUKU_ERROR_DEVICE);
    EXPECT_EQ(runtime, nullptr);
    const std::string message = gusuku_last_error_message();
    RecordProperty("message", message);  // in --gtest_output's report, for the record
    EXPECT_EQ(message.rfind("gusuku_runtime_open: options.frame_width/height: 8192 x 8192 needs a 256.0 MiB "
                            "storage buffer", 0), 0u) << message;
    EXPECT_NE(message.find("maxStorageBufferRange of "), std::string::npos) << message;
    EXPECT_EQ(message.find("GpuBuffer"), std::string::npos) << message;
}

}  // namespace
}  // namespace gusuku

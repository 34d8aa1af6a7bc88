// The runtime's errors keep their category (runtime.h, "Errors": host memory is kOutOfMemory, device failures
// kDevice): a host allocation that fails while the runtime opens reaches the app as out of memory, not as a
// device failure, on every way in: Runtime::open on the app's device, Runtime::openHeadless, and the C API's
// gusuku_runtime_open_headless (GUSUKU_ERROR_OUT_OF_MEMORY); and so is one in Weather::estimatedFrom, which
// said "invalid frame" for it (gusuku_weather_estimate likewise).
//
// The failure is real: this executable replaces the global operator new, and the test arms it on its own thread
// to refuse every allocation of at least kRefusedBytes. The bake set's lightmaps are made large enough that the
// runtime's conversion of them into the GPU's format (runtime_scene.cpp, inside open's resource creation) is the
// first such allocation; everything smaller, and everything allocated with malloc (the Vulkan loader, lavapipe),
// goes through untouched.

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app_owned_device.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_c_api_detail.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace {

// Allocations of at least this many bytes fail while armed (this thread only).
thread_local size_t t_refused_from_bytes = SIZE_MAX;

}  // namespace

// The global replacement: libstdc++'s other forms (new[], nothrow) call this one, and its operator delete frees
// with std::free, so malloc underneath keeps the two paired. GCC inlines this delete where it sees a new-expression
// and, knowing only the standard operator new, warns that free() meets a pointer from new (-Wmismatched-new-delete):
// here they are one allocator, so the warning is off for this file.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t byte_count) {
    if (byte_count >= t_refused_from_bytes) throw std::bad_alloc();
    if (void* memory = std::malloc(byte_count == 0 ? 1 : byte_count)) return memory;
    throw std::bad_alloc();
}
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::SyntheticBakeSetOptions;

// A 1024^2 lightmap converts into 4 MiB (E5B9G9R9) or 8 MiB (RGBA16F) in one host vector; the frame-sized and
// shadow-map-sized things the runtime allocates with operator new stay far below 1 MiB at the options below.
constexpr int kLightmapSide = 1024;
constexpr size_t kRefusedBytes = size_t(1) << 20;

BakeSetData largeLightmapBakeSet() {
    SyntheticBakeSetOptions options;
    options.lightmap_resolution = kLightmapSide;
    return makeSyntheticBakeSet(options);
}

RuntimeOptions smallOptions() {
    RuntimeOptions options;
    options.frame_width = 160;
    options.frame_height = 120;
    options.shadow_map_size = 256;
    return options;
}

GpuDevice describe(testing::AppOwnedDevice& app) {
    return GpuDevice::describe(app.instance, app.physical_device, app.device, app.queue, app.queue_family,
                               &app.queue_mutex, app.api_version);
}

// Arms the refusal for one scope of this thread.
class RefuseLargeAllocations {
public:
    RefuseLargeAllocations() { t_refused_from_bytes = kRefusedBytes; }
    ~RefuseLargeAllocations() { t_refused_from_bytes = SIZE_MAX; }
};

// The code a call's RuntimeError carries (kDevice if it throws something else, which runtime.h rules out).
template <typename Call> RuntimeErrorCode codeThrownBy(const Call& call, std::string& message) {
    try {
        call();
    } catch (const RuntimeError& error) {
        message = error.what();
        return error.code();
    }
    ADD_FAILURE() << "the call did not throw";
    return RuntimeErrorCode::kDevice;
}

TEST(RuntimeErrorCategories, HostMemoryRunningOutOpeningOnTheAppsDeviceIsOutOfMemory) {
    const BakeSetData bake_set = largeLightmapBakeSet();
    testing::AppOwnedDevice app;
    {
        const GpuDevice gpu = describe(app);
        std::string message;
        const RuntimeErrorCode code = codeThrownBy(
            [&] {
                RefuseLargeAllocations refuse;
                Runtime::open(gpu, bake_set, smallOptions());
            },
            message);
        EXPECT_EQ(code, RuntimeErrorCode::kOutOfMemory) << message;
        // Nothing else was wrong: with the memory back, the same call opens.
        EXPECT_NE(Runtime::open(gpu, bake_set, smallOptions()), nullptr);
    }
    app.destroyDevice();
    for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
}

TEST(RuntimeErrorCategories, HostMemoryRunningOutOpeningHeadlessIsOutOfMemory) {
    const BakeSetData bake_set = largeLightmapBakeSet();
    std::string message;
    const RuntimeErrorCode code = codeThrownBy(
        [&] {
            RefuseLargeAllocations refuse;
            Runtime::openHeadless(bake_set, smallOptions());
        },
        message);
    EXPECT_EQ(code, RuntimeErrorCode::kOutOfMemory) << message;
    EXPECT_NE(Runtime::openHeadless(bake_set, smallOptions()), nullptr);
}

TEST(RuntimeErrorCategories, HostMemoryRunningOutInTheCApiIsOutOfMemory) {
    const gusuku_bakeset bake_set{largeLightmapBakeSet()};
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    options.frame_width = 160;
    options.frame_height = 120;
    options.shadow_map_size = 256;
    gusuku_runtime* runtime = nullptr;
    gusuku_result result = GUSUKU_OK;
    {
        RefuseLargeAllocations refuse;
        result = gusuku_runtime_open_headless(&bake_set, &options, &runtime);
    }
    EXPECT_EQ(result, GUSUKU_ERROR_OUT_OF_MEMORY) << gusuku_result_name(result) << ": " << gusuku_last_error_message();
    EXPECT_EQ(runtime, nullptr);
    ASSERT_EQ(gusuku_runtime_open_headless(&bake_set, &options, &runtime), GUSUKU_OK) << gusuku_last_error_message();
    gusuku_runtime_close(runtime);
}

// Weather::estimatedFrom allocates two frame-sized arrays (runtime.h): a 1024^2 frame's 12 MiB of linear colour is
// refused, which is host memory running out, not a bad frame.
TEST(RuntimeErrorCategories, HostMemoryRunningOutEstimatingTheWeatherIsOutOfMemory) {
    constexpr uint32_t kSide = 1024;
    const std::vector<uint8_t> camera(size_t(kSide) * kSide * 4, 128);
    std::string message;
    const RuntimeErrorCode code = codeThrownBy(
        [&] {
            RefuseLargeAllocations refuse;
            Weather::estimatedFrom(camera.data(), kSide, kSide);
        },
        message);
    EXPECT_EQ(code, RuntimeErrorCode::kOutOfMemory) << message;
    gusuku_weather weather{};
    gusuku_result result = GUSUKU_OK;
    {
        RefuseLargeAllocations refuse;
        result = gusuku_weather_estimate(camera.data(), kSide, kSide, &weather);
    }
    EXPECT_EQ(result, GUSUKU_ERROR_OUT_OF_MEMORY) << gusuku_result_name(result) << ": " << gusuku_last_error_message();
    EXPECT_EQ(gusuku_weather_estimate(camera.data(), kSide, kSide, &weather), GUSUKU_OK);
}

}  // namespace
}  // namespace gusuku

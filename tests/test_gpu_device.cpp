// The compute helpers on a Vulkan device created outside gusuku, the way an AR app hands in its own device:
// the test makes the instance (with the Khronos validation layer and its own debug messenger), the device and
// the queue itself, describes them as a GpuDevice, and runs gusuku's buffers and pipelines on it. Any validation
// warning or error fails the test.

#include <cstdint>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"
#include "app_owned_device.h"
#include "smoke_scale_add_comp_spv.h"

namespace gusuku {
namespace {

using testing::AppOwnedDevice;

struct ScaleAddParams {  // the push-constant block of shaders/tests/smoke_scale_add.comp
    float scale;
    float offset;
    uint32_t count;
};

class AppDeviceTest : public ::testing::Test {
protected:
    void TearDown() override {
        app.destroyDevice();  // objects gusuku left on the app's device are reported here
        for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
    }
    AppOwnedDevice app;
};

TEST_F(AppDeviceTest, DescribeReadsTheDevicesFacts) {
    const GpuDevice gpu = GpuDevice::describe(app.instance, app.physical_device, app.device, app.queue,
                                              app.queue_family, &app.queue_mutex);
    VkPhysicalDeviceProperties expected;
    vkGetPhysicalDeviceProperties(app.physical_device, &expected);
    EXPECT_STREQ(gpu.properties.deviceName, expected.deviceName);
    EXPECT_EQ(gpu.limits().maxStorageBufferRange, expected.limits.maxStorageBufferRange);
    EXPECT_GT(gpu.memory_properties.memoryTypeCount, 0u);
    EXPECT_EQ(gpu.queue_mutex, &app.queue_mutex);
}

TEST_F(AppDeviceTest, ComputeDispatchOnTheAppsDeviceMatchesTheCpu) {
    const GpuDevice gpu = GpuDevice::describe(app.instance, app.physical_device, app.device, app.queue,
                                              app.queue_family, &app.queue_mutex);
    constexpr uint32_t count = 1000;
    std::vector<float> inputs(count);
    for (uint32_t index = 0; index < count; ++index) inputs[index] = float(index) * 0.25f - 100.0f;
    const ScaleAddParams params{3.0f, 0.5f, count};
    {
        // Inputs in device-local memory (uploaded through staging), outputs host-visible.
        GpuBuffer input_buffer(gpu, count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal);
        GpuBuffer output_buffer(gpu, count * sizeof(float));
        GpuBuffer key_sum_buffer(gpu, sizeof(uint32_t));
        EXPECT_FALSE(input_buffer.isMapped());
        input_buffer.uploadVector(inputs);
        const uint32_t zero = 0;
        key_sum_buffer.upload(&zero, sizeof zero);

        ComputePipeline pipeline(gpu, kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3,
                                 sizeof(ScaleAddParams));
        pipeline.bindBuffers({&input_buffer, &output_buffer, &key_sum_buffer});
        pipeline.dispatchAndWait(&params, (count + 63) / 64);

        const std::vector<float> outputs = output_buffer.downloadVector<float>(count);
        for (uint32_t index = 0; index < count; ++index) {
            const float product = params.scale * inputs[index];
            const float expected = product + params.offset;
            ASSERT_EQ(std::memcmp(&expected, &outputs[index], sizeof(float)), 0) << "element " << index;
        }
        uint32_t key_sum = 0;
        key_sum_buffer.download(&key_sum, sizeof key_sum);
        uint32_t expected_key_sum = 0;
        for (uint32_t index = 0; index < count; ++index) expected_key_sum += index % 1000 + 1;
        EXPECT_EQ(key_sum, expected_key_sum);
    }
    // Everything gusuku made on the app's device is gone with its objects: the app can destroy its device
    // now, and the validation layer reports any object left alive on it (TearDown fails the test then).
}

TEST_F(AppDeviceTest, DeviceLocalBufferRoundTripsThroughStaging) {
    const GpuDevice gpu = GpuDevice::describe(app.instance, app.physical_device, app.device, app.queue,
                                              app.queue_family);
    std::vector<uint32_t> words(4099);
    for (size_t index = 0; index < words.size(); ++index) words[index] = uint32_t(index * 2654435761u);
    GpuBuffer buffer(gpu, words.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal);
    buffer.uploadVector(words);
    EXPECT_EQ(buffer.downloadVector<uint32_t>(words.size()), words);
    // A partial write at an offset leaves the rest in place.
    const uint32_t patch[3] = {7, 8, 9};
    buffer.upload(patch, sizeof patch, 100 * sizeof(uint32_t));
    uint32_t read_back[5] = {};
    buffer.download(read_back, sizeof read_back, 99 * sizeof(uint32_t));
    EXPECT_EQ(read_back[0], words[99]);
    EXPECT_EQ(read_back[1], 7u);
    EXPECT_EQ(read_back[3], 9u);
    EXPECT_EQ(read_back[4], words[103]);
    EXPECT_THROW(buffer.download(read_back, sizeof read_back, buffer.size() - 4), std::out_of_range);
}

}  // namespace
}  // namespace gusuku

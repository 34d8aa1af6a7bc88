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

#include "gusuku/gpu_compute.h"
#include "gusuku/gpu_device.h"
#include "smoke_scale_add_comp_spv.h"

namespace gusuku {
namespace {

// The app side: everything here is plain Vulkan, written as an app would, not gusuku code.
class AppOwnedDevice {
public:
    AppOwnedDevice() {
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "app-owned device test";
        app.apiVersion = VK_API_VERSION_1_1;
        VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        messenger_info.messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
        messenger_info.pfnUserCallback = &AppOwnedDevice::onMessage;
        messenger_info.pUserData = this;
        VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        instance_info.pNext = &messenger_info;  // also catches messages from instance creation itself
        instance_info.pApplicationInfo = &app;
        instance_info.enabledLayerCount = 1;
        instance_info.ppEnabledLayerNames = &layer;
        instance_info.enabledExtensionCount = 1;
        instance_info.ppEnabledExtensionNames = &extension;
        if (vkCreateInstance(&instance_info, nullptr, &instance) != VK_SUCCESS)
            throw std::runtime_error("the test could not create a Vulkan instance with the validation layer");
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create_messenger == nullptr ||
            create_messenger(instance, &messenger_info, nullptr, &messenger) != VK_SUCCESS)
            throw std::runtime_error("no debug messenger");

        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> physical_devices(count);
        vkEnumeratePhysicalDevices(instance, &count, physical_devices.data());
        for (VkPhysicalDevice candidate : physical_devices) {
            uint32_t family_count = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, nullptr);
            std::vector<VkQueueFamilyProperties> families(family_count);
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, families.data());
            for (uint32_t family = 0; family < family_count; ++family)
                if (families[family].queueFlags & VK_QUEUE_COMPUTE_BIT) {
                    physical_device = candidate;
                    queue_family = family;
                    break;
                }
            if (physical_device != VK_NULL_HANDLE) break;
        }
        if (physical_device == VK_NULL_HANDLE) throw std::runtime_error("no device with a compute queue");

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = queue_family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        if (vkCreateDevice(physical_device, &device_info, nullptr, &device) != VK_SUCCESS)
            throw std::runtime_error("vkCreateDevice failed");
        vkGetDeviceQueue(device, queue_family, 0, &queue);
    }

    /// Destroys the device; the validation layer then reports any object still alive on it.
    void destroyDevice() {
        if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
        device = VK_NULL_HANDLE;
    }

    ~AppOwnedDevice() {
        destroyDevice();
        if (messenger != VK_NULL_HANDLE) {
            auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy_messenger(instance, messenger, nullptr);
        }
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
    }

    std::vector<std::string> messages() {
        std::lock_guard<std::mutex> lock(messages_mutex);
        return validation_messages;
    }

    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::mutex queue_mutex;  // the app's own lock around its queue submissions

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
        auto* self = static_cast<AppOwnedDevice*>(user);
        std::lock_guard<std::mutex> lock(self->messages_mutex);
        self->validation_messages.push_back(data && data->pMessage ? data->pMessage : "(no text)");
        return VK_FALSE;
    }
    std::mutex messages_mutex;
    std::vector<std::string> validation_messages;
};

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

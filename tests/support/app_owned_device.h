#pragma once
// A Vulkan device made the way an AR app makes its own, outside gusuku: the test creates the instance (with the
// Khronos validation layer and its own debug messenger), picks a device with a graphics and compute queue, and
// creates the device and queue. gusuku is then handed these handles (GpuDevice::describe) as an app would.
// Validation messages are collected; destroyDevice() makes the layer report any object gusuku left on it.

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/debug_message_source.h"

namespace gusuku::testing {

// The app side: everything here is plain Vulkan, written as an app would, not gusuku code.
class AppOwnedDevice {
public:
    /// api_version: the instance's VkApplicationInfo::apiVersion. timeline_semaphores: the device gets the
    /// timelineSemaphore feature (needs api_version 1.2).
    explicit AppOwnedDevice(uint32_t api_version = VK_API_VERSION_1_1, bool timeline_semaphores = false)
        : api_version(api_version) {
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "app-owned device test";
        app.apiVersion = api_version;
        // The app's own messenger, set as gusuku's tools set theirs (a test helper, not gusuku's code path).
        VkDebugUtilsMessengerCreateInfoEXT messenger_info =
            warningAndErrorMessengerInfo(&AppOwnedDevice::onMessage, this);
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
                if ((families[family].queueFlags & VK_QUEUE_COMPUTE_BIT) && (families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) {
                    physical_device = candidate;
                    queue_family = family;
                    break;
                }
            if (physical_device != VK_NULL_HANDLE) break;
        }
        if (physical_device == VK_NULL_HANDLE) throw std::runtime_error("no device with a graphics and compute queue");

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = queue_family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        VkPhysicalDeviceTimelineSemaphoreFeatures timeline{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES};
        timeline.timelineSemaphore = VK_TRUE;
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        if (timeline_semaphores) device_info.pNext = &timeline;
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

    uint32_t api_version;
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::mutex queue_mutex;  // the app's own lock around its queue submissions

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
        if (isVulkanLoaderMessage(types, data)) return VK_FALSE;  // the loader's note about other drivers
        auto* self = static_cast<AppOwnedDevice*>(user);
        std::lock_guard<std::mutex> lock(self->messages_mutex);
        self->validation_messages.push_back(data && data->pMessage ? data->pMessage : "(no text)");
        return VK_FALSE;
    }
    std::mutex messages_mutex;
    std::vector<std::string> validation_messages;
};

}  // namespace gusuku::testing

// gusuku-view's window and device (see view_device.h).

#include "view_device.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gusuku/gpu/debug_message_source.h"

namespace gusuku::view {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
std::atomic<uint32_t> validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL printValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT types,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    if (isVulkanLoaderMessage(types, data)) {  // a note about the installed drivers: shown, not counted
        std::fprintf(stderr, "gusuku-view: Vulkan loader: %s\n", data->pMessage ? data->pMessage : "");
        return VK_FALSE;
    }
    ++validation_messages;
    std::fprintf(stderr, "gusuku-view: Vulkan validation: %s [%s] %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "ERROR" : "WARNING",
                 data->pMessageIdName ? data->pMessageIdName : "", data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

bool validationAskedFor() {
    const char* value = std::getenv("GUSUKU_VALIDATION");
    return value && std::strcmp(value, "1") == 0;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& layer) {
        return std::strcmp(layer.layerName, name) == 0;
    });
}

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string("Vulkan: ") + what + " failed (" +
                                                       std::to_string(int(result)) + ")");
}

}  // namespace

uint32_t WindowDevice::validationMessageCount() { return validation_messages.load(); }

WindowDevice::WindowDevice(uint32_t width, uint32_t height, const std::string& title) {
    if (!glfwInit()) throw std::runtime_error("GLFW: cannot open a window (no display: is DISPLAY set?)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw std::runtime_error("GLFW: no Vulkan loader with a surface extension for this display");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan draws, not OpenGL
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("GLFW: cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                                 " window");
    }
    try {
        createInstance();
        check(glfwCreateWindowSurface(instance_, window_, nullptr, &surface_), "glfwCreateWindowSurface");
        pickDevice();
        createDevice();
    } catch (...) {
        release();
        throw;
    }
}

WindowDevice::~WindowDevice() { release(); }

void WindowDevice::release() noexcept {
    if (gpu_.device) vkDestroyDevice(gpu_.device, nullptr);
    gpu_.device = VK_NULL_HANDLE;
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
    if (window_) {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    window_ = nullptr;
}

void WindowDevice::createInstance() {
    uint32_t glfw_count = 0;
    const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&glfw_count);
    std::vector<const char*> extensions(glfw_extensions, glfw_extensions + glfw_count);
    std::vector<const char*> layers;
    const bool validation = validationAskedFor();
    if (validation) {
        if (!hasLayer(kValidationLayer))
            throw std::runtime_error(std::string("Vulkan validation was asked for but the layer ") + kValidationLayer +
                                     " is not installed (Debian package: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.pApplicationName = "gusuku-view";
    application.apiVersion = VK_API_VERSION_1_1;  // the colour matches' subgroups (runtime.h)
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = warningAndErrorMessengerInfo(printValidationMessage, nullptr);
    // Synchronization validation too, as the tools' own context turns on (vulkan_context.h).
    const VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync_validation;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &application;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (validation) {
        info.pNext = &messenger_info;
        messenger_info.pNext = &features;
    }
    check(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw std::runtime_error("Vulkan: vkCreateDebugUtilsMessengerEXT is not available");
        messenger_info.pNext = nullptr;
        check(create(instance_, &messenger_info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
}

// A Vulkan 1.1 device with a queue family that does graphics and compute and presents to the window, and
// VK_KHR_swapchain: a GPU before a CPU driver, and GUSUKU_DEVICE's name when it is set.
void WindowDevice::pickDevice() {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    const char* filter_text = std::getenv("GUSUKU_DEVICE");
    const std::string filter = lowercase(filter_text ? filter_text : "");
    std::string seen;
    int best_rank = -1;
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(device, &properties);
        seen += std::string(seen.empty() ? "" : ", ") + properties.deviceName;
        if (properties.apiVersion < VK_API_VERSION_1_1) continue;
        if (!filter.empty() && lowercase(properties.deviceName).find(filter) == std::string::npos) continue;
        uint32_t extension_count = 0;
        vkEnumerateDeviceExtensionProperties(device, nullptr, &extension_count, nullptr);
        std::vector<VkExtensionProperties> extensions(extension_count);
        vkEnumerateDeviceExtensionProperties(device, nullptr, &extension_count, extensions.data());
        if (std::none_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& extension) {
                return std::strcmp(extension.extensionName, VK_KHR_SWAPCHAIN_EXTENSION_NAME) == 0;
            }))
            continue;
        uint32_t family_count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(device, &family_count, nullptr);
        std::vector<VkQueueFamilyProperties> families(family_count);
        vkGetPhysicalDeviceQueueFamilyProperties(device, &family_count, families.data());
        for (uint32_t family = 0; family < family_count; ++family) {
            const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            VkBool32 presents = VK_FALSE;
            vkGetPhysicalDeviceSurfaceSupportKHR(device, family, surface_, &presents);
            if ((families[family].queueFlags & needed) != needed || !presents) continue;
            const int rank = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 3
                             : properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2
                                                                                               : 1;
            if (rank > best_rank) {
                best_rank = rank;
                physical_device_ = device;
                queue_family_ = family;
            }
            break;
        }
    }
    if (!physical_device_)
        throw std::runtime_error("Vulkan: no Vulkan 1.1 device" + (filter.empty() ? "" : " named \"" + filter + "\"") +
                                 " with a graphics and compute queue that presents to the window (devices: " + seen +
                                 ")");
}

void WindowDevice::createDevice() {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_device_, &supported);
    VkPhysicalDeviceFeatures enabled{};
    // The runtime clamps RuntimeOptions::max_anisotropy to the device; the app says it enabled the feature.
    enabled.samplerAnisotropy = supported.samplerAnisotropy;
    sampler_anisotropy_ = supported.samplerAnisotropy == VK_TRUE;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    const char* extensions[] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
    info.pEnabledFeatures = &enabled;
    VkDevice device = VK_NULL_HANDLE;
    check(vkCreateDevice(physical_device_, &info, nullptr, &device), "vkCreateDevice");
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(device, queue_family_, 0, &queue);
    gpu_ = GpuDevice::describe(instance_, physical_device_, device, queue, queue_family_, nullptr,
                               VK_API_VERSION_1_1);
}

}  // namespace gusuku::view

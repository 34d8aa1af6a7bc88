// The one headless Vulkan context (see vulkan_context.h for the contract). No surface extensions: the baker,
// the tests and the bench render offscreen; the runtime presents through its host application.

#include "gusuku/gpu/vulkan_context.h"

#include "gusuku/gpu/debug_message_source.h"
#include "gusuku/gpu/device_limits.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace gusuku {
namespace {

constexpr const char* kValidationLayerName = "VK_LAYER_KHRONOS_validation";

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string versionString(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) +
           "." + std::to_string(VK_API_VERSION_PATCH(version));
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

// Higher is preferred when no filter names a device: real GPUs first, lavapipe last.
int deviceTypeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    checkVk(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(count);
    checkVk(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

// Instance extensions provided by the loader/drivers (layer == nullptr) or by one layer.
bool hasInstanceExtension(const char* layer, const char* name) {
    uint32_t count = 0;
    checkVk(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr), "vkEnumerateInstanceExtensionProperties");
    std::vector<VkExtensionProperties> extensions(count);
    checkVk(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()),
            "vkEnumerateInstanceExtensionProperties");
    return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& extension) {
        return std::strcmp(extension.extensionName, name) == 0;
    });
}

// Index of a queue family with compute, preferring one that also has graphics (the runtime rasterises on the
// same queue); -1 when the device has no compute queue.
int pickQueueFamily(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    int compute_only = -1;
    for (uint32_t index = 0; index < count; ++index) {
        if (families[index].queueCount == 0 || !(families[index].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
        if (families[index].queueFlags & VK_QUEUE_GRAPHICS_BIT) return static_cast<int>(index);
        if (compute_only < 0) compute_only = static_cast<int>(index);
    }
    return compute_only;
}

bool environmentFlag(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && std::strcmp(value, "1") == 0;
}

}  // namespace

VulkanContextOptions vulkanOptionsFromEnvironment() {
    VulkanContextOptions options;
    options.enable_validation = environmentFlag("GUSUKU_VALIDATION");
    // An escape hatch for triage: GUSUKU_SYNC_VALIDATION=0 keeps the core checks but drops the hazard tracking.
    if (const char* sync = std::getenv("GUSUKU_SYNC_VALIDATION"); sync && std::strcmp(sync, "0") == 0)
        options.enable_synchronization_validation = false;
    if (const char* device = std::getenv("GUSUKU_DEVICE")) options.device_name_filter = device;
    return options;
}

VulkanContext::VulkanContext(const VulkanContextOptions& options) {
    try {
        createInstance(options);
        pickPhysicalDevice(options);
        createDevice();
    } catch (...) {
        destroy();  // the destructor does not run for a constructor that throws
        throw;
    }
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() noexcept {
    if (device_ != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device_);
        submitter_.reset();
        vkDestroyDevice(device_, nullptr);
    }
    device_ = VK_NULL_HANDLE;
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy_messenger) destroy_messenger(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

void VulkanContext::createInstance(const VulkanContextOptions& options) {
    uint32_t loader_version = VK_API_VERSION_1_0;
    checkVk(vkEnumerateInstanceVersion(&loader_version), "vkEnumerateInstanceVersion");
    if (loader_version < VK_API_VERSION_1_1)
        throw std::runtime_error("Vulkan: the loader offers Vulkan " + versionString(loader_version) +
                                 "; gusuku needs 1.1 or newer (subgroup operations)");
    // 1.2 brings the feature structs and driver properties we read; nothing here needs 1.3.
    instance_api_version_ = loader_version >= VK_API_VERSION_1_2 ? VK_API_VERSION_1_2 : VK_API_VERSION_1_1;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    bool synchronization_validation = false;
    validation_enabled_ = options.enable_validation;
    if (validation_enabled_) {
        if (!hasLayer(kValidationLayerName))
            throw std::runtime_error(std::string("Vulkan validation was asked for but the layer ") +
                                     kValidationLayerName +
                                     " is not installed (Debian package: vulkan-validationlayers)");
        if (!hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
            !hasInstanceExtension(kValidationLayerName, VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
            throw std::runtime_error("Vulkan validation was asked for but the instance extension "
                                     VK_EXT_DEBUG_UTILS_EXTENSION_NAME " is missing");
        layers.push_back(kValidationLayerName);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        synchronization_validation = options.enable_synchronization_validation &&
                                     hasInstanceExtension(kValidationLayerName, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        if (synchronization_validation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }

    VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.pApplicationName = "gusuku";
    application.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    application.pEngineName = "gusuku";
    application.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    application.apiVersion = instance_api_version_;

    // Chained into vkCreateInstance too, so messages about instance creation and destruction are caught.
    VkDebugUtilsMessengerCreateInfoEXT messenger_info =
        warningAndErrorMessengerInfo(&VulkanContext::debugCallback, this);

    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &application;
    instance_info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    instance_info.ppEnabledLayerNames = layers.data();
    instance_info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instance_info.ppEnabledExtensionNames = extensions.data();
    const VkValidationFeatureEnableEXT validation_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validation_features.enabledValidationFeatureCount = 1;
    validation_features.pEnabledValidationFeatures = &validation_feature;
    if (validation_enabled_) {
        instance_info.pNext = &messenger_info;
        if (synchronization_validation) messenger_info.pNext = &validation_features;
    }
    checkVk(vkCreateInstance(&instance_info, nullptr, &instance_), "vkCreateInstance");

    if (validation_enabled_) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create_messenger) throw std::runtime_error("Vulkan: vkCreateDebugUtilsMessengerEXT is not available");
        messenger_info.pNext = nullptr;  // the validation features belong to vkCreateInstance only
        checkVk(create_messenger(instance_, &messenger_info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
}

void VulkanContext::pickPhysicalDevice(const VulkanContextOptions& options) {
    uint32_t count = 0;
    checkVk(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    checkVk(vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "vkEnumeratePhysicalDevices");
    if (devices.empty())
        throw std::runtime_error("Vulkan: no physical device found (on Debian, install mesa-vulkan-drivers for "
                                 "lavapipe)");

    std::string filter = options.device_name_filter;
    if (filter.empty())
        if (const char* environment = std::getenv("GUSUKU_DEVICE")) filter = environment;
    const std::string filter_lowercase = lowercase(filter);

    std::string seen;  // for the error message
    int best_rank = -1;
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(device, &properties);
        seen += std::string(seen.empty() ? "" : ", ") + properties.deviceName;
        if (properties.apiVersion < VK_API_VERSION_1_1 || pickQueueFamily(device) < 0) continue;
        if (!filter.empty() && lowercase(properties.deviceName).find(filter_lowercase) == std::string::npos) continue;
        const int rank = deviceTypeRank(properties.deviceType);
        if (rank > best_rank) {
            best_rank = rank;
            physical_device_ = device;
            properties_ = properties;
        }
    }
    if (physical_device_ == VK_NULL_HANDLE) {
        if (!filter.empty())
            throw std::runtime_error("Vulkan: no Vulkan 1.1 device with a compute queue has \"" + filter +
                                     "\" in its name (devices: " + seen + ")");
        throw std::runtime_error("Vulkan: no Vulkan 1.1 device with a compute queue (devices: " + seen + ")");
    }
    queue_family_ = static_cast<uint32_t>(pickQueueFamily(physical_device_));
    // The limits as GpuDevice::describe gives them (device_limits.h), so properties() and gpu() agree; a bad
    // GUSUKU_CLAMP_LIMITS throws here, before the device exists.
    clampDeviceLimitsFromEnvironment(properties_.limits);

    subgroup_properties_ = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver_properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    const bool has_vulkan12 = instance_api_version_ >= VK_API_VERSION_1_2 && properties_.apiVersion >= VK_API_VERSION_1_2;
    if (has_vulkan12) subgroup_properties_.pNext = &driver_properties;
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &subgroup_properties_;
    vkGetPhysicalDeviceProperties2(physical_device_, &properties2);
    subgroup_properties_.pNext = nullptr;
    if (has_vulkan12) {
        // driverInfo reads "Mesa 22.3.6 (LLVM 15.0.6)"; the LLVM version is already in the device name.
        driver_info_ = driver_properties.driverInfo;
        const size_t parenthesis = driver_info_.find(" (");
        if (parenthesis != std::string::npos) driver_info_.resize(parenthesis);
    }
}

void VulkanContext::createDevice() {
    const bool has_vulkan12 = instance_api_version_ >= VK_API_VERSION_1_2 && properties_.apiVersion >= VK_API_VERSION_1_2;

    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan11Features supported11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    // Where Vulkan 1.2's structs are out of reach, 1.1's own struct for the one 1.1 feature enabled below.
    VkPhysicalDeviceSamplerYcbcrConversionFeatures supported_ycbcr{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SAMPLER_YCBCR_CONVERSION_FEATURES};
    if (has_vulkan12) {
        supported.pNext = &supported11;
        supported11.pNext = &supported12;
    } else {
        supported.pNext = &supported_ycbcr;
    }
    vkGetPhysicalDeviceFeatures2(physical_device_, &supported);

    // Only features that cost nothing when unused and that baker or runtime shaders may want. Deliberately not
    // robustBufferAccess: it slows every storage-buffer access and hides out-of-range bugs from the tests.
    const VkPhysicalDeviceFeatures& core = supported.features;
    enabled_features_ = {};
    enabled_features_.shaderInt64 = core.shaderInt64;
    enabled_features_.shaderInt16 = core.shaderInt16;
    enabled_features_.shaderFloat64 = core.shaderFloat64;
    enabled_features_.fragmentStoresAndAtomics = core.fragmentStoresAndAtomics;
    enabled_features_.vertexPipelineStoresAndAtomics = core.vertexPipelineStoresAndAtomics;
    enabled_features_.shaderStorageImageReadWithoutFormat = core.shaderStorageImageReadWithoutFormat;
    enabled_features_.shaderStorageImageWriteWithoutFormat = core.shaderStorageImageWriteWithoutFormat;
    enabled_features_.shaderStorageImageExtendedFormats = core.shaderStorageImageExtendedFormats;
    enabled_features_.samplerAnisotropy = core.samplerAnisotropy;
    enabled_features_.depthClamp = core.depthClamp;
    enabled_features_.depthBiasClamp = core.depthBiasClamp;
    enabled_features_.imageCubeArray = core.imageCubeArray;
    enabled_features_.multiDrawIndirect = core.multiDrawIndirect;
    enabled_features_.drawIndirectFirstInstance = core.drawIndirectFirstInstance;
    enabled_features_.shaderClipDistance = core.shaderClipDistance;

    VkPhysicalDeviceVulkan11Features enabled11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    enabled_vulkan12_features_ = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan12Features enabled12 = enabled_vulkan12_features_;
    if (has_vulkan12) {
        enabled11.storageBuffer16BitAccess = supported11.storageBuffer16BitAccess;
        enabled11.uniformAndStorageBuffer16BitAccess = supported11.uniformAndStorageBuffer16BitAccess;
        enabled11.shaderDrawParameters = supported11.shaderDrawParameters;
        // The runtime's zero-copy camera (runtime.h, camera_ycbcr_image) where the device has it.
        enabled11.samplerYcbcrConversion = supported11.samplerYcbcrConversion;
        enabled12.storageBuffer8BitAccess = supported12.storageBuffer8BitAccess;
        enabled12.uniformAndStorageBuffer8BitAccess = supported12.uniformAndStorageBuffer8BitAccess;
        enabled12.shaderFloat16 = supported12.shaderFloat16;
        enabled12.shaderInt8 = supported12.shaderInt8;
        enabled12.scalarBlockLayout = supported12.scalarBlockLayout;
        enabled12.uniformBufferStandardLayout = supported12.uniformBufferStandardLayout;
        enabled12.timelineSemaphore = supported12.timelineSemaphore;
        enabled12.hostQueryReset = supported12.hostQueryReset;
        enabled12.shaderSubgroupExtendedTypes = supported12.shaderSubgroupExtendedTypes;
        enabled_vulkan12_features_ = enabled12;
        enabled11.pNext = &enabled12;
    }

    VkPhysicalDeviceFeatures2 enabled{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    enabled.features = enabled_features_;
    VkPhysicalDeviceSamplerYcbcrConversionFeatures enabled_ycbcr = supported_ycbcr;
    enabled_ycbcr.pNext = nullptr;
    if (has_vulkan12) enabled.pNext = &enabled11;
    else if (enabled_ycbcr.samplerYcbcrConversion) enabled.pNext = &enabled_ycbcr;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;

    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.pNext = &enabled;  // features through pNext, so pEnabledFeatures stays null
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    checkVk(vkCreateDevice(physical_device_, &device_info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    gpu_ = GpuDevice::describe(instance_, physical_device_, device_, queue_, queue_family_, &queue_mutex_);
    submitter_ = std::make_unique<GpuSubmitter>(gpu_);
}

std::string VulkanContext::deviceDescription() const {
    std::string description = std::string(properties_.deviceName) + ", " + deviceTypeName(properties_.deviceType) +
                              ", Vulkan " + versionString(properties_.apiVersion);
    if (!driver_info_.empty()) description += ", driver " + driver_info_;
    return description;
}

bool VulkanContext::isSoftwareRasterizer() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

void VulkanContext::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
    submitter_->submitAndWait(record);
}

uint32_t VulkanContext::findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags properties) const {
    return gpu_.findMemoryType(type_bits, properties);
}

std::vector<std::string> VulkanContext::validationMessages() const {
    std::lock_guard<std::mutex> lock(messages_mutex_);
    return validation_messages_;
}

size_t VulkanContext::validationMessageCount() const {
    std::lock_guard<std::mutex> lock(messages_mutex_);
    return validation_messages_.size();
}

void VulkanContext::recordValidationMessage(std::string message) {
    std::cerr << "gusuku: Vulkan validation: " << message << '\n';
    std::lock_guard<std::mutex> lock(messages_mutex_);
    validation_messages_.push_back(std::move(message));
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT types,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                            void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT || user == nullptr) return VK_FALSE;
    if (isVulkanLoaderMessage(types, data)) {  // a note about the installed drivers: shown, not counted
        std::cerr << "gusuku: Vulkan loader: " << (data->pMessage ? data->pMessage : "(no text)") << '\n';
        return VK_FALSE;
    }
    std::string message = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "ERROR [" : "WARNING [";
    message += data && data->pMessageIdName ? data->pMessageIdName : "no message id";
    message += "] ";
    message += data && data->pMessage ? data->pMessage : "(no text)";
    static_cast<VulkanContext*>(user)->recordValidationMessage(std::move(message));
    return VK_FALSE;  // the spec asks callbacks to return false: never abort the call
}

}  // namespace gusuku

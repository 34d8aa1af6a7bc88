#pragma once
// One headless Vulkan context for the tools (the baker, gusuku-render, the bench) and for tests: it owns an
// instance, one device with a compute (and graphics, when present) queue, and optional Khronos validation whose
// messages are collected so that tests can fail on any of them. Everything that runs on the GPU takes the
// non-owning GpuDevice view (gpu_device.h), which this context owns one of and converts to, so the same code
// runs on an AR app's own device.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

namespace gusuku {

struct VulkanContextOptions {
    /// Enable VK_LAYER_KHRONOS_validation and collect its messages. Default: on when the environment
    /// variable GUSUKU_VALIDATION is 1. Tests force it on.
    bool enable_validation = false;
    /// With validation: also enable the layer's synchronization validation (missing barriers between
    /// dispatches, SYNC-HAZARD-* messages) through VK_EXT_validation_features, where the layer offers it.
    /// Measured on lavapipe: no visible cost for test_vulkan. GUSUKU_SYNC_VALIDATION=0 turns it off.
    bool enable_synchronization_validation = true;
    /// Substring of the device name to pick ("llvmpipe", "NVIDIA"); empty: a discrete or integrated GPU if one
    /// exists, else lavapipe. The environment variable GUSUKU_DEVICE overrides an empty value.
    std::string device_name_filter;
};

/// Options read from the environment (GUSUKU_VALIDATION, GUSUKU_SYNC_VALIDATION, GUSUKU_DEVICE).
VulkanContextOptions vulkanOptionsFromEnvironment();

class VulkanContext {
public:
    /// Throws std::runtime_error with a readable reason when no Vulkan device (or the validation layer, if
    /// asked for) is available.
    explicit VulkanContext(const VulkanContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    /// The non-owning view of this context's device, valid for the context's life. The conversion lets a
    /// VulkanContext be passed wherever a `const GpuDevice&` is taken.
    const GpuDevice& gpu() const { return gpu_; }
    operator const GpuDevice&() const { return gpu_; }

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_device_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queue_family_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }

    /// "llvmpipe (LLVM 15.0.6, 256 bits), CPU, Vulkan 1.3.230, driver Mesa 22.3.6"
    std::string deviceDescription() const;
    bool isSoftwareRasterizer() const;

    /// Records a one-shot command buffer, submits it and waits on a fence.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

    /// Index of a memory type allowed by type_bits with the given properties; throws if none.
    uint32_t findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags properties) const;

    bool validationEnabled() const { return validation_enabled_; }
    /// Subgroup size and supported stages/operations (lavapipe: 8 lanes, arithmetic supported in compute).
    const VkPhysicalDeviceSubgroupProperties& subgroupProperties() const { return subgroup_properties_; }
    /// The core features enabled on the device: the useful, harmless subset of what it supports (64-bit and
    /// 16-bit integers, doubles, storage writes from fragment shaders, format-less storage images, ...).
    const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabled_features_; }
    /// Vulkan 1.2 features enabled the same way (8-bit storage, float16/int8 arithmetic, scalar block layout,
    /// timeline semaphores, host query reset); all false when the device or instance is only Vulkan 1.1.
    const VkPhysicalDeviceVulkan12Features& enabledVulkan12Features() const { return enabled_vulkan12_features_; }

    /// Validation warnings and errors seen so far (info and verbose messages are not collected).
    /// Each reads "<ERROR|WARNING> [<message id name>] <message>".
    std::vector<std::string> validationMessages() const;
    size_t validationMessageCount() const;

private:
    void createInstance(const VulkanContextOptions& options);
    void pickPhysicalDevice(const VulkanContextOptions& options);
    void createDevice();
    void destroy() noexcept;
    void recordValidationMessage(std::string message);

    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceSubgroupProperties subgroup_properties_{};
    VkPhysicalDeviceFeatures enabled_features_{};
    VkPhysicalDeviceVulkan12Features enabled_vulkan12_features_{};  // pNext is kept null
    uint32_t instance_api_version_ = VK_API_VERSION_1_1;
    std::string driver_info_;  // "Mesa 22.3.6"; empty below Vulkan 1.2
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    GpuDevice gpu_;                           // the view handed to everything that runs on this device
    std::mutex queue_mutex_;                  // the queue needs external synchronisation (gpu_.queue_mutex)
    std::unique_ptr<GpuSubmitter> submitter_;  // submitAndWait's pool and fence
    bool validation_enabled_ = false;
    mutable std::mutex messages_mutex_;
    std::vector<std::string> validation_messages_;
};

}  // namespace gusuku

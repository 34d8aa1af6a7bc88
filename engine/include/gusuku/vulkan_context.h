#pragma once
// One headless Vulkan context for the baker, the runtime and the bench: instance, one device with a compute
// (and graphics, when present) queue, a command pool, and optional Khronos validation whose messages are
// collected so that tests can fail on any of them.

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace gusuku {

struct VulkanContextOptions {
    /// Enable VK_LAYER_KHRONOS_validation and collect its messages. Default: on when the environment
    /// variable GUSUKU_VALIDATION is 1. Tests force it on.
    bool enable_validation = false;
    /// Substring of the device name to pick ("llvmpipe", "NVIDIA"); empty: a discrete or integrated GPU if one
    /// exists, else lavapipe. The environment variable GUSUKU_DEVICE overrides an empty value.
    std::string device_name_filter;
};

/// Options read from the environment (GUSUKU_VALIDATION, GUSUKU_DEVICE).
VulkanContextOptions vulkanOptionsFromEnvironment();

class VulkanContext {
public:
    /// Throws std::runtime_error with a readable reason when no Vulkan device (or the validation layer, if
    /// asked for) is available.
    explicit VulkanContext(const VulkanContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

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
    /// Validation warnings and errors seen so far (info and verbose messages are not collected).
    std::vector<std::string> validationMessages() const;
    size_t validationMessageCount() const;

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool validation_enabled_ = false;
    mutable std::mutex messages_mutex_;
    std::vector<std::string> validation_messages_;
};

/// Throws std::runtime_error naming the call when result is not VK_SUCCESS.
void checkVk(VkResult result, const char* what);

}  // namespace gusuku

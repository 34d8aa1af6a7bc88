#pragma once
// One Vulkan object a pass owns, destroyed with it: the passes (frame_pass.h) hold their pipelines, layouts,
// render passes and framebuffers in these, so each pass's destroy is its destructor and a constructor that throws
// half-way leaves nothing behind. Private to gusuku_runtime.

#include <initializer_list>
#include <utility>

#include <vulkan/vulkan.h>

namespace gusuku::runtime_detail {

template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class DeviceObject {
public:
    DeviceObject() = default;
    DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
    ~DeviceObject() { reset(); }
    DeviceObject(DeviceObject&& other) noexcept
        : device_(other.device_), handle_(std::exchange(other.handle_, Handle(VK_NULL_HANDLE))) {}
    DeviceObject& operator=(DeviceObject&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = other.device_;
            handle_ = std::exchange(other.handle_, Handle(VK_NULL_HANDLE));
        }
        return *this;
    }
    DeviceObject(const DeviceObject&) = delete;
    DeviceObject& operator=(const DeviceObject&) = delete;

    Handle get() const { return handle_; }
    void reset() noexcept {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Handle handle_ = VK_NULL_HANDLE;
};

using Pipeline = DeviceObject<VkPipeline, vkDestroyPipeline>;
using PipelineLayout = DeviceObject<VkPipelineLayout, vkDestroyPipelineLayout>;
using RenderPass = DeviceObject<VkRenderPass, vkDestroyRenderPass>;
using Framebuffer = DeviceObject<VkFramebuffer, vkDestroyFramebuffer>;
using Sampler = DeviceObject<VkSampler, vkDestroySampler>;
using DescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = DeviceObject<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPool = DeviceObject<VkCommandPool, vkDestroyCommandPool>;
using Fence = DeviceObject<VkFence, vkDestroyFence>;

/// A pipeline layout of the given set layouts and one push-constant range (size 0: none).
PipelineLayout createPipelineLayout(VkDevice device, std::initializer_list<VkDescriptorSetLayout> set_layouts,
                                    VkShaderStageFlags push_stages, uint32_t push_bytes);

}  // namespace gusuku::runtime_detail

// The non-owning device view and one-shot submissions (see gpu_device.h for the contract).

#include "gusuku/gpu/gpu_device.h"

#include "gusuku/gpu/device_limits.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace gusuku {

void checkVk(VkResult result, const char* what) {
    if (result != VK_SUCCESS)
        throw std::runtime_error(std::string("Vulkan: ") + what + " failed with VkResult " + std::to_string(result));
}

GpuDevice GpuDevice::describe(VkInstance instance, VkPhysicalDevice physical_device, VkDevice device,
                              VkQueue queue, uint32_t queue_family_index, std::mutex* queue_mutex,
                              uint32_t instance_api_version) {
    GpuDevice gpu;
    gpu.instance = instance;
    gpu.physical_device = physical_device;
    gpu.device = device;
    gpu.queue = queue;
    gpu.queue_family_index = queue_family_index;
    gpu.queue_mutex = queue_mutex;
    gpu.instance_api_version = instance_api_version;
    if (physical_device != VK_NULL_HANDLE) {
        vkGetPhysicalDeviceProperties(physical_device, &gpu.properties);
        // The one place gusuku reads limits from: lowered here when GUSUKU_CLAMP_LIMITS asks (device_limits.h).
        clampDeviceLimitsFromEnvironment(gpu.properties.limits);
        vkGetPhysicalDeviceMemoryProperties(physical_device, &gpu.memory_properties);
    }
    return gpu;
}

int32_t GpuDevice::findMemoryTypePreferring(uint32_t type_bits, VkMemoryPropertyFlags required,
                                            VkMemoryPropertyFlags preferred) const {
    for (const VkMemoryPropertyFlags wanted : {required | preferred, required})
        for (uint32_t index = 0; index < memory_properties.memoryTypeCount; ++index)
            if ((type_bits & (1u << index)) && (memory_properties.memoryTypes[index].propertyFlags & wanted) == wanted)
                return static_cast<int32_t>(index);
    return -1;
}

uint32_t GpuDevice::findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required) const {
    const int32_t index = findMemoryTypePreferring(type_bits, required, 0);
    if (index >= 0) return static_cast<uint32_t>(index);
    std::ostringstream message;
    message << "Vulkan: no memory type with property flags 0x" << std::hex << required << " among allowed types 0x"
            << type_bits << " on " << properties.deviceName;
    throw std::runtime_error(message.str());
}

VkResult GpuDevice::submitToQueue(const VkSubmitInfo& submit_info, VkFence fence) const {
    if (queue_mutex == nullptr) return vkQueueSubmit(queue, 1, &submit_info, fence);
    std::lock_guard<std::mutex> lock(*queue_mutex);
    return vkQueueSubmit(queue, 1, &submit_info, fence);
}

GpuSubmitter::GpuSubmitter(const GpuDevice& gpu) : gpu_(gpu) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;  // one-shot command buffers only
    pool_info.queueFamilyIndex = gpu.queue_family_index;
    checkVk(vkCreateCommandPool(gpu.device, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    const VkResult fence_created = vkCreateFence(gpu.device, &fence_info, nullptr, &fence_);
    if (fence_created != VK_SUCCESS) {
        vkDestroyCommandPool(gpu.device, command_pool_, nullptr);
        checkVk(fence_created, "vkCreateFence");
    }
}

GpuSubmitter::~GpuSubmitter() {
    if (fence_ != VK_NULL_HANDLE) vkDestroyFence(gpu_.device, fence_, nullptr);
    if (command_pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(gpu_.device, command_pool_, nullptr);
}

void GpuSubmitter::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
    std::lock_guard<std::mutex> own_lock(own_mutex_);
    VkDevice device = gpu_.device;

    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = command_pool_;
    allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate_info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    checkVk(vkAllocateCommandBuffers(device, &allocate_info, &cmd), "vkAllocateCommandBuffers");

    try {
        VkCommandBufferBeginInfo begin_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin_info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        checkVk(vkBeginCommandBuffer(cmd, &begin_info), "vkBeginCommandBuffer");
        record(cmd);
        checkVk(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

        VkSubmitInfo submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit_info.commandBufferCount = 1;
        submit_info.pCommandBuffers = &cmd;
        checkVk(gpu_.submitToQueue(submit_info, fence_), "vkQueueSubmit");
    } catch (...) {
        // Not submitted, so not pending: safe to free.
        vkFreeCommandBuffers(device, command_pool_, 1, &cmd);
        throw;
    }
    // Once submitted, a failed wait (device lost) leaves the buffer possibly pending: leak it rather than free it.
    checkVk(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    checkVk(vkResetFences(device, 1, &fence_), "vkResetFences");
    vkFreeCommandBuffers(device, command_pool_, 1, &cmd);
}

}  // namespace gusuku

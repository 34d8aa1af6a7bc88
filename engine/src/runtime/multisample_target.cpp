// The main pass's multisampled attachments (multisample_target.h).

#include "multisample_target.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace gusuku::runtime_detail {

MultisampleTarget::MultisampleTarget(const GpuDevice& gpu, const MultisampleTargetDescription& description)
    : device_(gpu.device) {
    const bool depth = (description.aspect & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT |
                                    (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                           : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    VkImageFormatProperties properties{};
    const VkResult supported = vkGetPhysicalDeviceImageFormatProperties(
        gpu.physical_device, description.format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0, &properties);
    if (supported != VK_SUCCESS || (properties.sampleCounts & description.samples) == 0)
        throw std::runtime_error("multisampled " + std::string(depth ? "depth" : "colour") + " attachment: format " +
                                 std::to_string(int(description.format)) + " cannot have " +
                                 std::to_string(int(description.samples)) + " samples on " +
                                 gpu.properties.deviceName);
    try {
        VkImageCreateInfo image_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        image_info.imageType = VK_IMAGE_TYPE_2D;
        image_info.format = description.format;
        image_info.extent = {description.width, description.height, 1};
        image_info.mipLevels = 1;
        image_info.arrayLayers = 1;
        image_info.samples = description.samples;
        image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
        image_info.usage = usage;
        image_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        checkVk(vkCreateImage(device_, &image_info, nullptr, &image_), "vkCreateImage (multisampled)");

        VkMemoryRequirements requirements;
        vkGetImageMemoryRequirements(device_, image_, &requirements);
        const int32_t lazy = gpu.findMemoryTypePreferring(requirements.memoryTypeBits,
                                                          VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT, 0);
        VkMemoryAllocateInfo allocate_info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        allocate_info.allocationSize = requirements.size;
        allocate_info.memoryTypeIndex =
            lazy >= 0 ? uint32_t(lazy)
                      : gpu.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        lazily_allocated_ = lazy >= 0;
        const VkResult allocated = vkAllocateMemory(device_, &allocate_info, nullptr, &memory_);
        if (allocated == VK_ERROR_OUT_OF_HOST_MEMORY || allocated == VK_ERROR_OUT_OF_DEVICE_MEMORY)
            throw std::runtime_error("multisampled attachment: out of memory allocating " +
                                     std::to_string(requirements.size) + " bytes");
        checkVk(allocated, "vkAllocateMemory (multisampled)");
        memory_bytes_ = requirements.size;
        checkVk(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory (multisampled)");

        VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view_info.image = image_;
        view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view_info.format = description.format;
        view_info.subresourceRange = {description.aspect, 0, 1, 0, 1};
        checkVk(vkCreateImageView(device_, &view_info, nullptr, &view_), "vkCreateImageView (multisampled)");
    } catch (...) {
        release();
        throw;
    }
}

MultisampleTarget::~MultisampleTarget() { release(); }

MultisampleTarget::MultisampleTarget(MultisampleTarget&& other) noexcept { *this = std::move(other); }

MultisampleTarget& MultisampleTarget::operator=(MultisampleTarget&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
        memory_bytes_ = std::exchange(other.memory_bytes_, 0);
        lazily_allocated_ = std::exchange(other.lazily_allocated_, false);
    }
    return *this;
}

void MultisampleTarget::release() noexcept {
    if (device_ == VK_NULL_HANDLE) return;
    if (view_) vkDestroyImageView(device_, view_, nullptr);
    if (image_) vkDestroyImage(device_, image_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    memory_bytes_ = 0;
}

}  // namespace gusuku::runtime_detail

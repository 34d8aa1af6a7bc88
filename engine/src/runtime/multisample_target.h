#pragma once
// A multisampled attachment of the main pass (RuntimeOptions::msaa_samples > 1): colour or depth, frame-sized,
// with its memory and one view. Only the render pass reads and writes it (the colour is resolved into the
// composite at the pass's end), so it is made TRANSIENT_ATTACHMENT and bound to lazily allocated memory where
// the device has such a type (a tiler then never backs it with memory); elsewhere device-local memory. Kept apart
// from gpu_image.h, whose images are single-sampled and sampled or uploaded. Private to gusuku_runtime.

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

namespace gusuku::runtime_detail {

struct MultisampleTargetDescription {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;  ///< COLOR or DEPTH: which attachment usage it gets
    uint32_t width = 0;
    uint32_t height = 0;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;
};

class MultisampleTarget {
public:
    MultisampleTarget() = default;
    /// Throws std::runtime_error when the device cannot make it (format, sample count) or on Vulkan failure.
    MultisampleTarget(const GpuDevice& gpu, const MultisampleTargetDescription& description);
    ~MultisampleTarget();
    MultisampleTarget(MultisampleTarget&& other) noexcept;
    MultisampleTarget& operator=(MultisampleTarget&& other) noexcept;
    MultisampleTarget(const MultisampleTarget&) = delete;
    MultisampleTarget& operator=(const MultisampleTarget&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    /// The allocation's size (lazily allocated memory may commit less of it).
    VkDeviceSize memoryBytes() const { return memory_bytes_; }
    bool lazilyAllocated() const { return lazily_allocated_; }

private:
    void release() noexcept;
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceSize memory_bytes_ = 0;
    bool lazily_allocated_ = false;
};

}  // namespace gusuku::runtime_detail

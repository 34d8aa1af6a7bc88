#pragma once
// Images for the runtime's raster passes (gusuku_gpu): a 2D image or 2D array with its memory and one view, on a
// GpuDevice, plus the layout transition and upload helpers the runtime needs when it opens. The baker needs
// none of this (its textures travel as storage buffers).

#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

namespace gusuku {

struct GpuImageDescription {
    VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t layers = 1;          ///< > 1 makes a 2D-array view
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    bool array_view = false;      ///< view as VK_IMAGE_VIEW_TYPE_2D_ARRAY even with one layer
};

/// A device-local optimal-tiling image with one view (2D, or 2D array). Created in VK_IMAGE_LAYOUT_UNDEFINED.
/// Throws std::runtime_error when the format does not support the usage, or on Vulkan failure.
class GpuImage {
public:
    GpuImage() = default;
    GpuImage(const GpuDevice& gpu, const GpuImageDescription& description);
    ~GpuImage();
    GpuImage(GpuImage&& other) noexcept;
    GpuImage& operator=(GpuImage&& other) noexcept;
    GpuImage(const GpuImage&) = delete;
    GpuImage& operator=(const GpuImage&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    const GpuImageDescription& description() const { return description_; }
    VkDeviceSize memoryBytes() const { return memory_bytes_; }

    /// Uploads `bytes` (tightly packed texels of layer `layer`, row 0 first) through a staging buffer and leaves
    /// the whole image in `final_layout`. One submission, waited for: for setup only.
    void upload(const void* bytes, size_t byte_count, uint32_t layer, VkImageLayout final_layout);

private:
    void release() noexcept;
    const GpuDevice* gpu_ = nullptr;
    GpuImageDescription description_;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceSize memory_bytes_ = 0;
    VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;  // of every layer: uploads move all layers together
};

/// Records a layout transition of every layer and mip of `image` with full-pipeline stage masks (setup and
/// per-frame transitions of a handful of images: the masks' generality costs nothing measurable on lavapipe).
void recordImageLayoutTransition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                                 VkImageLayout old_layout, VkImageLayout new_layout, VkAccessFlags source_access,
                                 VkAccessFlags destination_access, VkPipelineStageFlags source_stages,
                                 VkPipelineStageFlags destination_stages);

/// Bytes per texel of the formats the runtime uses; 0 for others.
uint32_t bytesPerTexel(VkFormat format);

}  // namespace gusuku

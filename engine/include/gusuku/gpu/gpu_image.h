#pragma once
// Images for the runtime's raster passes (gusuku_gpu): a 2D image or 2D array with its memory and one view, on a
// GpuDevice, plus the layout transition, upload and mip-chain helpers the runtime needs when it opens. The baker
// needs none of this (its textures travel as storage buffers).

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
    /// Mip levels, 1 to fullMipLevelCount(width, height); the view spans all of them. Level l is
    /// max(1, width >> l) x max(1, height >> l).
    uint32_t mip_levels = 1;
};

/// Levels of a full mip chain down to 1 x 1: floor(log2(max(width, height))) + 1.
uint32_t fullMipLevelCount(uint32_t width, uint32_t height);

/// Whether `format` can have its mip chain made on the GPU by generateMipChain: optimal tiling with BLIT_SRC,
/// BLIT_DST and SAMPLED_IMAGE_FILTER_LINEAR (a linear blit; for an sRGB format the blit filters in linear light).
bool canBlitMipChain(const GpuDevice& gpu, VkFormat format);

/// A device-local optimal-tiling image with one view (2D, or 2D array) over all its layers and mip levels.
/// Created in VK_IMAGE_LAYOUT_UNDEFINED. Throws std::runtime_error when the format does not support the usage,
/// std::invalid_argument for a mip_levels outside [1, fullMipLevelCount], or on Vulkan failure.
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
    VkDeviceSize memoryBytes() const { return memory_bytes_; }  ///< the allocation: every layer and level

    /// Uploads `bytes` (tightly packed texels of level `level` of layer `layer`, row 0 first) through a staging
    /// buffer and leaves the whole image in `final_layout`. One submission, waited for: for setup only.
    void upload(const void* bytes, size_t byte_count, uint32_t layer, VkImageLayout final_layout,
                uint32_t level = 0);

    /// Fills levels 1 .. mip_levels - 1 of every layer from level 0 (already uploaded) by linear blits down the
    /// chain, each level from the one above, and leaves the whole image in `final_layout`. Needs
    /// canBlitMipChain(format) and usage TRANSFER_SRC | TRANSFER_DST (std::runtime_error otherwise). One
    /// submission, waited for: for setup only. Each level's texel is the mean of the 2 x 2 texels above it when
    /// the sides are even (a linear filter sampled at their shared corner); odd sides are filtered as the
    /// device's linear blit does.
    void generateMipChain(VkImageLayout final_layout);

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

/// Bytes per texel of the formats the runtime uses; 0 for others (and for block-compressed ones).
uint32_t bytesPerTexel(VkFormat format);
/// Bytes one width x height level of `format` takes: texels times bytesPerTexel, or for a block format of the
/// format table (gusuku/formats/format_table.h: ASTC) its block_bytes for every started block; 0 for formats the
/// runtime does not use.
size_t levelByteCount(VkFormat format, uint32_t width, uint32_t height);

}  // namespace gusuku

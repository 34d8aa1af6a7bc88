// Device-local images with one view, their setup uploads and mip chains (see gpu_image.h).

#include "gusuku/gpu/gpu_image.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "gusuku/formats/format_table.h"
#include "gusuku/gpu/gpu_compute.h"

namespace gusuku {

uint32_t bytesPerTexel(VkFormat format) {
    // The stored formats (lightmaps, textures, the pack's data) from the format table; the rest are the
    // runtime's own attachments and camera planes.
    if (const formats::FormatRow* row = formats::findFormat(uint32_t(format)))
        return row->block_side == 1 ? row->block_bytes : 0;
    switch (format) {
        case VK_FORMAT_R8G8_UNORM: return 2;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_D32_SFLOAT: return 4;
        default: return 0;
    }
}

size_t levelByteCount(VkFormat format, uint32_t width, uint32_t height) {
    if (const formats::FormatRow* row = formats::findFormat(uint32_t(format)))
        return size_t(formats::levelBytes(*row, width, height));
    return size_t(width) * height * bytesPerTexel(format);
}

namespace {

uint32_t levelSide(uint32_t side, uint32_t level) { return std::max(1u, side >> level); }

// A layout transition of `level_count` levels from `first_level`, every layer.
void recordLevelsTransition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, uint32_t first_level,
                            uint32_t level_count, VkImageLayout old_layout, VkImageLayout new_layout,
                            VkAccessFlags source_access, VkAccessFlags destination_access,
                            VkPipelineStageFlags source_stages, VkPipelineStageFlags destination_stages) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = source_access;
    barrier.dstAccessMask = destination_access;
    barrier.oldLayout = old_layout;
    barrier.newLayout = new_layout;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {aspect, first_level, level_count, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdPipelineBarrier(cmd, source_stages, destination_stages, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace

uint32_t fullMipLevelCount(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    for (uint32_t side = std::max(width, height); side > 1; side >>= 1) ++levels;
    return levels;
}

bool canBlitMipChain(const GpuDevice& gpu, VkFormat format) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, format, &properties);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (properties.optimalTilingFeatures & needed) == needed;
}

GpuImage::GpuImage(const GpuDevice& gpu, const GpuImageDescription& description)
    : gpu_(&gpu), description_(description) {
    const uint32_t most_levels = fullMipLevelCount(description.width, description.height);
    if (description.mip_levels < 1 || description.mip_levels > most_levels)
        throw std::invalid_argument("GpuImage: mip_levels " + std::to_string(description.mip_levels) +
                                    " is outside [1, " + std::to_string(most_levels) + "] for a " +
                                    std::to_string(description.width) + " x " +
                                    std::to_string(description.height) + " image");
    VkFormatProperties format_properties;
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, description.format, &format_properties);
    const VkFormatFeatureFlags features = format_properties.optimalTilingFeatures;
    auto require = [&](VkImageUsageFlags usage, VkFormatFeatureFlags feature, const char* what) {
        if ((description.usage & usage) && !(features & feature))
            throw std::runtime_error(std::string("GpuImage: format ") + std::to_string(description.format) +
                                     " cannot be used as " + what + " on " + gpu.properties.deviceName);
    };
    require(VK_IMAGE_USAGE_SAMPLED_BIT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "a sampled image");
    require(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "a colour attachment");
    require(VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
            "a depth attachment");

    VkDevice device = gpu.device;
    try {
        VkImageCreateInfo image_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        image_info.imageType = VK_IMAGE_TYPE_2D;
        image_info.format = description.format;
        image_info.extent = {description.width, description.height, 1};
        image_info.mipLevels = description.mip_levels;
        image_info.arrayLayers = description.layers;
        image_info.samples = VK_SAMPLE_COUNT_1_BIT;
        image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
        image_info.usage = description.usage;
        image_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        checkVk(vkCreateImage(device, &image_info, nullptr, &image_), "vkCreateImage");

        VkMemoryRequirements requirements;
        vkGetImageMemoryRequirements(device, image_, &requirements);
        VkMemoryAllocateInfo allocate_info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        allocate_info.allocationSize = requirements.size;
        allocate_info.memoryTypeIndex =
            gpu.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        const VkResult allocated = vkAllocateMemory(device, &allocate_info, nullptr, &memory_);
        if (allocated == VK_ERROR_OUT_OF_HOST_MEMORY || allocated == VK_ERROR_OUT_OF_DEVICE_MEMORY)
            throw std::runtime_error("GpuImage: out of memory allocating " + std::to_string(requirements.size) +
                                     " bytes");
        checkVk(allocated, "vkAllocateMemory");
        memory_bytes_ = requirements.size;
        checkVk(vkBindImageMemory(device, image_, memory_, 0), "vkBindImageMemory");

        VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view_info.image = image_;
        view_info.viewType =
            description.layers > 1 || description.array_view ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
        view_info.format = description.format;
        view_info.subresourceRange = {description.aspect, 0, description.mip_levels, 0, description.layers};
        checkVk(vkCreateImageView(device, &view_info, nullptr, &view_), "vkCreateImageView");
    } catch (...) {
        release();
        throw;
    }
}

GpuImage::~GpuImage() { release(); }

GpuImage::GpuImage(GpuImage&& other) noexcept
    : gpu_(std::exchange(other.gpu_, nullptr)),
      description_(other.description_),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      view_(std::exchange(other.view_, VK_NULL_HANDLE)),
      memory_bytes_(std::exchange(other.memory_bytes_, 0)),
      layout_(other.layout_) {}

GpuImage& GpuImage::operator=(GpuImage&& other) noexcept {
    if (this != &other) {
        release();
        gpu_ = std::exchange(other.gpu_, nullptr);
        description_ = other.description_;
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
        memory_bytes_ = std::exchange(other.memory_bytes_, 0);
        layout_ = other.layout_;
    }
    return *this;
}

void GpuImage::release() noexcept {
    if (gpu_ != nullptr) {
        if (view_ != VK_NULL_HANDLE) vkDestroyImageView(gpu_->device, view_, nullptr);
        if (image_ != VK_NULL_HANDLE) vkDestroyImage(gpu_->device, image_, nullptr);
        if (memory_ != VK_NULL_HANDLE) vkFreeMemory(gpu_->device, memory_, nullptr);
    }
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    memory_bytes_ = 0;
}

void GpuImage::upload(const void* bytes, size_t byte_count, uint32_t layer, VkImageLayout final_layout,
                      uint32_t level) {
    if (level >= description_.mip_levels)
        throw std::invalid_argument("GpuImage::upload: level " + std::to_string(level) + " of an image with " +
                                    std::to_string(description_.mip_levels) + " levels");
    const uint32_t width = levelSide(description_.width, level), height = levelSide(description_.height, level);
    const size_t expected = levelByteCount(description_.format, width, height);
    if (expected == 0 || byte_count != expected || layer >= description_.layers)
        throw std::invalid_argument("GpuImage::upload: " + std::to_string(byte_count) + " bytes for layer " +
                                    std::to_string(layer) + " level " + std::to_string(level) +
                                    " of an image needing " + std::to_string(expected));
    GpuBuffer staging(*gpu_, byte_count, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuMemory::kHostVisible);
    staging.upload(bytes, byte_count);
    GpuSubmitter submitter(*gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        recordImageLayoutTransition(cmd, image_, description_.aspect, layout_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {description_.aspect, level, layer, 1};
        region.imageExtent = {width, height, 1};
        vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        recordImageLayoutTransition(cmd, image_, description_.aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    final_layout, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    });
    layout_ = final_layout;
}

void GpuImage::generateMipChain(VkImageLayout final_layout) {
    const VkImageUsageFlags transfer = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if ((description_.usage & transfer) != transfer || !canBlitMipChain(*gpu_, description_.format))
        throw std::runtime_error("GpuImage::generateMipChain: format " + std::to_string(description_.format) +
                                 " with usage " + std::to_string(description_.usage) +
                                 " cannot be blitted with linear filtering on " + gpu_->properties.deviceName);
    const uint32_t levels = description_.mip_levels;
    const VkImageAspectFlags aspect = description_.aspect;
    const VkPipelineStageFlags transfer_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    GpuSubmitter submitter(*gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        // Every level to TRANSFER_DST (level 0 keeps its texels: its old layout is defined), then each level
        // in turn becomes the source of the next.
        recordImageLayoutTransition(cmd, image_, aspect, layout_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, transfer_stage);
        for (uint32_t level = 1; level < levels; ++level) {
            recordLevelsTransition(cmd, image_, aspect, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                   VK_ACCESS_TRANSFER_READ_BIT, transfer_stage, transfer_stage);
            VkImageBlit blit{};
            blit.srcSubresource = {aspect, level - 1, 0, description_.layers};
            blit.srcOffsets[1] = {int32_t(levelSide(description_.width, level - 1)),
                                  int32_t(levelSide(description_.height, level - 1)), 1};
            blit.dstSubresource = {aspect, level, 0, description_.layers};
            blit.dstOffsets[1] = {int32_t(levelSide(description_.width, level)),
                                  int32_t(levelSide(description_.height, level)), 1};
            vkCmdBlitImage(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image_,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        }
        if (levels > 1)
            recordLevelsTransition(cmd, image_, aspect, 0, levels - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   final_layout, VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_SHADER_READ_BIT,
                                   transfer_stage, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
        recordLevelsTransition(cmd, image_, aspect, levels - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               final_layout, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                               transfer_stage, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    });
    layout_ = final_layout;
}

void recordImageLayoutTransition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                                 VkImageLayout old_layout, VkImageLayout new_layout, VkAccessFlags source_access,
                                 VkAccessFlags destination_access, VkPipelineStageFlags source_stages,
                                 VkPipelineStageFlags destination_stages) {
    recordLevelsTransition(cmd, image, aspect, 0, VK_REMAINING_MIP_LEVELS, old_layout, new_layout, source_access,
                           destination_access, source_stages, destination_stages);
}

}  // namespace gusuku

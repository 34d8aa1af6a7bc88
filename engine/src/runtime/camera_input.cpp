// The camera frame into the runtime (camera_input.h).

#include "camera_input.h"

#include <algorithm>
#include <string>

#include "camera_frag_spv.h"
#include "camera_interface.h"
#include "camera_pack_comp_spv.h"
#include "camera_pack_ycbcr_comp_spv.h"
#include "camera_vert_spv.h"
#include "camera_ycbcr_frag_spv.h"
#include "runtime_pipelines.h"

namespace gusuku::runtime_detail {

using shader_interface::CameraPushConstants;

namespace {

constexpr VkShaderStageFlags kCameraStages = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
// Stages that read the camera's planes (the camera-in draw, the packing kernel).
constexpr VkPipelineStageFlags kCameraReaders =
    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;

bool isYuv(CameraFormat format) { return format == CameraFormat::kNv12 || format == CameraFormat::kNv21; }

bool isSrgbFormat(VkFormat format) {
    return format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_B8G8R8A8_SRGB;
}

// The app image formats a camera format accepts (FrameInput::camera_image_format).
bool acceptsImageFormat(CameraFormat camera, bool zero_copy, VkFormat format) {
    if (zero_copy) return format == kYcbcrCameraFormat;
    switch (camera) {
        case CameraFormat::kRgba8: return format == VK_FORMAT_R8G8B8A8_UNORM || format == VK_FORMAT_R8G8B8A8_SRGB;
        case CameraFormat::kBgra8: return format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
        default: return false;
    }
}

VkImageLayout sampledLayoutFor(VkImageLayout given) {
    return given == VK_IMAGE_LAYOUT_GENERAL ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

}  // namespace

CameraPlaneFormats cameraPlaneFormats(CameraFormat format) {
    switch (format) {
        // _SRGB: the sampler decodes (a table on most hardware) instead of the shader's pow per pixel.
        case CameraFormat::kRgba8: return {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_UNDEFINED};
        case CameraFormat::kBgra8: return {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_UNDEFINED};
        case CameraFormat::kNv12:
        case CameraFormat::kNv21: return {VK_FORMAT_R8_UNORM, VK_FORMAT_R8G8_UNORM};
    }
    return {};
}

CameraInput::CameraInput(const GpuDevice& gpu, const RuntimeOptions& options, uint32_t slot_count, bool pack)
    : gpu_(gpu),
      width_(options.frame_width),
      height_(options.frame_height),
      format_(options.camera_format),
      ycbcr_model_(options.camera_ycbcr_model),
      ycbcr_range_(options.camera_ycbcr_range),
      plane_formats_(cameraPlaneFormats(options.camera_format)) {
    try {
        if (options.camera_ycbcr_image) {
            ycbcr_ = std::make_unique<YcbcrCameraSampler>(gpu_, options);
        } else {
            createPlanes(slot_count);
        }
        specialisation_values_ = {isYuv(format_) ? CAMERA_KIND_TWO_PLANE_YUV : CAMERA_KIND_FOUR_BYTE,
                                  ycbcr_model_ == YcbcrModel::kBt709 ? 1u : 0u,
                                  ycbcr_range_ == YcbcrRange::kFull ? 1u : 0u,
                                  format_ == CameraFormat::kNv21 ? 1u : 0u,
                                  ycbcr_ && ycbcr_->filtersLinearly() ? 1u : 0u,
                                  height_};
        for (uint32_t index = 0; index < CAMERA_CONSTANT_COUNT; ++index)
            specialisation_entries_[index] = {index, uint32_t(index * sizeof(uint32_t)), sizeof(uint32_t)};
        specialisation_ = {CAMERA_CONSTANT_COUNT, specialisation_entries_.data(), sizeof(specialisation_values_),
                           specialisation_values_.data()};
        createDescriptors(slot_count);
        if (pack) createPackPipeline();
    } catch (...) {
        destroy();
        throw;
    }
}

// The runtime's own plane images and per-slot staging, for host pixels.
void CameraInput::createPlanes(uint32_t slot_count) {
    GpuImageDescription plane;
    plane.format = plane_formats_.plane0;
    plane.width = width_;
    plane.height = height_;
    plane.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    plane0_ = GpuImage(gpu_, plane);
    size_t staging_bytes = size_t(width_) * height_ * (isYuv(format_) ? 1 : 4);  // plane 0's bytes
    if (isYuv(format_)) {
        plane.format = plane_formats_.plane1;
        plane.width = width_ / 2;
        plane.height = height_ / 2;
        plane1_ = GpuImage(gpu_, plane);
        staging_bytes += size_t(width_ / 2) * (height_ / 2) * 2;
    }
    for (uint32_t slot = 0; slot < slot_count; ++slot)
        staging_.emplace_back(gpu_, staging_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuMemory::kHostVisible);
    // The planes start readable, so a set pointed at them is valid before the first upload.
    GpuSubmitter submitter(gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        for (const GpuImage* image : {&plane0_, &plane1_})
            if (image->handle() != VK_NULL_HANDLE)
                recordImageLayoutTransition(cmd, image->handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                            VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0,
                                            VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                                            kCameraReaders);
    });
}

CameraInput::~CameraInput() { destroy(); }

void CameraInput::createDescriptors(uint32_t slot_count) {
    bound_sets_.assign(slot_count, VK_NULL_HANDLE);
    slot_sources_.resize(slot_count);
    if (ycbcr_) {
        createZeroCopyDescriptors();
        return;
    }
    const VkDevice device = gpu_.device;
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};  // texelFetch only: the filter is unused
    sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    checkVk(vkCreateSampler(device, &sampler, nullptr, &sampler_), "vkCreateSampler (camera)");
    const VkDescriptorSetLayoutBinding bindings[CAMERA_BINDING_COUNT] = {
        {CAMERA_PLANE0_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kCameraStages, nullptr},
        {CAMERA_PLANE1_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kCameraStages, nullptr},
    };
    VkDescriptorSetLayoutCreateInfo layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout.bindingCount = CAMERA_BINDING_COUNT;
    layout.pBindings = bindings;
    checkVk(vkCreateDescriptorSetLayout(device, &layout, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
    const VkDescriptorSetLayoutBinding packed = {CAMERA_PACKED_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    layout.bindingCount = 1;
    layout.pBindings = &packed;
    checkVk(vkCreateDescriptorSetLayout(device, &layout, nullptr, &packed_set_layout_), "vkCreateDescriptorSetLayout");

    const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, CAMERA_BINDING_COUNT * slot_count},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = slot_count + 1;
    pool.poolSizeCount = 2;
    pool.pPoolSizes = sizes;
    checkVk(vkCreateDescriptorPool(device, &pool, nullptr, &pool_), "vkCreateDescriptorPool (camera)");
    slot_sets_.resize(slot_count);
    const std::vector<VkDescriptorSetLayout> layouts(slot_count, set_layout_);
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = pool_;
    allocate.descriptorSetCount = slot_count;
    allocate.pSetLayouts = layouts.data();
    checkVk(vkAllocateDescriptorSets(device, &allocate, slot_sets_.data()), "vkAllocateDescriptorSets (camera)");
    for (uint32_t slot = 0; slot < slot_count; ++slot) {
        pointSlotAt(slot, plane0_.view(), isYuv(format_) ? plane1_.view() : plane0_.view(),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        bound_sets_[slot] = slot_sets_[slot];
    }
}

// The zero-copy route's set layout (plane 0's binding alone, its sampler immutable: a sampler with a conversion
// can be no other way) and a set for each cached view, written when the view is made.
void CameraInput::createZeroCopyDescriptors() {
    const VkDevice device = gpu_.device;
    const VkDescriptorSetLayoutBinding binding = {CAMERA_PLANE0_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                  1, kCameraStages, ycbcr_->sampler()};
    VkDescriptorSetLayoutCreateInfo layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout.bindingCount = 1;
    layout.pBindings = &binding;
    checkVk(vkCreateDescriptorSetLayout(device, &layout, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
    const VkDescriptorSetLayoutBinding packed = {CAMERA_PACKED_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    layout.pBindings = &packed;
    checkVk(vkCreateDescriptorSetLayout(device, &layout, nullptr, &packed_set_layout_), "vkCreateDescriptorSetLayout");
    const VkDescriptorPoolSize sizes[2] = {
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(kViewCacheSize) * kMaxYcbcrDescriptorsPerSampler},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = uint32_t(kViewCacheSize) + 1;
    pool.poolSizeCount = 2;
    pool.pPoolSizes = sizes;
    checkVk(vkCreateDescriptorPool(device, &pool, nullptr, &pool_), "vkCreateDescriptorPool (camera)");
    const std::vector<VkDescriptorSetLayout> layouts(kViewCacheSize, set_layout_);
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = pool_;
    allocate.descriptorSetCount = uint32_t(kViewCacheSize);
    allocate.pSetLayouts = layouts.data();
    checkVk(vkAllocateDescriptorSets(device, &allocate, view_sets_.data()), "vkAllocateDescriptorSets (camera)");
}

void CameraInput::createPackPipeline() {
    const VkDevice device = gpu_.device;
    packed_buffer_ = GpuBuffer(gpu_, size_t(width_) * height_ * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               GpuMemory::kDeviceLocal);
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = pool_;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &packed_set_layout_;
    checkVk(vkAllocateDescriptorSets(device, &allocate, &packed_set_), "vkAllocateDescriptorSets (camera pack)");
    const VkDescriptorBufferInfo buffer{packed_buffer_.handle(), 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = packed_set_;
    write.dstBinding = CAMERA_PACKED_BINDING;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &buffer;
    vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);

    const VkDescriptorSetLayout set_layouts[2] = {set_layout_, packed_set_layout_};
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(CameraPushConstants)};
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.setLayoutCount = 2;
    layout.pSetLayouts = set_layouts;
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &push;
    checkVk(vkCreatePipelineLayout(device, &layout, nullptr, &pack_layout_), "vkCreatePipelineLayout (camera pack)");
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = ycbcr_ ? sizeof(kCameraPackYcbcrCompSpirv) : sizeof(kCameraPackCompSpirv);
    module_info.pCode = ycbcr_ ? kCameraPackYcbcrCompSpirv : kCameraPackCompSpirv;
    VkShaderModule module = VK_NULL_HANDLE;
    checkVk(vkCreateShaderModule(device, &module_info, nullptr, &module), "vkCreateShaderModule (camera pack)");
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = &specialisation_;
    info.layout = pack_layout_;
    const VkResult result = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pack_pipeline_);
    vkDestroyShaderModule(device, module, nullptr);
    checkVk(result, "vkCreateComputePipelines (camera pack)");
}

void CameraInput::createDrawPipeline(VkRenderPass render_pass, VkSampleCountFlagBits samples) {
    const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(CameraPushConstants)};
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.setLayoutCount = 1;
    layout.pSetLayouts = &set_layout_;
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &push;
    checkVk(vkCreatePipelineLayout(gpu_.device, &layout, nullptr, &draw_layout_), "vkCreatePipelineLayout (camera)");
    GraphicsPipelineDescription draw;
    draw.layout = draw_layout_;
    draw.render_pass = render_pass;
    draw.vertex_spirv = kCameraVertSpirv;
    draw.vertex_spirv_bytes = sizeof(kCameraVertSpirv);
    draw.fragment_spirv = ycbcr_ ? kCameraYcbcrFragSpirv : kCameraFragSpirv;
    draw.fragment_spirv_bytes = ycbcr_ ? sizeof(kCameraYcbcrFragSpirv) : sizeof(kCameraFragSpirv);
    draw.fragment_specialization = &specialisation_;
    draw.depth_test = false;
    draw.depth_write = false;
    // Per-pixel shading at the pass's sample count: the full-screen draw covers every sample of every pixel and
    // writes the camera pixel's one value into all of them, so a resolve of untouched pixels gives it back.
    draw.samples = samples;
    draw_pipeline_ = createGraphicsPipeline(gpu_.device, draw);
}

// The zero-copy route's views carry their set, written with the layout: a frame in another layout is another
// entry, never a rewrite of a set a frame in flight may read.
bool CameraInput::holds(const CachedView& entry, const FrameInput& frame) const {
    return entry.view != VK_NULL_HANDLE && entry.image == frame.camera_image &&
           entry.format == frame.camera_image_format &&
           (!ycbcr_ || entry.layout == sampledLayoutFor(frame.camera_image_layout));
}

bool CameraInput::needsEviction(const FrameInput& frame) const {
    if (frame.camera_image == VK_NULL_HANDLE) return false;
    for (const CachedView& entry : views_)
        if (entry.view == VK_NULL_HANDLE || holds(entry, frame)) return false;
    return true;
}

size_t CameraInput::viewFor(const FrameInput& frame) {
    CachedView* free_entry = nullptr;
    CachedView* oldest = &views_[0];
    for (CachedView& entry : views_) {
        if (holds(entry, frame)) {
            entry.last_used = ++use_counter_;
            return size_t(&entry - views_.data());
        }
        if (entry.view == VK_NULL_HANDLE && free_entry == nullptr) free_entry = &entry;
        if (entry.last_used < oldest->last_used) oldest = &entry;
    }
    CachedView& entry = free_entry != nullptr ? *free_entry : *oldest;
    if (entry.view != VK_NULL_HANDLE) releaseView(entry);  // the caller waited (needsEviction)
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = frame.camera_image;
    info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    info.format = frame.camera_image_format;
    info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkSamplerYcbcrConversionInfo conversion{VK_STRUCTURE_TYPE_SAMPLER_YCBCR_CONVERSION_INFO};
    if (ycbcr_) {
        conversion.conversion = ycbcr_->conversion();  // a view of a Y'CbCr image names the sampler's conversion
        info.pNext = &conversion;
    }
    const VkResult result = vkCreateImageView(gpu_.device, &info, nullptr, &entry.view);
    if (result != VK_SUCCESS) {
        entry = {};
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           "frame: camera_image: vkCreateImageView failed (" + std::to_string(int(result)) + ")");
    }
    entry.image = frame.camera_image;
    entry.format = frame.camera_image_format;
    entry.layout = sampledLayoutFor(frame.camera_image_layout);
    entry.last_used = ++use_counter_;
    const size_t index = size_t(&entry - views_.data());
    if (ycbcr_) {
        // The sampler is the layout's immutable one; its field here is ignored.
        const VkDescriptorImageInfo image{VK_NULL_HANDLE, entry.view, entry.layout};
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = view_sets_[index];
        write.dstBinding = CAMERA_PLANE0_BINDING;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        write.pImageInfo = &image;
        vkUpdateDescriptorSets(gpu_.device, 1, &write, 0, nullptr);
    }
    return index;
}

void CameraInput::releaseView(CachedView& entry) {
    for (SlotSource& source : slot_sources_)
        if (source.plane0 == entry.view) source = {};  // the slot's set is pointed again before its next use
    // (A zero-copy slot's set is chosen again by its next prepare; the entry's set is rewritten with its next view.)
    vkDestroyImageView(gpu_.device, entry.view, nullptr);
    entry = {};
}

bool CameraInput::forget(VkImage image) {
    bool found = false;
    for (CachedView& entry : views_)
        if (entry.view != VK_NULL_HANDLE && entry.image == image) {
            releaseView(entry);
            found = true;
        }
    return found;
}

void CameraInput::pointSlotAt(uint32_t slot, VkImageView plane0, VkImageView plane1, VkImageLayout layout) {
    SlotSource& source = slot_sources_[slot];
    if (source.plane0 == plane0 && source.layout == layout) return;
    const VkDescriptorImageInfo images[2] = {{sampler_, plane0, layout}, {sampler_, plane1, layout}};
    VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    for (uint32_t index = 0; index < 2; ++index) {
        writes[index].dstSet = slot_sets_[slot];
        writes[index].dstBinding = index == 0 ? CAMERA_PLANE0_BINDING : CAMERA_PLANE1_BINDING;
        writes[index].descriptorCount = 1;
        writes[index].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[index].pImageInfo = &images[index];
    }
    vkUpdateDescriptorSets(gpu_.device, 2, writes, 0, nullptr);
    source.plane0 = plane0;
    source.layout = layout;
}

void CameraInput::prepare(uint32_t slot, const FrameInput& frame, const ColourStatisticsGrid* pack_grid) {
    pack_grid_ = pack_grid;
    if (frame.camera_image == VK_NULL_HANDLE) {
        stageHostPixels(slot, frame);
        pointSlotAt(slot, plane0_.view(), isYuv(format_) ? plane1_.view() : plane0_.view(),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        slot_sources_[slot].view_decodes_srgb = isYuv(format_) ? 0u : 1u;
        bound_sets_[slot] = slot_sets_[slot];
        return;
    }
    if (!acceptsImageFormat(format_, ycbcr_ != nullptr, frame.camera_image_format)) {
        const std::string given = "frame: camera_image_format: VkFormat " + std::to_string(int(frame.camera_image_format));
        if (ycbcr_)
            throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                               given + " given, but options.camera_ycbcr_image takes " + kYcbcrCameraFormatName +
                                   " (VkFormat " + std::to_string(int(kYcbcrCameraFormat)) + ")");
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           given + (isYuv(format_) ? " given, but a Y'CbCr camera comes as host planes (camera_luma, "
                                                     "camera_chroma), or as a G8_B8R8_2PLANE_420_UNORM image with "
                                                     "options.camera_ycbcr_image"
                                                   : " does not match options.camera_format (R8G8B8A8 or B8G8R8A8, "
                                                     "_UNORM or _SRGB)"));
    }
    const size_t index = viewFor(frame);
    const CachedView& entry = views_[index];
    slot_sources_[slot].view_decodes_srgb = isSrgbFormat(entry.format) ? 1u : 0u;
    if (ycbcr_) {
        bound_sets_[slot] = view_sets_[index];  // written when the view was made: nothing to write per frame
        return;
    }
    pointSlotAt(slot, entry.view, entry.view, sampledLayoutFor(frame.camera_image_layout));
    bound_sets_[slot] = slot_sets_[slot];
}

void CameraInput::stageHostPixels(uint32_t slot, const FrameInput& frame) {
    GpuBuffer& staging = staging_[slot];
    auto copyPlane = [&](const uint8_t* rows, uint32_t row_bytes, uint32_t packed_row_bytes, uint32_t row_count,
                         size_t offset) {
        const uint32_t stride = row_bytes == 0 ? packed_row_bytes : row_bytes;
        if (stride == packed_row_bytes) {
            staging.upload(rows, size_t(packed_row_bytes) * row_count, offset);
            return;
        }
        for (uint32_t row = 0; row < row_count; ++row)
            staging.upload(rows + size_t(row) * stride, packed_row_bytes, offset + size_t(row) * packed_row_bytes);
    };
    if (!isYuv(format_)) {
        copyPlane(frame.camera_rgba8, frame.camera_row_bytes, width_ * 4, height_, 0);
        return;
    }
    copyPlane(frame.camera_luma, frame.camera_luma_row_bytes, width_, height_, 0);
    copyPlane(frame.camera_chroma, frame.camera_chroma_row_bytes, (width_ / 2) * 2, height_ / 2,
              size_t(width_) * height_);
}

void CameraInput::recordUpload(VkCommandBuffer cmd, uint32_t slot) const {
    // The earlier frames' reads of the planes finish before this copy replaces them (their content is discarded).
    for (const GpuImage* image : {&plane0_, &plane1_})
        if (image->handle() != VK_NULL_HANDLE)
            recordImageLayoutTransition(cmd, image->handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                                        kCameraReaders, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyBufferToImage(cmd, staging_[slot].handle(), plane0_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    if (isYuv(format_)) {
        region.bufferOffset = VkDeviceSize(width_) * height_;
        region.imageExtent = {width_ / 2, height_ / 2, 1};
        vkCmdCopyBufferToImage(cmd, staging_[slot].handle(), plane1_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
    }
    for (const GpuImage* image : {&plane0_, &plane1_})
        if (image->handle() != VK_NULL_HANDLE)
            recordImageLayoutTransition(cmd, image->handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                        VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                                        VK_PIPELINE_STAGE_TRANSFER_BIT, kCameraReaders);
}

void CameraInput::recordPack(VkCommandBuffer cmd, uint32_t slot, const ColourStatisticsGrid& grid) const {
    // The earlier frames' statistics read the packed words before this kernel rewrites them.
    VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                         &before, 0, nullptr, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pack_pipeline_);
    const VkDescriptorSet sets[2] = {bound_sets_[slot], packed_set_};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pack_layout_, 0, 2, sets, 0, nullptr);
    // Only the grid's pixels: the ground statistics at 640 x 360 read 1 pixel in 49, and packing every pixel
    // cost ~2.8 ms on lavapipe (camera sampling is the dear part).
    const CameraPushConstants push{width_, slot_sources_[slot].view_decodes_srgb, grid.stride, grid.offset,
                                   grid.samples_x, grid.samples_y};
    vkCmdPushConstants(cmd, pack_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (grid.samples_x + CAMERA_PACK_WORKGROUP - 1) / CAMERA_PACK_WORKGROUP,
                  (grid.samples_y + CAMERA_PACK_WORKGROUP - 1) / CAMERA_PACK_WORKGROUP, 1);
    // The statistics kernels' own barrier (recordBeforeStatistics) makes these writes visible to them.
}

void CameraInput::recordBeforePasses(VkCommandBuffer cmd, uint32_t slot, const FrameInput& frame,
                                     const ColourStatisticsGrid* pack_grid) {
    if (frame.camera_image == VK_NULL_HANDLE) {
        recordUpload(cmd, slot);
    } else if (frame.camera_image_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
        // The app's earlier writes (ordered by its semaphore or by submission order) before the move.
        recordImageLayoutTransition(cmd, frame.camera_image, VK_IMAGE_ASPECT_COLOR_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                    VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, kCameraReaders);
    }
    if (pack_grid != nullptr && pack_pipeline_ != VK_NULL_HANDLE) recordPack(cmd, slot, *pack_grid);
}

void CameraInput::recordDraw(VkCommandBuffer cmd, uint32_t slot) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, draw_pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, draw_layout_, 0, 1, &bound_sets_[slot], 0, nullptr);
    const CameraPushConstants push{width_, slot_sources_[slot].view_decodes_srgb, 0, 0, 0, 0};
    vkCmdPushConstants(cmd, draw_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
}

void CameraInput::recordAfterPasses(VkCommandBuffer cmd, const FrameInput& frame) const {
    if (frame.camera_image == VK_NULL_HANDLE || frame.camera_image_layout != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)
        return;
    recordImageLayoutTransition(cmd, frame.camera_image, VK_IMAGE_ASPECT_COLOR_BIT,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_MEMORY_READ_BIT, kCameraReaders,
                                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
}

uint64_t CameraInput::memoryBytes() const {
    uint64_t bytes = plane0_.memoryBytes() + plane1_.memoryBytes() + packed_buffer_.size();
    for (const GpuBuffer& buffer : staging_) bytes += buffer.size();
    return bytes;
}

void CameraInput::destroy() noexcept {
    const VkDevice device = gpu_.device;
    for (CachedView& entry : views_)
        if (entry.view != VK_NULL_HANDLE) vkDestroyImageView(device, entry.view, nullptr);
    views_ = {};
    for (VkPipeline pipeline : {draw_pipeline_, pack_pipeline_})
        if (pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline, nullptr);
    for (VkPipelineLayout layout : {draw_layout_, pack_layout_})
        if (layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, layout, nullptr);
    if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, pool_, nullptr);
    for (VkDescriptorSetLayout layout : {set_layout_, packed_set_layout_})
        if (layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, layout, nullptr);
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device, sampler_, nullptr);
    ycbcr_.reset();  // after the set layout that holds its sampler
    view_sets_ = {};
    draw_pipeline_ = pack_pipeline_ = VK_NULL_HANDLE;
    draw_layout_ = pack_layout_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    set_layout_ = packed_set_layout_ = VK_NULL_HANDLE;
    sampler_ = VK_NULL_HANDLE;
}

}  // namespace gusuku::runtime_detail

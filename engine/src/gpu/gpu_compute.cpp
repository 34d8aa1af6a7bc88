// Buffers and compute pipelines over storage and uniform texel buffers (see gpu_compute.h for the contract).

#include "gusuku/gpu/gpu_compute.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace gusuku {
namespace {

// Bytes per texel of the formats a texel-buffer binding may use (32-bit channels: what a shader reads exactly).
size_t textureFormatBytes(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UINT:
    case VK_FORMAT_R8G8B8A8_UNORM: return 4;
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw std::invalid_argument("ComputePipeline: texel buffer format " + std::to_string(int(format)) +
                                         " is not one of the supported 32-bit-channel formats");
    }
}

std::string mebibytes(VkDeviceSize bytes) {
    return std::to_string(static_cast<double>(bytes) / (1024.0 * 1024.0)) + " MiB (" + std::to_string(bytes) + " bytes)";
}

void checkRange(size_t offset, size_t byte_count, size_t buffer_bytes, const char* what) {
    if (offset > buffer_bytes || byte_count > buffer_bytes - offset)
        throw std::out_of_range(std::string("GpuBuffer::") + what + ": bytes [" + std::to_string(offset) + ", " +
                                std::to_string(offset + byte_count) + ") lie outside the buffer's " +
                                std::to_string(buffer_bytes) + " bytes");
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// GpuBuffer

GpuBuffer::GpuBuffer(const GpuDevice& gpu, size_t byte_count, VkBufferUsageFlags usage, GpuMemory memory)
    : gpu_(&gpu), memory_kind_(memory) {
    // Rounded to 4 so shaders may read whole uint words; never 0 so the buffer can always be bound.
    byte_count_ = byte_count == 0 ? 4 : (byte_count + 3) / 4 * 4;
    const VkPhysicalDeviceLimits& limits = gpu.limits();
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && byte_count_ > limits.maxStorageBufferRange)
        throw std::runtime_error("GpuBuffer: a storage buffer of " + mebibytes(byte_count_) +
                                " exceeds this device's maxStorageBufferRange of " +
                                mebibytes(limits.maxStorageBufferRange) + " (" + gpu.properties.deviceName +
                                "); split the data over several buffers or dispatches");

    VkDevice device = gpu.device;
    VkBufferCreateInfo buffer_info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    buffer_info.size = byte_count_;
    // Transfer usage costs nothing and lets callers copy or fill buffers with vkCmdCopyBuffer/vkCmdFillBuffer.
    buffer_info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    try {
        checkVk(vkCreateBuffer(device, &buffer_info, nullptr, &buffer_), "vkCreateBuffer");
        VkMemoryRequirements requirements;
        vkGetBufferMemoryRequirements(device, buffer_, &requirements);
        VkMemoryAllocateInfo allocate_info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        allocate_info.allocationSize = requirements.size;
        const VkMemoryPropertyFlags mappable = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        if (memory == GpuMemory::kHostVisible) {
            allocate_info.memoryTypeIndex = gpu.findMemoryType(requirements.memoryTypeBits, mappable);
        } else {
            allocate_info.memoryTypeIndex = gpu.findMemoryType(requirements.memoryTypeBits,
                                                               VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        }
        const VkResult allocated = vkAllocateMemory(device, &allocate_info, nullptr, &memory_);
        if (allocated == VK_ERROR_OUT_OF_HOST_MEMORY || allocated == VK_ERROR_OUT_OF_DEVICE_MEMORY)
            throw std::runtime_error("GpuBuffer: out of memory allocating " + mebibytes(requirements.size));
        checkVk(allocated, "vkAllocateMemory");
        checkVk(vkBindBufferMemory(device, buffer_, memory_, 0), "vkBindBufferMemory");
        // Host-visible buffers are mapped once for the buffer's life: host-coherent, so no flushes or
        // invalidates are needed. Device-local ones are never mapped, even where the type happens to allow it
        // (lavapipe), so the staging path is the one exercised on every device.
        if (memory == GpuMemory::kHostVisible)
            checkVk(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    } catch (...) {
        release();
        throw;
    }
}

GpuBuffer::~GpuBuffer() { release(); }

GpuBuffer::GpuBuffer(GpuBuffer&& other) noexcept
    : gpu_(std::exchange(other.gpu_, nullptr)),
      memory_kind_(other.memory_kind_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      byte_count_(std::exchange(other.byte_count_, 0)) {}

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& other) noexcept {
    if (this != &other) {
        release();
        gpu_ = std::exchange(other.gpu_, nullptr);
        memory_kind_ = other.memory_kind_;
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        mapped_ = std::exchange(other.mapped_, nullptr);
        byte_count_ = std::exchange(other.byte_count_, 0);
    }
    return *this;
}

void GpuBuffer::release() {
    if (gpu_ != nullptr) {
        VkDevice device = gpu_->device;
        if (mapped_ != nullptr) vkUnmapMemory(device, memory_);
        if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer_, nullptr);
        if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device, memory_, nullptr);
    }
    mapped_ = nullptr;
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    byte_count_ = 0;
}

void GpuBuffer::upload(const void* bytes, size_t byte_count, size_t offset) {
    checkRange(offset, byte_count, byte_count_, "upload");
    if (byte_count == 0) return;
    if (mapped_ != nullptr)
        std::memcpy(static_cast<char*>(mapped_) + offset, bytes, byte_count);
    else
        copyThroughStaging(const_cast<void*>(bytes), byte_count, offset, /*to_device=*/true);
}

void GpuBuffer::download(void* bytes, size_t byte_count, size_t offset) const {
    checkRange(offset, byte_count, byte_count_, "download");
    if (byte_count == 0) return;
    if (mapped_ != nullptr)
        std::memcpy(bytes, static_cast<const char*>(mapped_) + offset, byte_count);
    else
        copyThroughStaging(bytes, byte_count, offset, /*to_device=*/false);
}

void GpuBuffer::copyThroughStaging(void* host_bytes, size_t byte_count, size_t offset, bool to_device) const {
    GpuBuffer staging(*gpu_, byte_count, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuMemory::kHostVisible);
    if (to_device) std::memcpy(staging.mapped_, host_bytes, byte_count);
    GpuSubmitter submitter(*gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{to_device ? 0 : offset, to_device ? offset : 0, byte_count};
        vkCmdCopyBuffer(cmd, to_device ? staging.buffer_ : buffer_, to_device ? buffer_ : staging.buffer_, 1, &region);
        // Transfer writes made visible to the shaders that read the buffer next, or to the host read below.
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = to_device ? VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                                VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT
                                          : VK_ACCESS_HOST_READ_BIT;
        const VkPipelineStageFlags destination_stages =
            to_device ? VK_PIPELINE_STAGE_ALL_COMMANDS_BIT : VK_PIPELINE_STAGE_HOST_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, destination_stages, 0, 1, &barrier, 0, nullptr, 0,
                             nullptr);
    });
    if (!to_device) std::memcpy(host_bytes, staging.mapped_, byte_count);
}

// ---------------------------------------------------------------------------------------------------------------
// ComputePipeline

ComputePipeline::ComputePipeline(const GpuDevice& gpu, const uint32_t* spirv, size_t spirv_bytes,
                                 uint32_t buffer_count, uint32_t push_constant_bytes,
                                 const std::vector<TexelBufferBinding>& texel_buffers,
                                 const std::vector<uint32_t>& specialization)
    : gpu_(gpu), storage_buffer_count_(buffer_count), push_constant_bytes_(push_constant_bytes),
      binding_formats_(buffer_count, VK_FORMAT_UNDEFINED), bound_views_(buffer_count) {
    for (const TexelBufferBinding& texel : texel_buffers) {
        if (texel.binding >= buffer_count || texel.format == VK_FORMAT_UNDEFINED)
            throw std::invalid_argument("ComputePipeline: texel buffer binding " + std::to_string(texel.binding) +
                                        " is not one of the " + std::to_string(buffer_count) +
                                        " bindings or has no format");
        textureFormatBytes(texel.format);  // throws for a format bindBuffers could not size
        binding_formats_[texel.binding] = texel.format;
    }
    const uint32_t texel_buffer_count = uint32_t(
        std::count_if(binding_formats_.begin(), binding_formats_.end(), [](VkFormat f) { return f != VK_FORMAT_UNDEFINED; }));
    const uint32_t storage_buffer_count = buffer_count - texel_buffer_count;
    if (spirv == nullptr || spirv_bytes == 0 || spirv_bytes % 4 != 0)
        throw std::invalid_argument("ComputePipeline: SPIR-V must be a non-empty array of 32-bit words");
    const uint32_t push_constant_limit = std::min<uint32_t>(128, gpu.limits().maxPushConstantsSize);
    if (push_constant_bytes % 4 != 0 || push_constant_bytes > push_constant_limit)
        throw std::invalid_argument("ComputePipeline: push constants must be a multiple of 4 bytes and at most " +
                                    std::to_string(push_constant_limit) + "; got " +
                                    std::to_string(push_constant_bytes));
    if (storage_buffer_count > gpu.limits().maxPerStageDescriptorStorageBuffers)
        throw std::invalid_argument("ComputePipeline: " + std::to_string(storage_buffer_count) +
                                    " storage buffers exceed the device's per-stage limit of " +
                                    std::to_string(gpu.limits().maxPerStageDescriptorStorageBuffers));
    if (texel_buffer_count > gpu.limits().maxPerStageDescriptorSampledImages)
        throw std::invalid_argument("ComputePipeline: " + std::to_string(texel_buffer_count) +
                                    " texel buffers exceed the device's per-stage limit of " +
                                    std::to_string(gpu.limits().maxPerStageDescriptorSampledImages));

    VkDevice device = gpu.device;
    try {
        VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        module_info.codeSize = spirv_bytes;
        module_info.pCode = spirv;
        checkVk(vkCreateShaderModule(device, &module_info, nullptr, &module_), "vkCreateShaderModule");

        std::vector<VkDescriptorSetLayoutBinding> bindings(buffer_count);
        for (uint32_t binding = 0; binding < buffer_count; ++binding) {
            bindings[binding].binding = binding;
            bindings[binding].descriptorType = descriptorType(binding);
            bindings[binding].descriptorCount = 1;
            bindings[binding].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        }
        VkDescriptorSetLayoutCreateInfo set_layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_layout_info.bindingCount = buffer_count;
        set_layout_info.pBindings = bindings.data();
        checkVk(vkCreateDescriptorSetLayout(device, &set_layout_info, nullptr, &set_layout_),
                "vkCreateDescriptorSetLayout");

        VkPushConstantRange push_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
        VkPipelineLayoutCreateInfo pipeline_layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        pipeline_layout_info.setLayoutCount = 1;
        pipeline_layout_info.pSetLayouts = &set_layout_;
        pipeline_layout_info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
        pipeline_layout_info.pPushConstantRanges = &push_range;
        checkVk(vkCreatePipelineLayout(device, &pipeline_layout_info, nullptr, &pipeline_layout_),
                "vkCreatePipelineLayout");

        VkComputePipelineCreateInfo pipeline_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        pipeline_info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        pipeline_info.stage.module = module_;
        pipeline_info.stage.pName = "main";
        std::vector<VkSpecializationMapEntry> entries;
        for (uint32_t id = 0; id < specialization.size(); ++id)
            entries.push_back({id, uint32_t(id * sizeof(uint32_t)), sizeof(uint32_t)});
        const VkSpecializationInfo specialization_info{uint32_t(entries.size()), entries.data(),
                                                       specialization.size() * sizeof(uint32_t), specialization.data()};
        if (!specialization.empty()) pipeline_info.stage.pSpecializationInfo = &specialization_info;
        pipeline_info.layout = pipeline_layout_;
        checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline_),
                "vkCreateComputePipelines");

        // A pool of exactly one set; with no buffers the (empty) set layout still needs no pool.
        if (buffer_count > 0) {
            std::vector<VkDescriptorPoolSize> pool_sizes;
            if (storage_buffer_count > 0) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_buffer_count});
            if (texel_buffer_count > 0)
                pool_sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, texel_buffer_count});
            VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
            pool_info.maxSets = 1;
            pool_info.poolSizeCount = uint32_t(pool_sizes.size());
            pool_info.pPoolSizes = pool_sizes.data();
            checkVk(vkCreateDescriptorPool(device, &pool_info, nullptr, &descriptor_pool_), "vkCreateDescriptorPool");
            VkDescriptorSetAllocateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
            set_info.descriptorPool = descriptor_pool_;
            set_info.descriptorSetCount = 1;
            set_info.pSetLayouts = &set_layout_;
            checkVk(vkAllocateDescriptorSets(device, &set_info, &descriptor_set_), "vkAllocateDescriptorSets");
        }
    } catch (...) {
        destroy();
        throw;
    }
}

ComputePipeline::~ComputePipeline() { destroy(); }

void ComputePipeline::destroy() noexcept {
    VkDevice device = gpu_.device;
    // The descriptor set goes with its pool.
    if (descriptor_pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, descriptor_pool_, nullptr);
    if (pipeline_ != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline_, nullptr);
    if (pipeline_layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, pipeline_layout_, nullptr);
    if (set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
    if (module_ != VK_NULL_HANDLE) vkDestroyShaderModule(device, module_, nullptr);
    for (BoundView& bound : bound_views_) {
        if (bound.view != VK_NULL_HANDLE) vkDestroyBufferView(device, bound.view, nullptr);
        bound = {};
    }
    for (VkBufferView view : retired_views_) vkDestroyBufferView(device, view, nullptr);
    retired_views_.clear();
    descriptor_pool_ = VK_NULL_HANDLE;
    descriptor_set_ = VK_NULL_HANDLE;
    pipeline_ = VK_NULL_HANDLE;
    pipeline_layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
    module_ = VK_NULL_HANDLE;
}

void ComputePipeline::bindBuffers(const std::vector<const GpuBuffer*>& buffers) {
    if (buffers.size() != storage_buffer_count_)
        throw std::invalid_argument("ComputePipeline::bindBuffers: " + std::to_string(buffers.size()) +
                                    " buffers given for " + std::to_string(storage_buffer_count_) + " bindings");
    std::vector<VkDescriptorBufferInfo> buffer_infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes(buffers.size());
    for (size_t binding = 0; binding < buffers.size(); ++binding) {
        if (buffers[binding] == nullptr || buffers[binding]->handle() == VK_NULL_HANDLE)
            throw std::invalid_argument("ComputePipeline::bindBuffers: binding " + std::to_string(binding) +
                                        " has no buffer");
        writes[binding] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[binding].dstSet = descriptor_set_;
        writes[binding].dstBinding = static_cast<uint32_t>(binding);
        writes[binding].descriptorCount = 1;
        writes[binding].descriptorType = descriptorType(uint32_t(binding));
        if (binding_formats_[binding] == VK_FORMAT_UNDEFINED) {
            buffer_infos[binding] = {buffers[binding]->handle(), 0, VK_WHOLE_SIZE};
            writes[binding].pBufferInfo = &buffer_infos[binding];
        } else {
            writes[binding].pTexelBufferView = &texelView(uint32_t(binding), *buffers[binding]);
        }
    }
    if (!writes.empty())
        vkUpdateDescriptorSets(gpu_.device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

VkDescriptorType ComputePipeline::descriptorType(uint32_t binding) const {
    return binding_formats_[binding] == VK_FORMAT_UNDEFINED ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                            : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
}

const VkBufferView& ComputePipeline::texelView(uint32_t binding, const GpuBuffer& buffer) {
    BoundView& bound = bound_views_[binding];
    if (bound.view != VK_NULL_HANDLE && bound.buffer == buffer.handle()) return bound.view;
    const VkFormat format = binding_formats_[binding];
    const size_t texel_bytes = textureFormatBytes(format);
    // A view covers whole texels only; the buffer's last partial texel (if any) is never read.
    const uint64_t texel_count = std::max<uint64_t>(1, buffer.size() / texel_bytes);
    if (texel_count > gpu_.limits().maxTexelBufferElements)
        throw std::runtime_error("ComputePipeline: a texel buffer of " + std::to_string(texel_count) +
                                 " texels exceeds this device's maxTexelBufferElements of " +
                                 std::to_string(gpu_.limits().maxTexelBufferElements) + " (" +
                                 gpu_.properties.deviceName + ")");
    VkBufferViewCreateInfo view_info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    view_info.buffer = buffer.handle();
    view_info.format = format;
    view_info.offset = 0;
    view_info.range = texel_count * texel_bytes;
    VkBufferView view = VK_NULL_HANDLE;
    checkVk(vkCreateBufferView(gpu_.device, &view_info, nullptr, &view), "vkCreateBufferView");
    if (bound.view != VK_NULL_HANDLE) retired_views_.push_back(bound.view);
    bound = {buffer.handle(), view};
    return bound.view;
}

void ComputePipeline::recordDispatch(VkCommandBuffer cmd, const void* push_constants, uint32_t groups_x,
                                     uint32_t groups_y, uint32_t groups_z) const {
    if (push_constant_bytes_ > 0 && push_constants == nullptr)
        throw std::invalid_argument("ComputePipeline::recordDispatch: the pipeline has " +
                                    std::to_string(push_constant_bytes_) + " bytes of push constants but none given");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    if (descriptor_set_ != VK_NULL_HANDLE)
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, 1, &descriptor_set_, 0,
                                nullptr);
    if (push_constant_bytes_ > 0)
        vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes_, push_constants);
    vkCmdDispatch(cmd, groups_x, groups_y, groups_z);
}

void ComputePipeline::dispatchAndWait(const void* push_constants, uint32_t groups_x, uint32_t groups_y,
                                      uint32_t groups_z) {
    if (!submitter_) submitter_ = std::make_unique<GpuSubmitter>(gpu_);
    submitter_->submitAndWait([&](VkCommandBuffer cmd) {
        recordDispatch(cmd, push_constants, groups_x, groups_y, groups_z);
        // Makes the shader's writes visible to the host reads that follow the fence.
        recordComputeBarrier(cmd);
    });
}

void recordComputeBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    // Read-after-write and write-after-write for the next dispatch, and host reads after the fence.
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr,
                         0, nullptr);
}

}  // namespace gusuku

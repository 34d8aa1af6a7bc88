#pragma once
// Minimal compute helpers on a GpuDevice (the app's device or a VulkanContext's, gpu_device.h): buffers and
// compute pipelines whose descriptor set 0 holds buffers at bindings 0..N-1 (storage buffers, or uniform texel
// buffers where the pipeline says so) plus one push-constant block. That is all the baker needs: textures, sky
// maps and the BVH travel as buffers (lavapipe lacks descriptor indexing, docs/design.md 5). A VulkanContext converts to `const GpuDevice&`, so it can be passed as is.
//
// Lifetime: the GpuDevice object passed in (not only its handles) must outlive the buffers and pipelines made
// on it; they keep a pointer to it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

namespace gusuku {

/// Where a buffer's bytes live.
enum class GpuMemory {
    /// Host-visible, host-coherent, mapped for the buffer's life: upload and download are plain memcpy. Right
    /// for the baker, whose buffers are read back every pass (on lavapipe all memory is host memory anyway).
    kHostVisible,
    /// Device-local (host-visible too only if the device's device-local types all are): for data the GPU reads
    /// every frame and the host writes once, such as the runtime's lightmaps and meshes on a phone's GPU.
    /// upload and download go through a temporary staging buffer and one submission each (setup only).
    kDeviceLocal,
};

/// A buffer (storage by default) in the memory chosen by GpuMemory.
class GpuBuffer {
public:
    GpuBuffer() = default;
    /// byte_count is rounded up to 4; a zero-sized request allocates 4 bytes so bindings stay valid.
    /// Throws std::runtime_error when a storage buffer would exceed the device's maxStorageBufferRange
    /// (128 MiB on lavapipe) or memory runs out. Transfer src/dst usage is always added.
    GpuBuffer(const GpuDevice& gpu, size_t byte_count, VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
              GpuMemory memory = GpuMemory::kHostVisible);
    ~GpuBuffer();
    GpuBuffer(GpuBuffer&& other) noexcept;
    GpuBuffer& operator=(GpuBuffer&& other) noexcept;
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    /// Host-visible: plain memcpy into/out of the persistently mapped memory. Device-local: a copy through a
    /// temporary staging buffer, submitted and waited for (allocates; for setup, not per frame). Either way no
    /// GPU work may be using the bytes meanwhile. Throws std::out_of_range when [offset, offset + byte_count)
    /// is not inside the buffer.
    void upload(const void* bytes, size_t byte_count, size_t offset = 0);
    void download(void* bytes, size_t byte_count, size_t offset = 0) const;
    template <typename T> void uploadVector(const std::vector<T>& values) {
        upload(values.data(), values.size() * sizeof(T));
    }
    template <typename T> std::vector<T> downloadVector(size_t count) const {
        std::vector<T> values(count);
        download(values.data(), count * sizeof(T));
        return values;
    }

    VkBuffer handle() const { return buffer_; }
    size_t size() const { return byte_count_; }
    GpuMemory memory() const { return memory_kind_; }
    /// True when upload/download are plain memcpy (the bytes are mapped).
    bool isMapped() const { return mapped_ != nullptr; }

private:
    void release();
    void copyThroughStaging(void* host_bytes, size_t byte_count, size_t offset, bool to_device) const;
    const GpuDevice* gpu_ = nullptr;
    GpuMemory memory_kind_ = GpuMemory::kHostVisible;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    void* mapped_ = nullptr;
    size_t byte_count_ = 0;
};

/// A binding of set 0 that the shader reads as a uniform texel buffer (GLSL usamplerBuffer / samplerBuffer
/// with texelFetch) through a view of the whole buffer in `format`, rather than as a storage buffer. Why: on
/// lavapipe a storage-buffer load at a per-lane address runs as a loop over the SIMD lanes, one scalar load
/// each, while a texel fetch gathers all lanes in straight-line vector code. The buffer must have been made
/// with VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT.
struct TexelBufferBinding {
    uint32_t binding;
    VkFormat format;
};

/// A compute pipeline from embedded SPIR-V with `buffer_count` buffers at set 0, bindings 0..count-1 (storage
/// buffers, except those listed in texel_buffers), and a push-constant block of push_constant_bytes (<= 128).
/// specialization: 32-bit values of the shader's constant_id 0, 1, ... (a bool's is 0 or 1); empty: the shader's
/// defaults.
class ComputePipeline {
public:
    ComputePipeline(const GpuDevice& gpu, const uint32_t* spirv, size_t spirv_bytes, uint32_t buffer_count,
                    uint32_t push_constant_bytes, const std::vector<TexelBufferBinding>& texel_buffers = {},
                    const std::vector<uint32_t>& specialization = {});
    ~ComputePipeline();
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    /// Points the descriptor set at these buffers (size must equal buffer_count). There is one set per
    /// pipeline: rebinding while a recorded command buffer that uses it is still to be submitted changes what
    /// that command buffer reads, so record one dispatch per binding (dispatchAndWait) or use several pipelines.
    /// A texel-buffer binding gets a view of the whole buffer (kept until the pipeline is destroyed, reused
    /// while the same buffer is bound); throws std::runtime_error when the buffer holds more texels than the
    /// device's maxTexelBufferElements (128 Mi on lavapipe).
    void bindBuffers(const std::vector<const GpuBuffer*>& buffers);

    /// Records bind + push constants + dispatch into cmd (no barrier: add recordComputeBarrier between dependent
    /// dispatches). push_constants must point at push_constant_bytes bytes when that is non-zero.
    void recordDispatch(VkCommandBuffer cmd, const void* push_constants, uint32_t groups_x, uint32_t groups_y = 1,
                        uint32_t groups_z = 1) const;

    /// Records, submits and waits: one synchronous dispatch, followed by a barrier that makes its writes
    /// visible to the host. Uses a GpuSubmitter of the pipeline's own, made on first use.
    void dispatchAndWait(const void* push_constants, uint32_t groups_x, uint32_t groups_y = 1,
                         uint32_t groups_z = 1);

private:
    void destroy() noexcept;
    VkDescriptorType descriptorType(uint32_t binding) const;
    const VkBufferView& texelView(uint32_t binding, const GpuBuffer& buffer);
    const GpuDevice& gpu_;
    std::unique_ptr<GpuSubmitter> submitter_;  // for dispatchAndWait
    uint32_t storage_buffer_count_;  // all bindings, texel buffers included
    uint32_t push_constant_bytes_;
    std::vector<VkFormat> binding_formats_;  // per binding: VK_FORMAT_UNDEFINED for a storage buffer
    struct BoundView {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkBufferView view = VK_NULL_HANDLE;
    };
    std::vector<BoundView> bound_views_;         // per binding, the view now in the set
    std::vector<VkBufferView> retired_views_;    // views replaced by a rebind: a pending dispatch may use them
    VkShaderModule module_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet descriptor_set_ = VK_NULL_HANDLE;
};

/// Inserts a compute-to-compute (and compute-to-host) memory barrier: shader writes before it are visible to
/// shader reads and writes after it and to host reads after the submission's fence.
void recordComputeBarrier(VkCommandBuffer cmd);

}  // namespace gusuku

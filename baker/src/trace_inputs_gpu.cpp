// The trace kernels' shared inputs on the device (trace_inputs_gpu.h).

#include "gusuku_bake/trace_inputs_gpu.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include "bake_irradiance_interface.h"
#include "camera_trace_interface.h"
#include "gusuku_bake/alpha_mask_footprint.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/trace_input_kind.h"

namespace gusuku::bake {

// Both kernels number the shared inputs alike; traceInputBuffers relies on it.
static_assert(BAKE_BVH_NODE_BINDING == 0 && CAMERA_BVH_NODE_BINDING == 0);
static_assert(BAKE_BVH_TRIANGLE_BINDING == 1 && CAMERA_BVH_TRIANGLE_BINDING == 1);
static_assert(BAKE_SHADING_TRIANGLE_BINDING == 2 && CAMERA_SHADING_TRIANGLE_BINDING == 2);
static_assert(BAKE_MATERIAL_BINDING == 3 && CAMERA_MATERIAL_BINDING == 3);
static_assert(BAKE_TEXTURE_BINDING == 4 && CAMERA_TEXTURE_BINDING == 4);
static_assert(BAKE_SKY_RADIANCE_BINDING == 5 && CAMERA_SKY_RADIANCE_BINDING == 5);
static_assert(BAKE_SKY_TABLE_BINDING == 6 && CAMERA_SKY_TABLE_BINDING == 6);

namespace {
// Either kind of kernel can bind the inputs (trace_input_kind.h).
constexpr VkBufferUsageFlags kTraceInputUsage =
    VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
}  // namespace

TraceInputKind traceInputKind(const GpuDevice& gpu) {
    const uint64_t largest_texels = uint64_t(gpu.limits().maxStorageBufferRange) / 4;
    return gpu.limits().maxTexelBufferElements >= largest_texels ? TraceInputKind::TexelBuffers
                                                                   : TraceInputKind::StorageBuffers;
}

const char* traceInputKindName(TraceInputKind kind) {
    return kind == TraceInputKind::TexelBuffers ? "texel buffers" : "storage buffers";
}

std::vector<TexelBufferBinding> traceInputTexelBindings(TraceInputKind kind) {
    if (kind == TraceInputKind::StorageBuffers) return {};
    return traceInputTexelBindings();
}

void checkTraceDeviceLimits(const GpuDevice& gpu) {
    static_assert(BAKE_IRRADIANCE_BINDING_COUNT == 10 && CAMERA_TRACE_BINDING_COUNT == 10);
    const VkPhysicalDeviceLimits& limits = gpu.limits();
    const TraceInputKind kind = traceInputKind(gpu);
    const std::string why = kind == TraceInputKind::StorageBuffers
                                ? std::string(" (storage buffers, as maxTexelBufferElements of ") +
                                      std::to_string(limits.maxTexelBufferElements) +
                                      " is below what a bake may upload)"
                                : " (texel buffers)";
    auto need = [&](const char* limit, uint64_t have, uint64_t needed, const std::string& use) {
        if (have >= needed) return;
        throw std::runtime_error(std::string("the trace kernels need ") + limit + " >= " + std::to_string(needed) +
                                 ", " + use + why + "; this device's (" + gpu.properties.deviceName + ") is " +
                                 std::to_string(have) + ": bake on a device that has it (lavapipe, SwiftShader or a "
                                 "desktop GPU)");
    };
    constexpr uint32_t kInputs = 7;  // the scene's five buffers and the sky's two
    const uint32_t storage = kind == TraceInputKind::StorageBuffers ? BAKE_IRRADIANCE_BINDING_COUNT
                                                                     : BAKE_IRRADIANCE_BINDING_COUNT - kInputs;
    need("maxPerStageDescriptorStorageBuffers", limits.maxPerStageDescriptorStorageBuffers, storage,
         "their storage buffers");
    need("maxDescriptorSetStorageBuffers", limits.maxDescriptorSetStorageBuffers, storage, "their storage buffers");
    if (kind == TraceInputKind::TexelBuffers) {
        need("maxPerStageDescriptorSampledImages", limits.maxPerStageDescriptorSampledImages, kInputs,
             "their texel buffers");
        need("maxDescriptorSetSampledImages", limits.maxDescriptorSetSampledImages, kInputs, "their texel buffers");
    }
    need("maxComputeWorkGroupSize[0]", limits.maxComputeWorkGroupSize[0], BAKE_WORKGROUP_SIZE, "their workgroup");
    need("maxComputeWorkGroupInvocations", limits.maxComputeWorkGroupInvocations, BAKE_WORKGROUP_SIZE,
         "their workgroup");
    need("maxPushConstantsSize", limits.maxPushConstantsSize,
         std::max(sizeof(shader_interface::BakeIrradiancePushConstants),
                  sizeof(shader_interface::CameraTracePushConstants)),
         "their push constants");
}

TraceSceneGpu uploadTraceScene(const GpuDevice& gpu, const TraceScene& scene, int max_texture_size) {
    std::shared_ptr<const Bvh> built = scene.bvh;
    if (!built) built = std::make_shared<const Bvh>(buildBvh(scene.mesh, scene.triangle_flags));
    const Bvh& bvh = *built;
    const PackedSceneShading shading = packSceneShading(scene.mesh, max_texture_size);
    // Only triangles whose footprint holds a texel below the cutoff run the alpha test: the flags the BVH's leaf
    // records carry are narrowed here, where the texture as uploaded is known (the tree's shape does not depend
    // on the flags, so the records are patched rather than the tree rebuilt).
    const std::vector<uint32_t> flags = narrowAlphaMaskFlags(shading, scene.triangle_flags);
    std::vector<BvhTriangleGpu> leaf_triangles = bvh.triangles;
    for (BvhTriangleGpu& leaf : leaf_triangles)
        if (leaf.triangle_index < flags.size()) leaf.flags = flags[leaf.triangle_index];
    constexpr VkBufferUsageFlags kTexel = kTraceInputUsage;
    TraceSceneGpu uploaded;
    uploaded.bvh_nodes = uploadedBuffer(gpu, bvh.nodes, kTexel);
    uploaded.bvh_triangles = uploadedBuffer(gpu, leaf_triangles, kTexel);
    uploaded.shading_triangles = uploadedBuffer(gpu, shading.triangles, kTexel);
    uploaded.materials = uploadedBuffer(gpu, shading.materials, kTexel);
    uploaded.texture_words = uploadedBuffer(gpu, shading.texture_words, kTexel);
    uploaded.triangle_count = scene.mesh.triangleCount();
    uploaded.dropped_triangle_count = bvh.dropped_triangle_count;
    for (uint32_t triangle_flags : flags) {
        const bool tested = (triangle_flags & kTriangleFlagAlphaMasked) != 0;
        uploaded.has_alpha_masks |= tested;
        uploaded.alpha_tested_triangle_count += tested ? 1u : 0u;
    }
    return uploaded;
}

std::vector<uint32_t> traceKernelSpecialization(const TraceSceneGpu& scene) {
    return {scene.has_alpha_masks ? 1u : 0u};
}

SkyTablesGpu uploadSkyTables(const GpuDevice& gpu, const SkySamplingTables& sky) {
    return {uploadedBuffer(gpu, sky.radiance_rgba, kTraceInputUsage), uploadedBuffer(gpu, sky.table, kTraceInputUsage)};
}

std::vector<TexelBufferBinding> traceInputTexelBindings() {
    return {{BAKE_BVH_NODE_BINDING, VK_FORMAT_R32G32B32A32_UINT},
            {BAKE_BVH_TRIANGLE_BINDING, VK_FORMAT_R32G32B32A32_UINT},
            {BAKE_SHADING_TRIANGLE_BINDING, VK_FORMAT_R32G32B32A32_UINT},
            {BAKE_MATERIAL_BINDING, VK_FORMAT_R32G32B32A32_UINT},
            {BAKE_TEXTURE_BINDING, VK_FORMAT_R32_UINT},
            {BAKE_SKY_RADIANCE_BINDING, VK_FORMAT_R32G32B32A32_SFLOAT},
            {BAKE_SKY_TABLE_BINDING, VK_FORMAT_R32_SFLOAT}};
}

std::vector<const GpuBuffer*> traceInputBuffers(const TraceSceneGpu& scene, const SkyTablesGpu& sky,
                                                const std::vector<const GpuBuffer*>& kernel_buffers) {
    std::vector<const GpuBuffer*> buffers = {&scene.bvh_nodes,         &scene.bvh_triangles, &scene.shading_triangles,
                                             &scene.materials,         &scene.texture_words, &sky.radiance,
                                             &sky.table};
    buffers.insert(buffers.end(), kernel_buffers.begin(), kernel_buffers.end());
    return buffers;
}

}  // namespace gusuku::bake

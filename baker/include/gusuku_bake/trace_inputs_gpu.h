#pragma once
// What both trace kernels read: the scene (BVH, shading triangles, materials, textures) and the sky (radiance
// map and sampling tables), uploaded once per tracer as uniform texel buffers at bindings 0-6 of set 0
// (shaders/include/bake_irradiance_interface.h and camera_trace_interface.h give them the same numbers;
// bvh_layout.glsl, scene_shading.glsl and sky_sampling.glsl say why texel buffers and in which formats).
// One upload and one binding list, so the bake's tracer and the camera tracer cannot drift apart.

#include <cstddef>
#include <vector>

#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

/// The scene's five buffers, bindings 0-4.
struct TraceSceneGpu {
    GpuBuffer bvh_nodes;
    GpuBuffer bvh_triangles;
    GpuBuffer shading_triangles;
    GpuBuffer materials;
    GpuBuffer texture_words;
    size_t triangle_count = 0;          ///< the scene's triangles
    size_t dropped_triangle_count = 0;  ///< left out of the BVH (degenerate or not finite)
    bool has_alpha_masks = false;       ///< a triangle runs the alpha test (narrowAlphaMaskFlags kept its flag)
    size_t alpha_tested_triangle_count = 0;  ///< triangles that run it: those whose footprint holds a hole
};

/// The trace kernels' specialisation constants for this scene: constant_id 0 is BVH_ALPHA_MASKS
/// (shaders/include/bvh_alpha_mask.glsl), 1 only when the scene has a masked triangle, so an opaque scene runs
/// a kernel without the alpha test at all.
std::vector<uint32_t> traceKernelSpecialization(const TraceSceneGpu& scene);

/// Builds the BVH (or takes scene.bvh when the scene carries one) and packs the shading (textures box-downsampled to max_texture_size), then uploads both.
/// Throws what buildBvh, packSceneShading and GpuBuffer throw.
TraceSceneGpu uploadTraceScene(const GpuDevice& gpu, const TraceScene& scene, int max_texture_size);

/// The sky's two buffers, bindings 5 and 6.
struct SkyTablesGpu {
    GpuBuffer radiance;
    GpuBuffer table;
};

SkyTablesGpu uploadSkyTables(const GpuDevice& gpu, const SkySamplingTables& sky);

/// The seven bindings' texel formats, for ComputePipeline.
std::vector<TexelBufferBinding> traceInputTexelBindings();

/// Bindings 0-6 (the scene's, then the sky's), followed by the kernel's own buffers, for bindBuffers.
std::vector<const GpuBuffer*> traceInputBuffers(const TraceSceneGpu& scene, const SkyTablesGpu& sky,
                                                const std::vector<const GpuBuffer*>& kernel_buffers);

/// A buffer of `usage` holding `values` (16 bytes at least: Vulkan refuses an empty one).
template <typename T>
GpuBuffer uploadedBuffer(const GpuDevice& gpu, const std::vector<T>& values,
                         VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    GpuBuffer buffer(gpu, std::max<size_t>(values.size() * sizeof(T), 16), usage);
    if (!values.empty()) buffer.uploadVector(values);
    return buffer;
}

}  // namespace gusuku::bake

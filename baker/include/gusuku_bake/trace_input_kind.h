#pragma once
// How the trace kernels read their shared inputs (trace_inputs_gpu.h): as uniform texel buffers, where lavapipe
// gathers a texel fetch's lanes in vector code (bvh_layout.glsl), or as storage buffers, for a device whose
// maxTexelBufferElements is below what a scene can hold (65536, the Vulkan minimum, on SwiftShader and many
// phones). Both kernels are built both ways (shaders/CMakeLists.txt, TRACE_INPUTS_STORAGE_BUFFERS); the loads
// return the same bits, so a bake is the same either way on one driver (test_trace_input_kinds).

#include <vector>

#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"

namespace gusuku::bake {

enum class TraceInputKind { TexelBuffers, StorageBuffers };

/// Texel buffers when every buffer the bake may upload (each at most maxStorageBufferRange bytes, which the
/// preflight checks, so at most a quarter of that in 4-byte texels) fits the device's maxTexelBufferElements;
/// storage buffers otherwise. A property of the device alone, so a device bakes every scene the same way.
/// GUSUKU_CLAMP_LIMITS=maxTexelBufferElements=65536 (gusuku/gpu/device_limits.h) picks storage buffers on any device.
TraceInputKind traceInputKind(const GpuDevice& gpu);

const char* traceInputKindName(TraceInputKind kind);

/// The seven inputs' texel formats for ComputePipeline under `kind` (none: all storage buffers).
std::vector<TexelBufferBinding> traceInputTexelBindings(TraceInputKind kind);

/// Throws std::runtime_error naming the first device limit the trace kernels need and the device lacks: under
/// storage buffers, all 10 bindings as storage buffers in one stage and set (maxPerStageDescriptorStorageBuffers
/// and maxDescriptorSetStorageBuffers: Vulkan 1.0 promises only 4 and 24, SwiftShader and the Android Baseline
/// 2022 profile have 35 or more); under texel buffers 7 sampled images and 3 storage buffers; a 64-lane workgroup;
/// the largest push constants (72 bytes). The bake calls it before its geometry, each tracer when it is made.
void checkTraceDeviceLimits(const GpuDevice& gpu);

}  // namespace gusuku::bake

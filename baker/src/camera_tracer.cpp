#include "gusuku_bake/camera_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "bake_accumulate_comp_spv.h"
#include "bake_accumulate_interface.h"
#include "camera_trace_comp_spv.h"
#include "camera_trace_interface.h"
#include "camera_trace_storage_comp_spv.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/trace_input_kind.h"

namespace gusuku::bake {

namespace {

// Bindings and push constants are written once, in shaders/include/camera_trace_interface.h.
using TracePushConstants = shader_interface::CameraTracePushConstants;
using AccumulatePushConstants = shader_interface::BakeAccumulatePushConstants;
static_assert(sizeof(TracePushConstants) == 128 && offsetof(TracePushConstants, intrinsics) == 32 &&
                  offsetof(TracePushConstants, camera_row0) == 48 &&
                  offsetof(TracePushConstants, sun_direction_cos_max) == 96 &&
                  offsetof(TracePushConstants, sun_irradiance_ray_offset) == 112,
              "std430 offsets of camera_trace_interface.h's push constants");
static_assert(CAMERA_TRACE_WORKGROUP_SIZE == BAKE_ACCUMULATE_WORKGROUP_SIZE,
              "one workgroup count serves the trace and the accumulate kernels");
static_assert(CAMERA_GUIDE_VEC4S_PER_PIXEL == 3, "CameraGuides' accessors read three vec4 per pixel");

constexpr uint32_t kWorkgroupSize = CAMERA_TRACE_WORKGROUP_SIZE;
// One chunk's per-sample scratch (pixels x samples vec4) is kept under this, well inside lavapipe's 128 MiB cap.
constexpr size_t kMaxScratchBytes = size_t(64) << 20;

[[noreturn]] void refuse(const std::string& field, const std::string& problem) {
    throw std::invalid_argument("camera render: " + field + ": " + problem);
}

bool finite(double value) { return std::isfinite(value); }

void checkView(const GpuDevice& gpu, const CameraLight& light, const CameraIntrinsics& intrinsics,
               const CameraPose& pose, const CameraRenderOptions& options) {
    if (light.sky == nullptr) refuse("light.sky", "no sky tables");
    if (!(finite(intrinsics.fx) && intrinsics.fx > 0.0)) refuse("intrinsics.fx", "must be finite and > 0");
    if (!(finite(intrinsics.fy) && intrinsics.fy > 0.0)) refuse("intrinsics.fy", "must be finite and > 0");
    if (!finite(intrinsics.cx) || !finite(intrinsics.cy)) refuse("intrinsics.cx/cy", "must be finite");
    if (intrinsics.width == 0 || intrinsics.height == 0) refuse("intrinsics.width/height", "empty image");
    const uint64_t pixels = uint64_t(intrinsics.width) * intrinsics.height;
    const uint64_t by_groups = uint64_t(gpu.limits().maxComputeWorkGroupCount[0]) * kWorkgroupSize;
    const uint64_t by_guides = gpu.limits().maxStorageBufferRange / (CAMERA_GUIDE_VEC4S_PER_PIXEL * sizeof(glm::vec4));
    if (pixels > std::min(by_groups, by_guides))
        refuse("intrinsics.width/height", std::to_string(pixels) + " pixels, more than the device allows (" +
                                              std::to_string(std::min(by_groups, by_guides)) + ")");
    for (int axis = 0; axis < 3; ++axis) {
        if (!finite(pose.position_enu[axis])) refuse("pose.position_enu", "must be finite");
        for (int other = 0; other < 3; ++other) {
            if (!finite(pose.camera_to_enu[axis][other])) refuse("pose.camera_to_enu", "must be finite");
            const double expected = axis == other ? 1.0 : 0.0;
            if (std::fabs(glm::dot(pose.camera_to_enu[axis], pose.camera_to_enu[other]) - expected) > 1e-3)
                refuse("pose.camera_to_enu", "columns must be orthonormal");
        }
    }
    if (options.samples_per_pixel == 0) refuse("samples_per_pixel", "must be > 0");
}

}  // namespace

CameraTracer::CameraTracer(const GpuDevice& gpu, const TraceScene& scene, int max_texture_size)
    : gpu_(gpu), submitter_(std::make_unique<GpuSubmitter>(gpu)),
      scene_((checkTraceDeviceLimits(gpu), uploadTraceScene(gpu, scene, max_texture_size))) {
    ray_counter_ = GpuBuffer(gpu, 16);
    // How the kernel reads the scene and the sky is the device's choice (trace_input_kind.h).
    const TraceInputKind kind = traceInputKind(gpu);
    const bool texel = kind == TraceInputKind::TexelBuffers;
    trace_pipeline_ = std::make_unique<ComputePipeline>(
        gpu, texel ? kCameraTraceCompSpirv : kCameraTraceStorageCompSpirv,
        texel ? sizeof(kCameraTraceCompSpirv) : sizeof(kCameraTraceStorageCompSpirv), CAMERA_TRACE_BINDING_COUNT,
        uint32_t(sizeof(TracePushConstants)), traceInputTexelBindings(kind), traceKernelSpecialization(scene_));
    accumulate_pipeline_ = std::make_unique<ComputePipeline>(gpu, kBakeAccumulateCompSpirv,
                                                             sizeof(kBakeAccumulateCompSpirv),
                                                             BAKE_ACCUMULATE_BINDING_COUNT,
                                                             uint32_t(sizeof(AccumulatePushConstants)));
}

CameraTracer::~CameraTracer() = default;

CameraRender CameraTracer::render(const CameraLight& light, const CameraIntrinsics& intrinsics,
                                  const CameraPose& pose, const CameraRenderOptions& options) {
    checkView(gpu_, light, intrinsics, pose, options);
    const auto start = std::chrono::steady_clock::now();
    sky_ = uploadSkyTables(gpu_, *light.sky);

    const uint32_t pixel_count = intrinsics.width * intrinsics.height;
    TracePushConstants push{};
    push.width = intrinsics.width;
    push.height = intrinsics.height;
    push.max_bounces = options.max_bounces;
    push.seed = options.seed;
    push.skip_flags = options.include_building ? 0u : kTriangleFlagBuilding;
    const SkySampling sky_sampling = resolveSkySampling(options.sky_sampling, *light.sky);
    push.flags = (light.sun.present ? CAMERA_FLAG_SUN_PRESENT : 0u) |
                 (sky_sampling == SkySampling::CosineAndMap ? CAMERA_FLAG_SKY_NEXT_EVENT : 0u);
    push.intrinsics[0] = float(intrinsics.fx);
    push.intrinsics[1] = float(intrinsics.fy);
    push.intrinsics[2] = float(intrinsics.cx);
    push.intrinsics[3] = float(intrinsics.cy);
    shader_interface::vec4* rows[3] = {&push.camera_row0, &push.camera_row1, &push.camera_row2};
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) (*rows[row])[column] = float(pose.camera_to_enu[column][row]);
        (*rows[row])[3] = float(pose.position_enu[row]);
    }
    // The same sun as the bake's TracePass (IrradianceTracer::addSamples).
    packSunLight(light.sun, options.ray_offset_m, push.sun_direction_cos_max.components,
                 push.sun_irradiance_ray_offset.components);

    const uint32_t pixel_groups = (pixel_count + kWorkgroupSize - 1) / kWorkgroupSize;
    const size_t pixel_bytes = size_t(pixel_count) * sizeof(glm::vec4);
    const uint32_t max_chunk = uint32_t(std::clamp<size_t>(kMaxScratchBytes / pixel_bytes, 1,
                                                           gpu_.limits().maxComputeWorkGroupCount[1]));
    const uint32_t first_chunk = std::min(max_chunk, options.samples_per_pixel);
    if (sample_estimates_.size() < size_t(first_chunk) * pixel_bytes)
        sample_estimates_ = GpuBuffer(gpu_, size_t(first_chunk) * pixel_bytes);
    GpuBuffer guides(gpu_, size_t(pixel_count) * CAMERA_GUIDE_VEC4S_PER_PIXEL * sizeof(glm::vec4));
    GpuBuffer sums(gpu_, pixel_bytes);
    sums.uploadVector(std::vector<glm::vec4>(pixel_count, glm::vec4(0.0f)));
    static_assert(CAMERA_SAMPLE_ESTIMATE_BINDING == 7 && CAMERA_GUIDE_BINDING == 8 && CAMERA_RAY_COUNTER_BINDING == 9);
    trace_pipeline_->bindBuffers(traceInputBuffers(scene_, sky_, {&sample_estimates_, &guides, &ray_counter_}));
    // The accumulate pass also sums squared luminance (the bake's variance); a frame has no use for it, but
    // the pass needs the buffer (zeroed: a sum of non-finite garbage would be harmless but is not needed).
    GpuBuffer luminance_square_sums(gpu_, std::max<size_t>(size_t(pixel_count) * sizeof(float), 16));
    luminance_square_sums.uploadVector(std::vector<float>(pixel_count, 0.0f));
    accumulate_pipeline_->bindBuffers({&sample_estimates_, &sums, &luminance_square_sums});

    CameraRender result;
    result.samples_per_pixel = options.samples_per_pixel;
    const uint32_t zero_counter[4] = {0, 0, 0, 0};
    const auto countRays = [&] {
        uint32_t rays = 0;
        ray_counter_.download(&rays, sizeof rays);
        result.rays_traced += rays;
        ray_counter_.upload(zero_counter, sizeof zero_counter);
    };
    ray_counter_.upload(zero_counter, sizeof zero_counter);

    // The guides: one ray through each pixel's centre.
    TracePushConstants guide_push = push;
    guide_push.flags |= CAMERA_FLAG_GUIDE_PASS;
    guide_push.sample_count = 1;
    submitter_->submitAndWait([&](VkCommandBuffer cmd) {
        trace_pipeline_->recordDispatch(cmd, &guide_push, pixel_groups, 1);
        recordComputeBarrier(cmd);
    });
    countRays();

    for (uint32_t done = 0; done < options.samples_per_pixel;) {
        const uint32_t chunk = std::min(first_chunk, options.samples_per_pixel - done);
        push.first_sample = done;
        push.sample_count = chunk;
        const AccumulatePushConstants accumulate_push{pixel_count, chunk};
        submitter_->submitAndWait([&](VkCommandBuffer cmd) {
            trace_pipeline_->recordDispatch(cmd, &push, pixel_groups, chunk);
            recordComputeBarrier(cmd);
            accumulate_pipeline_->recordDispatch(cmd, &accumulate_push, pixel_groups);
            recordComputeBarrier(cmd);
        });
        countRays();
        done += chunk;
        if (options.progress) options.progress(done, options.samples_per_pixel);
    }

    const std::vector<glm::vec4> pixel_sums = sums.downloadVector<glm::vec4>(pixel_count);
    result.radiance.width = int(intrinsics.width);
    result.radiance.height = int(intrinsics.height);
    result.radiance.texels.resize(size_t(pixel_count) * 4);
    const float inverse_samples = 1.0f / float(options.samples_per_pixel);
    for (size_t i = 0; i < pixel_count; ++i) {
        for (int channel = 0; channel < 3; ++channel)
            result.radiance.texels[4 * i + channel] = pixel_sums[i][channel] * inverse_samples;
        result.radiance.texels[4 * i + 3] = 1.0f;
    }
    result.guides.width = int(intrinsics.width);
    result.guides.height = int(intrinsics.height);
    result.guides.texels = guides.downloadVector<glm::vec4>(size_t(pixel_count) * CAMERA_GUIDE_VEC4S_PER_PIXEL);
    result.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace gusuku::bake

#include "gusuku_bake/irradiance_tracer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

#include "bake_accumulate_comp_spv.h"
#include "bake_accumulate_interface.h"
#include "bake_irradiance_comp_spv.h"
#include "bake_irradiance_interface.h"
#include "bake_irradiance_storage_comp_spv.h"
#include "gusuku/maths/colour.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/trace_input_kind.h"

namespace gusuku::bake {

namespace {

// Bindings and push constants are written once, in shaders/include/bake_{irradiance,accumulate}_interface.h.
using BakePushConstants = shader_interface::BakeIrradiancePushConstants;
using AccumulatePushConstants = shader_interface::BakeAccumulatePushConstants;
static_assert(sizeof(BakePushConstants) == 76 && offsetof(BakePushConstants, first_point) == 4 &&
                  offsetof(BakePushConstants, sun_direction_cos_max) == 32 &&
                  offsetof(BakePushConstants, sun_irradiance_ray_offset) == 48 &&
                  offsetof(BakePushConstants, sky_next_event) == 64 &&
                  offsetof(BakePushConstants, sky_rays_at_point) == 68 &&
                  offsetof(BakePushConstants, samples_per_lane_group) == 72,
              "std430 offsets of bake_irradiance_interface.h's push constants");
static_assert(uint32_t(TraceMode::IndirectIrradiance) == BAKE_MODE_INDIRECT &&
              uint32_t(TraceMode::SunDirect) == BAKE_MODE_SUN_DIRECT);
// ComputePipeline takes the values of constant_id 0, 1, 2, ... in order (gpu_compute.h).
static_assert(BAKE_SKY_NEXT_EVENT_CONSTANT == 1 && BAKE_TRACE_MODE_CONSTANT == 2 &&
              IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT == 3);

constexpr uint32_t kWorkgroupSize = BAKE_WORKGROUP_SIZE;
static_assert(BAKE_ACCUMULATE_WORKGROUP_SIZE == BAKE_WORKGROUP_SIZE, "one point_groups count serves both kernels");
// The per-sample scratch buffer holds point_count x chunk vec4s; chunks are cut so it stays under this (well
// inside lavapipe's 128 MiB storage-buffer cap).
constexpr size_t kMaxScratchBytes = size_t(64) << 20;
// The most samples of one point that consecutive invocations of the trace kernel take (bake_irradiance.comp):
// lavapipe's SIMD width in 32-bit lanes (256-bit vectors). On the shrine (16 samples, byte-identical bake sets)
// this layout traced 1.30x the rays per wall second of one point per lane (docs/measurements.md, "Tracer speed").
constexpr uint32_t kMaxSamplesPerLaneGroup = 8;

}  // namespace

void packSunLight(const SunLight& sun, float ray_offset_m, float direction_cos_max[4], float irradiance_ray_offset[4]) {
    const glm::dvec3 sun_direction = sun.present ? glm::normalize(sun.direction_enu) : glm::dvec3(0.0, 0.0, 1.0);
    for (int axis = 0; axis < 3; ++axis) {
        direction_cos_max[axis] = float(sun_direction[axis]);
        irradiance_ray_offset[axis] = float(sun.irradiance_rgb[axis]);
    }
    direction_cos_max[3] = float(std::cos(sun.angular_radius_deg * std::numbers::pi / 180.0));
    irradiance_ray_offset[3] = ray_offset_m;
}

uint64_t tracerCodeHash() {
    return ContentHash().addBytes(kBakeIrradianceCompSpirv, sizeof(kBakeIrradianceCompSpirv)).value();
}

IrradianceTracer::IrradianceTracer(VulkanContext& context, const TraceScene& scene, const SkySamplingTables& sky,
                                   int max_texture_size)
    : context_(context), scene_((checkTraceDeviceLimits(context), uploadTraceScene(context, scene, max_texture_size))) {
    ray_counter_ = GpuBuffer(context, 16);
    setSky(sky);
    accumulate_pipeline_ = std::make_unique<ComputePipeline>(context, kBakeAccumulateCompSpirv,
                                                             sizeof(kBakeAccumulateCompSpirv), BAKE_ACCUMULATE_BINDING_COUNT,
                                                             uint32_t(sizeof(AccumulatePushConstants)));
}

IrradianceTracer::~IrradianceTracer() = default;

ComputePipeline& IrradianceTracer::pipelineFor(const TraceKernelVariant& variant) {
    std::unique_ptr<ComputePipeline>& pipeline = pipelines_[variant];
    if (!pipeline) {
        std::vector<uint32_t> specialization = traceKernelSpecialization(scene_);  // constant_id 0
        specialization.push_back(variant.sky_next_event ? 1u : 0u);               // BAKE_SKY_NEXT_EVENT_CONSTANT
        specialization.push_back(uint32_t(variant.mode));                         // BAKE_TRACE_MODE_CONSTANT
        specialization.push_back(variant.bounces_before_roulette);  // IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT
        // The device decides how the kernel reads the scene and the sky (trace_input_kind.h); the results are
        // the same bits either way, so the bake's input_hash keeps the texel kernel's code (tracerCodeHash).
        const TraceInputKind kind = traceInputKind(context_);
        const bool texel = kind == TraceInputKind::TexelBuffers;
        pipeline = std::make_unique<ComputePipeline>(
            context_, texel ? kBakeIrradianceCompSpirv : kBakeIrradianceStorageCompSpirv,
            texel ? sizeof(kBakeIrradianceCompSpirv) : sizeof(kBakeIrradianceStorageCompSpirv),
            BAKE_IRRADIANCE_BINDING_COUNT, uint32_t(sizeof(BakePushConstants)), traceInputTexelBindings(kind),
            specialization);
    }
    return *pipeline;
}

TraceKernelVariant IrradianceTracer::kernelVariantFor(const TracePass& pass) const {
    TraceKernelVariant variant;
    variant.sky_next_event = resolvedSkySampling(pass.sky_sampling) == SkySampling::CosineAndMap;
    variant.mode = pass.mode;
    // 0 would end every path at its first reflection's roulette just as 1 does: the kernel clamped it to 1 before
    // it was a specialisation constant, and so does this.
    variant.bounces_before_roulette = std::max(pass.bounces_before_roulette, 1u);
    return variant;
}

void IrradianceTracer::setSky(const SkySamplingTables& sky) {
    sky_ = uploadSkyTables(context_, sky);
    automatic_sky_sampling_ = resolveSkySampling(SkySampling::Automatic, sky);
}

PointAccumulator IrradianceTracer::createAccumulator(const std::vector<QueryPointGpu>& points) {
    // Every point of a set is traced in one dispatch, a workgroup per BAKE_WORKGROUP_SIZE points.
    const uint64_t max_points = uint64_t(context_.gpu().limits().maxComputeWorkGroupCount[0]) * kWorkgroupSize;
    if (points.size() > max_points)
        throw std::runtime_error("the bake traces " + std::to_string(points.size()) +
                                 " points in one set, more than this device's (" +
                                 context_.gpu().properties.deviceName + ") maxComputeWorkGroupCount[0] of " +
                                 std::to_string(context_.gpu().limits().maxComputeWorkGroupCount[0]) + " x " +
                                 std::to_string(kWorkgroupSize) +
                                 " lets one dispatch reach: bake with a smaller lightmap (site.json "
                                 "bake.texels_per_metre) or a coarser ground grid");
    PointAccumulator accumulator;
    accumulator.point_count = uint32_t(points.size());
    accumulator.points = uploadedBuffer(context_, points);
    accumulator.sums = GpuBuffer(context_, std::max<size_t>(points.size() * sizeof(glm::vec4), 16));
    const std::vector<glm::vec4> zeros(points.size(), glm::vec4(0.0f));
    if (!zeros.empty()) accumulator.sums.uploadVector(zeros);
    accumulator.luminance_square_sums = GpuBuffer(context_, std::max<size_t>(points.size() * sizeof(float), 16));
    const std::vector<float> square_zeros(points.size(), 0.0f);
    if (!square_zeros.empty()) accumulator.luminance_square_sums.uploadVector(square_zeros);
    return accumulator;
}

BakePushConstants IrradianceTracer::pushConstantsFor(const TracePass& pass) const {
    BakePushConstants push{};
    push.max_bounces = pass.max_bounces;
    push.seed = pass.seed;
    push.skip_flags = pass.skip_flags;
    push.sun_present = pass.sun.present ? 1u : 0u;
    packSunLight(pass.sun, pass.ray_offset_m, push.sun_direction_cos_max.components,
                 push.sun_irradiance_ray_offset.components);
    push.sky_next_event = resolvedSkySampling(pass.sky_sampling) == SkySampling::CosineAndMap ? 1u : 0u;
    push.sky_rays_at_point = resolvedSkyRaysAtPoint(pass);
    return push;
}

uint64_t IrradianceTracer::dispatchRange(PointAccumulator& accumulator, const TraceKernelVariant& variant,
                                         BakePushConstants push, uint32_t first_point,
                                         uint32_t point_count, uint32_t first_sample, uint32_t sample_count) {
    const size_t scratch_bytes = size_t(point_count) * size_t(sample_count) * sizeof(glm::vec4);
    if (sample_estimates_.size() < scratch_bytes) sample_estimates_ = GpuBuffer(context_, scratch_bytes);
    static_assert(BAKE_QUERY_POINT_BINDING == 7 && BAKE_SAMPLE_ESTIMATE_BINDING == 8 && BAKE_RAY_COUNTER_BINDING == 9);
    ComputePipeline& pipeline = pipelineFor(variant);
    pipeline.bindBuffers(traceInputBuffers(scene_, sky_, {&accumulator.points, &sample_estimates_, &ray_counter_}));
    accumulate_pipeline_->bindBuffers({&sample_estimates_, &accumulator.sums, &accumulator.luminance_square_sums});
    push.point_count = point_count;
    push.first_point = first_point;
    push.first_sample = first_sample;
    push.sample_count = sample_count;
    const AccumulatePushConstants accumulate_push{point_count, sample_count, first_point};
    const uint32_t zero_counter[4] = {0, 0, 0, 0};
    ray_counter_.upload(zero_counter, sizeof zero_counter);
    // The largest of 8, 4, 2, 1 that divides the chunk (bake_irradiance.comp: a point's samples side by side).
    uint32_t lane_group = kMaxSamplesPerLaneGroup;
    const uint64_t max_groups = context_.gpu().limits().maxComputeWorkGroupCount[0];
    while (sample_count % lane_group != 0 ||
           (lane_group > 1 && (uint64_t(point_count) * lane_group + kWorkgroupSize - 1) / kWorkgroupSize > max_groups))
        lane_group /= 2;
    push.samples_per_lane_group = lane_group;
    const uint32_t point_groups = (point_count + kWorkgroupSize - 1) / kWorkgroupSize;
    const uint32_t trace_groups = uint32_t((uint64_t(point_count) * lane_group + kWorkgroupSize - 1) / kWorkgroupSize);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        pipeline.recordDispatch(cmd, &push, trace_groups, sample_count / lane_group);
        recordComputeBarrier(cmd);
        accumulate_pipeline_->recordDispatch(cmd, &accumulate_push, point_groups);
        recordComputeBarrier(cmd);
    });
    uint32_t rays = 0;
    ray_counter_.download(&rays, sizeof rays);
    return rays;
}

uint64_t IrradianceTracer::addSamples(PointAccumulator& accumulator, uint32_t sample_count, const TracePass& pass) {
    if (accumulator.points_with_next_sample != 0)
        throw std::logic_error("addSamples: a sample pass is part done (finish it with addSampleToNextPoints)");
    // An empty set (no ground cell on the SfM mesh, say) has nothing to trace, but its samples are still done:
    // callers loop until samples_done reaches their target, and would spin forever if it never moved.
    if (accumulator.point_count == 0) {
        accumulator.samples_done += sample_count;
        return 0;
    }
    const BakePushConstants push = pushConstantsFor(pass);
    const TraceKernelVariant variant = kernelVariantFor(pass);
    const size_t point_bytes = size_t(accumulator.point_count) * sizeof(glm::vec4);
    // A sample per workgroup row: at most the device's maxComputeWorkGroupCount[1] (65535 or more).
    const uint32_t max_chunk = uint32_t(std::max<size_t>(
        1, std::min<size_t>(kMaxScratchBytes / point_bytes, context_.gpu().limits().maxComputeWorkGroupCount[1])));
    uint64_t rays = 0;
    for (uint32_t done = 0; done < sample_count;) {
        const uint32_t chunk = std::min(max_chunk, sample_count - done);
        rays += dispatchRange(accumulator, variant, push, 0, accumulator.point_count, accumulator.samples_done, chunk);
        accumulator.samples_done += chunk;
        done += chunk;
    }
    return rays;
}

uint64_t IrradianceTracer::addSampleToNextPoints(PointAccumulator& accumulator, uint32_t point_count,
                                                 const TracePass& pass) {
    const uint32_t first_point = accumulator.points_with_next_sample;
    const uint32_t count = std::min(point_count, accumulator.point_count - first_point);
    uint64_t rays = 0;
    if (count > 0)
        rays = dispatchRange(accumulator, kernelVariantFor(pass), pushConstantsFor(pass), first_point, count,
                             accumulator.samples_done, 1);
    accumulator.points_with_next_sample += count;
    if (accumulator.points_with_next_sample >= accumulator.point_count) {
        accumulator.points_with_next_sample = 0;
        ++accumulator.samples_done;
    }
    return rays;
}

std::vector<glm::vec4> IrradianceTracer::readSums(const PointAccumulator& accumulator) const {
    return accumulator.sums.downloadVector<glm::vec4>(accumulator.point_count);
}

std::vector<float> IrradianceTracer::readLuminanceSquareSums(const PointAccumulator& accumulator) const {
    return accumulator.luminance_square_sums.downloadVector<float>(accumulator.point_count);
}

void IrradianceTracer::restoreSums(PointAccumulator& accumulator, const std::vector<glm::vec4>& sums,
                                   const std::vector<float>& luminance_square_sums, uint32_t samples_done,
                                   uint32_t points_with_next_sample) {
    if (sums.size() != accumulator.point_count || luminance_square_sums.size() != accumulator.point_count)
        throw std::invalid_argument("restoreSums: point count differs from the accumulator's");
    if (points_with_next_sample >= std::max(accumulator.point_count, 1u))
        throw std::invalid_argument("restoreSums: points_with_next_sample " + std::to_string(points_with_next_sample) +
                                    " is not below the point count " + std::to_string(accumulator.point_count));
    if (!sums.empty()) accumulator.sums.uploadVector(sums);
    if (!luminance_square_sums.empty()) accumulator.luminance_square_sums.uploadVector(luminance_square_sums);
    accumulator.samples_done = samples_done;
    accumulator.points_with_next_sample = points_with_next_sample;
}

std::vector<glm::vec3> IrradianceTracer::traceIrradiance(const std::vector<QueryPointGpu>& points,
                                                         uint32_t samples, const TracePass& pass) {
    PointAccumulator accumulator = createAccumulator(points);
    // Chunks keep each dispatch short (a long one can trip a driver watchdog on real GPUs).
    const uint32_t chunk = 16;
    while (accumulator.samples_done < samples)
        addSamples(accumulator, std::min(chunk, samples - accumulator.samples_done), pass);
    const std::vector<glm::vec4> sums = readSums(accumulator);
    std::vector<glm::vec3> irradiance(sums.size());
    for (size_t i = 0; i < sums.size(); ++i) irradiance[i] = glm::vec3(sums[i]) / float(std::max(samples, 1u));
    return irradiance;
}

float luminanceVarianceOfMean(const glm::vec4& sum, float luminance_square_sum, uint32_t samples) {
    if (samples < 2) return 0.0f;
    const double count = double(samples);
    const double mean = luminanceRec709(glm::dvec3(sum)) / count;
    const double sample_variance = std::max(double(luminance_square_sum) / count - mean * mean, 0.0) * count /
                                   (count - 1.0);
    return float(sample_variance / count);
}

SkySampling IrradianceTracer::resolvedSkySampling(SkySampling requested) const {
    return requested == SkySampling::Automatic ? automatic_sky_sampling_ : requested;
}

uint32_t IrradianceTracer::resolvedSkyRaysAtPoint(const TracePass& pass) const {
    if (resolvedSkySampling(pass.sky_sampling) != SkySampling::CosineAndMap) return 1;
    if (pass.sky_rays_at_point == 0)
        return pass.sun.present || pass.mode != TraceMode::IndirectIrradiance ? 1u : kSkyRaysAtPointWithoutSun;
    // A power of two: the rays of a sample are then one aligned block of the Sobol sequence (rngNext2Split).
    if (pass.sky_rays_at_point > 64 || !std::has_single_bit(pass.sky_rays_at_point))
        throw std::invalid_argument("TracePass::sky_rays_at_point " + std::to_string(pass.sky_rays_at_point) +
                                    " is not a power of two up to 64");
    return pass.sky_rays_at_point;
}

SkySampling resolveSkySampling(SkySampling requested, const SkySamplingTables& sky) {
    if (requested != SkySampling::Automatic) return requested;
    return sky.cosine_relative_variance > kSkyNextEventRelativeVarianceThreshold ? SkySampling::CosineAndMap
                                                                                 : SkySampling::CosineOnly;
}

const char* skySamplingName(SkySampling sampling) {
    switch (sampling) {
        case SkySampling::CosineOnly: return "cosine";
        case SkySampling::CosineAndMap: return "cosine + map (MIS)";
        case SkySampling::Automatic: break;
    }
    return "automatic";
}

}  // namespace gusuku::bake

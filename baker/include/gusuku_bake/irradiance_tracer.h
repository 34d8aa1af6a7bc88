#pragma once
// The GPU irradiance tracer: uploads a TraceScene (BVH, shading, textures) and a sky once, then adds samples
// to running irradiance sums at sets of query points (lightmap texels, ground cells, test probes). The light
// transport itself is in shaders/include/irradiance_paths.glsl; this class only moves data and dispatches.

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_inputs_gpu.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::shader_interface {
struct BakeIrradiancePushConstants;  // shaders/include/bake_irradiance_interface.h, private to the baker
}
namespace gusuku::bake {

/// A point where irradiance is estimated, in the shader's layout. The convention at a surface (README, "How the
/// baker works"): the cosine lobe about `normal`, with directions below the plane of `face_normal` contributing
/// nothing, so a lightmap texel and a path vertex on the same surface gather the same light.
struct QueryPointGpu {
    glm::vec4 position;                  ///< xyz ENU metres
    glm::vec4 normal;                    ///< xyz unit: the shading normal, about which the cosine lobe gathers;
                                         ///< w: 0, or (uint bits) 1 + the random stream to draw from
                                         ///< (adaptive_sampling.h's copies; 0: the point's own index)
    glm::vec4 face_normal{0.0f};         ///< xyz unit geometric normal of the surface (either winding; the
                                         ///< shader takes it on `normal`'s side); zero: `normal`'s own plane;
                                         ///< w (uint bits, with a stream in normal.w): its first sample index
};
static_assert(sizeof(QueryPointGpu) == 48);

/// The sun as a light for bounces (and for the sun-only test mode).
struct SunLight {
    bool present = false;
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};  ///< unit, towards the sun
    glm::dvec3 irradiance_rgb{0.0};           ///< on a plane facing the sun (normal incidence)
    double angular_radius_deg = 0.2675;       ///< the solar disc's mean apparent radius
};

/// The sun as the bake's and the camera's kernels take it (shaders/include/irradiance_paths.glsl's settings):
/// direction_cos_max = unit direction towards the sun (ENU; (0, 0, 1) when absent) and the cosine of the disc's
/// angular radius; irradiance_ray_offset = E_sun per channel and the ray offset in metres. One packing for both
/// tracers, so the camera's sun is the bake's.
void packSunLight(const SunLight& sun, float ray_offset_m, float direction_cos_max[4], float irradiance_ray_offset[4]);

enum class TraceMode : uint32_t {
    IndirectIrradiance = 0,  ///< E_ind: everything but the direct sun at the point
    SunDirect = 1,           ///< only the direct sun term (sun disc sampled, shadow ray): a test path
};

/// How paths gather sky light at each vertex.
enum class SkySampling : uint32_t {
    Automatic = 0,     ///< CosineAndMap when the sky's cosine relative variance exceeds
                       ///< kSkyNextEventRelativeVarianceThreshold, else CosineOnly
    CosineOnly = 1,    ///< the cosine-sampled continuation ray alone sees the sky (one ray per vertex)
    CosineAndMap = 2,  ///< plus a shadow ray to a direction drawn from the map, MIS (power heuristic)
};

/// The tracer's default for TracePass::bounces_before_roulette (the GLSL's kBouncesBeforeRoulette).
inline constexpr uint32_t kBouncesBeforeRoulette = 3;

struct TracePass {
    TraceMode mode = TraceMode::IndirectIrradiance;
    uint32_t skip_flags = 0;   ///< e.g. kTriangleFlagBuilding for E_without
    uint32_t max_bounces = 4;
    uint32_t seed = 1;
    SunLight sun;
    float ray_offset_m = 1e-3f;  ///< how far rays start off their surface
    SkySampling sky_sampling = SkySampling::Automatic;
    /// Russian roulette ends paths only from this many reflections on (shaders/include/irradiance_paths.glsl's
    /// kBouncesBeforeRoulette, 3, says why); 1 is the estimator before issue 11.1, for tests that compare the two.
    /// Like `mode`, a value other than the default gets a kernel of its own (TraceKernelVariant): the bake's kernel
    /// carries no switch for it.
    uint32_t bounces_before_roulette = kBouncesBeforeRoulette;
    /// With the map sampled (CosineAndMap): sky next-event rays at the query point itself, a power of two up to
    /// 64 (irradiance_paths.glsl); every later vertex sends one. 0: resolvedSkyRaysAtPoint decides.
    uint32_t sky_rays_at_point = 0;
};

/// What a bake kernel pipeline is specialised for (bake_irradiance_interface.h's specialisation constants): a
/// pass's choices that select code, fixed when the pipeline is made so that the bake's own pipeline has the test
/// paths (the sun-direct mode, the earlier roulette) compiled out.
struct TraceKernelVariant {
    bool sky_next_event = true;
    TraceMode mode = TraceMode::IndirectIrradiance;
    uint32_t bounces_before_roulette = kBouncesBeforeRoulette;
    bool operator<(const TraceKernelVariant& other) const {
        return std::tie(sky_next_event, mode, bounces_before_roulette) <
               std::tie(other.sky_next_event, other.mode, other.bounces_before_roulette);
    }
};

/// Sky next-event rays at the query point when a pass has no sun and samples the map (TracePass::sky_rays_at_point
/// 0). Without a sun, a lit texel's noise is the sky it sees itself: on the shrine's overcast slot (photographed
/// sky, map sampled) a texel's estimate with no bounce at all had about the variance of the whole path on its
/// brightest texels, which hold most of the squared error, so more map rays there cost one ray each where a
/// whole sample costs several. Of 1, 4, 8 and 16 rays (converge's study, adaptive, error^2 x rays), 8 was best.
/// With a sun the noise is sunlight bounced off lit surfaces, which more sky rays do not reach: they gained
/// nothing on the shrine's sunny_1200.
inline constexpr uint32_t kSkyRaysAtPointWithoutSun = 8;

/// Running sums for one set of query points, resident on the GPU.
struct PointAccumulator {
    GpuBuffer points;
    GpuBuffer sums;          ///< vec4 per point: irradiance sum xyz, w the sum of the first rays' back-face scores:
                             ///< 1 per hit on the back of a one-sided surface, 1/9 per hit on a double-sided face
                             ///< of a closed part (closed_parts.h) from behind by its winding (irradiance_paths.glsl),
                             ///< so w / samples above kMaxBackfaceFraction = 0.1 means over 10 % one-sided or over
                             ///< 90 % closed double-sided backs (an open sheet's back scores nothing)
    GpuBuffer luminance_square_sums;  ///< float per point: sum of each sample's squared luminance (Rec.709), so
                                      ///< luminanceVarianceOfMean can say how noisy the point's mean is
    uint32_t point_count = 0;
    uint32_t samples_done = 0;  ///< samples every point holds
    /// A sample pass cut into point ranges (addSampleToNextPoints): points [0, this) also hold sample
    /// samples_done. 0 between passes; when the last point gets its sample, samples_done advances and this is 0.
    uint32_t points_with_next_sample = 0;
};

/// Fingerprint of the tracing kernel's SPIR-V: part of a bake's input hash, so checkpoints written by other
/// tracer code are never resumed.
uint64_t tracerCodeHash();

class IrradianceTracer {
public:
    /// Builds the BVH over scene.mesh and uploads everything. `sky` is the sky with the sun disc removed
    /// (its sampling tables). Cost: the BVH build (O(n log n), bvh.h) plus the upload.
    IrradianceTracer(VulkanContext& context, const TraceScene& scene, const SkySamplingTables& sky,
                     int max_texture_size = 512);
    ~IrradianceTracer();

    /// Replaces the sky (each slot has its own).
    void setSky(const SkySamplingTables& sky);

    /// What `requested` means for the current sky: Automatic resolved by the sky's cosine relative variance.
    SkySampling resolvedSkySampling(SkySampling requested) const;
    /// What pass.sky_rays_at_point means for the current sky: 1 when the map is not sampled; else as given, or
    /// for 0, kSkyRaysAtPointWithoutSun without a sun (a sun-direct pass counts as with one) and 1 with one.
    uint32_t resolvedSkyRaysAtPoint(const TracePass& pass) const;

    /// Triangles of alpha-masked materials that run the alpha test, and all of them (the others' footprints read
    /// no texel below the cutoff: narrowAlphaMaskFlags, alpha_mask_footprint.h).
    size_t alphaTestedTriangleCount() const { return scene_.alpha_tested_triangle_count; }

    PointAccumulator createAccumulator(const std::vector<QueryPointGpu>& points);

    /// Adds `sample_count` samples per point: samples [samples_done, samples_done + sample_count) of each
    /// point's fixed random stream, so the result depends only on the total, not on how it was chunked.
    /// Returns the number of rays traced. An empty accumulator advances samples_done without tracing. Throws
    /// std::logic_error while a pass is part done (points_with_next_sample > 0).
    uint64_t addSamples(PointAccumulator& accumulator, uint32_t sample_count, const TracePass& pass);
    /// One sample pass in pieces, so that no dispatch need be longer than a stop may wait: adds sample
    /// samples_done to the next `point_count` points that lack it (from points_with_next_sample on, fewer at the
    /// end of the pass). The sums are those of a whole pass: each point's sum takes its samples in order, from its
    /// own random stream, however the points were split. Returns the number of rays traced.
    uint64_t addSampleToNextPoints(PointAccumulator& accumulator, uint32_t point_count, const TracePass& pass);

    /// The running sums (vec4 per point, see PointAccumulator::sums).
    std::vector<glm::vec4> readSums(const PointAccumulator& accumulator) const;
    /// The running sums of squared luminance (float per point, see PointAccumulator::luminance_square_sums).
    std::vector<float> readLuminanceSquareSums(const PointAccumulator& accumulator) const;
    /// Restores sums saved from an earlier run (resume), with the number of samples they hold (and the points of
    /// a part-done pass that hold one more, PointAccumulator::points_with_next_sample).
    void restoreSums(PointAccumulator& accumulator, const std::vector<glm::vec4>& sums,
                     const std::vector<float>& luminance_square_sums, uint32_t samples_done,
                     uint32_t points_with_next_sample = 0);

    /// Convenience: mean irradiance at each point after `samples` samples (tests, tools).
    std::vector<glm::vec3> traceIrradiance(const std::vector<QueryPointGpu>& points, uint32_t samples,
                                           const TracePass& pass);

    size_t triangleCount() const { return scene_.triangle_count; }
    size_t droppedTriangleCount() const { return scene_.dropped_triangle_count; }

private:
    shader_interface::BakeIrradiancePushConstants pushConstantsFor(const TracePass& pass) const;
    /// Samples [first_sample, first_sample + sample_count) of points [first_point, first_point + point_count),
    /// traced and added onto their sums in one submission; returns the rays traced.
    uint64_t dispatchRange(PointAccumulator& accumulator, const TraceKernelVariant& variant,
                           shader_interface::BakeIrradiancePushConstants push, uint32_t first_point,
                           uint32_t point_count, uint32_t first_sample, uint32_t sample_count);

    TraceKernelVariant kernelVariantFor(const TracePass& pass) const;
    /// The bake kernel specialised for `variant`, made on first use: a bake makes one or two (with and without
    /// the sky map's next-event block, BAKE_SKY_NEXT_EVENT), tests a few more.
    ComputePipeline& pipelineFor(const TraceKernelVariant& variant);

    VulkanContext& context_;
    /// bake_irradiance.comp, one path per invocation, by specialisation.
    std::map<TraceKernelVariant, std::unique_ptr<ComputePipeline>> pipelines_;
    std::unique_ptr<ComputePipeline> accumulate_pipeline_;  ///< bake_accumulate.comp: ordered sums
    GpuBuffer sample_estimates_;                            ///< one chunk's per-sample estimates
    TraceSceneGpu scene_;  ///< bindings 0-4
    SkyTablesGpu sky_;     ///< bindings 5-6
    GpuBuffer ray_counter_;
    SkySampling automatic_sky_sampling_ = SkySampling::CosineOnly;  ///< what Automatic means for the current sky
};

/// The variance of a point's mean luminance after `samples` samples, from its sums (the sample variance with
/// Bessel's correction, over samples; 0 for fewer than two samples). Independent samples are assumed: the
/// scrambled Sobol draws do better than that, so this overstates the error of a well-stratified mean.
float luminanceVarianceOfMean(const glm::vec4& sum, float luminance_square_sum, uint32_t samples);

/// What `requested` means for a sky: Automatic resolved by its cosine relative variance.
SkySampling resolveSkySampling(SkySampling requested, const SkySamplingTables& sky);

/// "cosine" or "cosine + map (MIS)", for manifests and logs.
const char* skySamplingName(SkySampling sampling);

}  // namespace gusuku::bake

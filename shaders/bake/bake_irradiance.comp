#version 450
// Bake kernel: one invocation per (query point, sample): x indexes the point of the dispatch's range (a lightmap texel or a ground cell),
// y the sample within this dispatch's chunk. Each writes its one-sample estimate to a scratch slot;
// bake_accumulate.comp then adds the chunk's samples onto the running sums in sample order.
//
// Why one sample per invocation: llvmpipe (lavapipe) guards shader loops with an iteration limiter that counts
// every iteration of the loops nested inside an outermost loop; an invocation looping over hundreds of samples
// (each with BVH traversal loops inside) silently hit it and lost samples (a long dispatch traced fewer rays
// than the same samples split into shorter ones). One path per invocation stays far below it.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "bake_irradiance_interface.h"

layout(local_size_x = BAKE_WORKGROUP_SIZE) in;

// constant_id 1, false only in the pipeline the tracer makes for passes that gather the sky with the cosine lobe
// alone (IrradianceTracer::pipelineFor): llvmpipe runs the map's next-event block masked for the whole SIMD group
// even when the push constant turns it off (its draws, CDF searches and one pass of the shadow ray's traversal
// loops at every vertex), so that pipeline compiles it out. With it true the push constant decides, as before.
layout(constant_id = BAKE_SKY_NEXT_EVENT_CONSTANT) const bool BAKE_SKY_NEXT_EVENT = true;
// What this pipeline traces (BAKE_MODE_*): every bake's pipeline keeps the default; only tests make one with the
// sun-direct mode, so the bake's kernel carries no branch for it.
layout(constant_id = BAKE_TRACE_MODE_CONSTANT) const uint BAKE_TRACE_MODE = BAKE_MODE_INDIRECT;

#define BVH_NODE_BINDING BAKE_BVH_NODE_BINDING
#define BVH_TRIANGLE_BINDING BAKE_BVH_TRIANGLE_BINDING
#define SHADING_TRIANGLE_BINDING BAKE_SHADING_TRIANGLE_BINDING
#define MATERIAL_BINDING BAKE_MATERIAL_BINDING
#define TEXTURE_BINDING BAKE_TEXTURE_BINDING
#define SKY_RADIANCE_BINDING BAKE_SKY_RADIANCE_BINDING
#define SKY_TABLE_BINDING BAKE_SKY_TABLE_BINDING

#include "sampling.glsl"
#include "bvh_traverse.glsl"
#include "scene_shading.glsl"
#include "sky_sampling.glsl"
#include "irradiance_paths.glsl"

struct QueryPoint {
    vec4 position;     // xyz ENU metres
    vec4 normal;       // xyz unit: the shading normal, about which the cosine lobe gathers; w: uint bits, 0 or
                       // 1 + the index of the random stream to draw from (adaptive sampling's copies of a point)
    vec4 face_normal;  // xyz unit geometric normal (either winding); zero: the shading normal's own plane;
                       // w: uint bits, the first sample index of the stream (with a stream in normal.w)
};
layout(std430, set = 0, binding = BAKE_QUERY_POINT_BINDING) readonly buffer QueryPoints { QueryPoint query_points[]; };
// Per (sample in chunk, point): xyz the irradiance estimate, w the first ray's back-face score
// (estimateIndirectIrradiance: 1 for a one-sided back, kDoubleSidedBackfaceScore for a double-sided one).
layout(std430, set = 0, binding = BAKE_SAMPLE_ESTIMATE_BINDING) writeonly buffer SampleEstimates { vec4 sample_estimates[]; };
layout(std430, set = 0, binding = BAKE_RAY_COUNTER_BINDING) buffer RayCounter { uint rays_traced_total[]; };

// The push-constant block `pc` (BakeIrradiancePushConstants) is declared in bake_irradiance_interface.h.

void main() {
    // x indexes the dispatch's range of points (a long pass is cut into ranges so a stop need not wait for it);
    // the point's own index picks its random stream, so the ranges change nothing. Consecutive invocations (the
    // SIMD lanes llvmpipe runs in step) take pc.samples_per_lane_group samples of one point, y the group of
    // samples: a lane group's paths then leave one point along one normal, so they meet the same occluders and
    // end at more alike depths than the paths of neighbouring texels, and fewer lanes idle. Each (point, sample)
    // draws its own numbers whichever lane runs it, so the layout changes no result.
    uint range_index = gl_GlobalInvocationID.x / pc.samples_per_lane_group;
    uint point_index = pc.first_point + range_index;
    uint sample_in_chunk = gl_GlobalInvocationID.y * pc.samples_per_lane_group +
                           gl_GlobalInvocationID.x % pc.samples_per_lane_group;
    bool in_range = range_index < pc.point_count && sample_in_chunk < pc.sample_count;
    if (in_range) {
        QueryPoint point = query_points[point_index];
        PathSettings settings;
        settings.max_bounces = pc.max_bounces;
        settings.skip_flags = pc.skip_flags;
        settings.sun_present = pc.sun_present != 0u;
        settings.sun_direction = pc.sun_direction_cos_max.xyz;
        settings.sun_cos_max = pc.sun_direction_cos_max.w;
        settings.sun_irradiance = pc.sun_irradiance_ray_offset.xyz;
        settings.ray_offset = pc.sun_irradiance_ray_offset.w;
        settings.sky_next_event = BAKE_SKY_NEXT_EVENT && pc.sky_next_event != 0u;
        g_sky_rays_at_point = max(pc.sky_rays_at_point, 1u);

        // The face plane on the shading normal's side: the half-space light may come from (irradiance_paths.glsl).
        vec3 face_normal = point.face_normal.xyz;
        if (dot(face_normal, face_normal) == 0.0) face_normal = point.normal.xyz;
        else if (dot(face_normal, point.normal.xyz) < 0.0) face_normal = -face_normal;

        // A point's random numbers: its own stream, or (a copy for adaptive sampling's extra samples) the stream of
        // the point it copies from the given sample on, so that a texel's samples are one scrambled Sobol
        // sequence however they were split (independent short sequences stratify far worse).
        uint stream_plus_one = floatBitsToUint(point.normal.w);
        uint stream = stream_plus_one == 0u ? point_index : stream_plus_one - 1u;
        uint first_sample = stream_plus_one == 0u ? 0u : floatBitsToUint(point.face_normal.w);
        Rng rng = rngForSample(pc.seed, stream, first_sample + pc.first_sample + sample_in_chunk);
        vec4 estimate = vec4(0.0);
        if (BAKE_TRACE_MODE == BAKE_MODE_SUN_DIRECT) {
            estimate.xyz = sunIrradianceAt(point.position.xyz, point.normal.xyz, face_normal, rng, settings);
        } else {
            float backface_score;
            estimate.xyz = estimateIndirectIrradiance(point.position.xyz, point.normal.xyz, face_normal, rng,
                                                      settings, backface_score);
            // A NaN from a degenerate input must never reach an output: drop that sample's value.
            if (any(isnan(estimate.xyz)) || any(isinf(estimate.xyz))) estimate.xyz = vec3(0.0);
            estimate.w = backface_score;
        }
        sample_estimates[sample_in_chunk * pc.point_count + range_index] = estimate;
    }
    // One atomic per subgroup rather than per invocation.
    uint subgroup_rays = subgroupAdd(in_range ? g_rays_traced : 0u);
    if (subgroupElect()) atomicAdd(rays_traced_total[0], subgroup_rays);
}

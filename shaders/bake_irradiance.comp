#version 450
// Bake kernel: one invocation per query point (a lightmap texel or a ground cell), sample_count samples per
// dispatch added to the point's running sum. Sums persist across dispatches (and across a resumed bake), so
// samples [first_sample, first_sample + sample_count) of every point are drawn from their own fixed streams.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#define BVH_NODE_BINDING 0
#define BVH_TRIANGLE_BINDING 1
#define SHADING_TRIANGLE_BINDING 2
#define MATERIAL_BINDING 3
#define TEXTURE_BINDING 4
#define SKY_RADIANCE_BINDING 5
#define SKY_TABLE_BINDING 6

#include "sampling.glsl"
#include "bvh_traverse.glsl"
#include "scene_shading.glsl"
#include "sky_sampling.glsl"
#include "irradiance_paths.glsl"

struct QueryPoint {
    vec4 position;  // xyz ENU metres
    vec4 normal;    // xyz unit
};
layout(std430, set = 0, binding = 7) readonly buffer QueryPoints { QueryPoint query_points[]; };
// xyz: sum of irradiance estimates; w: number of first rays that hit a back face (texel validity).
layout(std430, set = 0, binding = 8) buffer Accumulation { vec4 accumulated[]; };
layout(std430, set = 0, binding = 9) buffer RayCounter { uint rays_traced_total[]; };

const uint kModeIndirect = 0u;   // E_ind: everything but the direct sun at the point
const uint kModeSunDirect = 1u;  // the direct sun term alone (tests)

layout(push_constant) uniform PushConstants {
    uint point_count;
    uint first_sample;
    uint sample_count;
    uint max_bounces;
    uint seed;
    uint skip_flags;
    uint mode;
    uint sun_present;
    vec4 sun_direction_cos_max;
    vec4 sun_irradiance_ray_offset;
} pc;

void main() {
    uint point_index = gl_GlobalInvocationID.x;
    if (point_index >= pc.point_count) return;
    QueryPoint point = query_points[point_index];

    PathSettings settings;
    settings.max_bounces = pc.max_bounces;
    settings.skip_flags = pc.skip_flags;
    settings.sun_present = pc.sun_present != 0u;
    settings.sun_direction = pc.sun_direction_cos_max.xyz;
    settings.sun_cos_max = pc.sun_direction_cos_max.w;
    settings.sun_irradiance = pc.sun_irradiance_ray_offset.xyz;
    settings.ray_offset = pc.sun_irradiance_ray_offset.w;

    // Samples are added one by one onto the stored sum, so the floating-point result is the same however the
    // samples are split into dispatches (a resumed bake matches an uninterrupted one bit for bit).
    vec4 running_sum = accumulated[point_index];
    for (uint s = 0u; s < pc.sample_count; ++s) {
        Rng rng = rngForSample(pc.seed, point_index, pc.first_sample + s);
        if (pc.mode == kModeSunDirect) {
            running_sum.xyz += sunIrradianceAt(point.position.xyz, point.normal.xyz, rng, settings);
        } else {
            bool backface_hit;
            vec3 estimate = estimateIndirectIrradiance(point.position.xyz, point.normal.xyz, rng, settings,
                                                       backface_hit);
            // A NaN from a degenerate input must never reach an output: drop that sample's value.
            if (any(isnan(estimate)) || any(isinf(estimate))) estimate = vec3(0.0);
            running_sum += vec4(estimate, backface_hit ? 1.0 : 0.0);
        }
    }
    accumulated[point_index] = running_sum;
    atomicAdd(rays_traced_total[0], g_rays_traced);
}

#version 450
// Test and timing kernel for bvh_traverse.glsl (tests/test_bvh.cpp): one invocation per ray; writes the
// closest hit and/or the any-hit answer, as push constant `queries` asks, so each can be timed alone.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#define BVH_NODE_BINDING 0
#define BVH_TRIANGLE_BINDING 1
#include "bvh_traverse.glsl"

struct ProbeRay {
    vec3 origin;
    float t_max;
    vec3 direction;
    uint skip_flags;
};

// 32 bytes. triangle_index 0xffffffff and t = -1 when there is no closest hit (or it was not asked for).
struct ProbeResult {
    float t;
    uint triangle_index;
    float barycentric_u;
    float barycentric_v;
    uint front_face;  // 0 or 1
    uint occluded;    // 0 or 1; 0 when the any-hit query was not asked for
    uint pad0;
    uint pad1;
};

layout(std430, set = 0, binding = 2) readonly buffer ProbeRays { ProbeRay rays[]; };
layout(std430, set = 0, binding = 3) writeonly buffer ProbeResults { ProbeResult results[]; };

const uint kQueryClosest = 1u;
const uint kQueryOccluded = 2u;

layout(push_constant) uniform ProbeParams {
    uint ray_count;
    uint queries;  // kQueryClosest | kQueryOccluded
} params;

void main() {
    uint ray_index = gl_GlobalInvocationID.x;
    if (ray_index >= params.ray_count) return;
    ProbeRay ray = rays[ray_index];

    ProbeResult result;
    result.t = -1.0;
    result.triangle_index = 0xffffffffu;
    result.barycentric_u = 0.0;
    result.barycentric_v = 0.0;
    result.front_face = 0u;
    result.occluded = 0u;
    result.pad0 = 0u;
    result.pad1 = 0u;
    if ((params.queries & kQueryClosest) != 0u) {
        BvhHit hit;
        if (bvhTraceClosest(ray.origin, ray.direction, ray.t_max, ray.skip_flags, hit)) {
            result.t = hit.t;
            result.triangle_index = hit.triangle_index;
            result.barycentric_u = hit.barycentric_u;
            result.barycentric_v = hit.barycentric_v;
            result.front_face = hit.front_face ? 1u : 0u;
        }
    }
    if ((params.queries & kQueryOccluded) != 0u)
        result.occluded = bvhOccluded(ray.origin, ray.direction, ray.t_max, ray.skip_flags) ? 1u : 0u;
    results[ray_index] = result;
}

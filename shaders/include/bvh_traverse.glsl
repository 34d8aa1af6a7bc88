// Software ray tracing against the baker's BVH (lavapipe has no ray queries, DESIGN.md 5). Same tests and
// same node visiting order as baker/src/bvh_cpu_trace.cpp; tests/test_bvh.cpp holds the two together.
//
// Usage: #define BVH_NODE_BINDING and BVH_TRIANGLE_BINDING (set 0 storage buffers), then include.
//   bool bvhTraceClosest(origin, direction, t_max, skip_flags, out BvhHit hit): closest hit, 0 < t < t_max.
//   bool bvhOccluded(origin, direction, t_max, skip_flags): any hit, 0 < t < t_max.
// Triangles with (flags & skip_flags) != 0 are ignored. Both faces are hit (no culling). t is in units of
// |direction|. hit.front_face = dot(cross(edge1, edge2), direction) < 0. Barycentrics: position =
// v0 + u*edge1 + v*edge2, attributes interpolate as (1-u-v)*a0 + u*a1 + v*a2 in the source vertex order.
// Rays must have finite components; the ray's origin should already be offset off the surface it leaves.
#ifndef GUSUKU_BVH_TRAVERSE_GLSL
#define GUSUKU_BVH_TRAVERSE_GLSL

#include "bvh_layout.glsl"

// The builder bounds the tree depth by kBvhMaxDepth (bvh.h), and nearest-first traversal pushes at most one
// node per level, so this stack cannot overflow on a BVH from buildBvh.
#define BVH_STACK_SIZE 64

struct BvhHit {
    float t;
    uint triangle_index;
    float barycentric_u;
    float barycentric_v;
    bool front_face;
};

// See bvh_cpu_trace.cpp for why: a 1e-7 barycentric overlap closes cracks between neighbours, and the far
// slab distance grows by 4 ulps so rounding never culls a box the ray touches.
const float kBvhBarycentricSlack = 1e-7;
const float kBvhSlabFarScale = 1.0 + 4.0 * 1.1920929e-7;
const float kBvhMiss = 3.0e38;  // "no entry": larger than any t_max the callers pass (they use <= 1e30)

// Zero (or denormal) direction components become a huge finite value of the direction's sign, so the slab
// test never multiplies 0 by inf.
vec3 bvhSafeInverse(vec3 direction) {
    vec3 magnitude = max(abs(direction), vec3(1e-20));
    vec3 signed_magnitude = mix(-magnitude, magnitude, greaterThanEqual(direction, vec3(0.0)));
    return 1.0 / signed_magnitude;
}

// Entry distance into a node's box, or kBvhMiss when the ray misses it or enters beyond t_limit.
float bvhSlabEntry(uint node_index, vec3 origin, vec3 inverse_direction, float t_limit) {
    vec3 t0 = (bvh_nodes[node_index].bounds_min - origin) * inverse_direction;
    vec3 t1 = (bvh_nodes[node_index].bounds_max - origin) * inverse_direction;
    vec3 t_small = min(t0, t1);
    vec3 t_large = max(t0, t1);
    float t_enter = max(max(t_small.x, t_small.y), max(t_small.z, 0.0));
    float t_exit = min(min(t_large.x, t_large.y), min(t_large.z, t_limit)) * kBvhSlabFarScale;
    return t_enter <= t_exit ? t_enter : kBvhMiss;
}

// Moller-Trumbore on (v0, edge1, edge2). Returns true with t, u, v when 0 < t < t_max.
bool bvhIntersectTriangle(BvhTriangle triangle, vec3 origin, vec3 direction, float t_max,
                          out float t, out float u, out float v) {
    t = 0.0;
    u = 0.0;
    v = 0.0;
    vec3 p = cross(direction, triangle.edge2);
    float determinant = dot(triangle.edge1, p);
    if (determinant == 0.0) return false;
    float inverse_determinant = 1.0 / determinant;
    vec3 to_origin = origin - triangle.v0;
    u = dot(to_origin, p) * inverse_determinant;
    if (!(u >= -kBvhBarycentricSlack && u <= 1.0 + kBvhBarycentricSlack)) return false;
    vec3 q = cross(to_origin, triangle.edge1);
    v = dot(direction, q) * inverse_determinant;
    if (!(v >= -kBvhBarycentricSlack && u + v <= 1.0 + kBvhBarycentricSlack)) return false;
    t = dot(triangle.edge2, q) * inverse_determinant;
    return t > 0.0 && t < t_max;
}

// One traversal for both queries: any_hit stops at the first accepted triangle. Nearest child first, the
// farther one on the stack. Loop shape "while-while" (Aila and Laine 2009, "Understanding the Efficiency of
// Ray Traversal on GPUs"): descend to a leaf, then test its triangles; on lavapipe, whose SIMD lanes run in
// step, this measured 0-20 % faster than one loop with an if (leaf) branch.
bool bvhTraverse(vec3 origin, vec3 direction, float t_max, uint skip_flags, bool any_hit, out BvhHit hit) {
    hit.t = t_max;
    hit.triangle_index = 0xffffffffu;
    hit.barycentric_u = 0.0;
    hit.barycentric_v = 0.0;
    hit.front_face = false;
    if (!(t_max > 0.0)) return false;

    vec3 inverse_direction = bvhSafeInverse(direction);
    if (bvhSlabEntry(0u, origin, inverse_direction, t_max) == kBvhMiss) return false;

    float t_closest = t_max;
    bool found = false;
    uint stack[BVH_STACK_SIZE];
    uint stack_size = 0u;
    uint node_index = 0u;
    const uint kNoNode = 0xffffffffu;
    while (node_index != kNoNode) {
        // Descend through inner nodes until a leaf (while-while: lanes of a SIMD group stay in step).
        while (bvh_nodes[node_index].triangle_count == 0u) {
            uint left = bvh_nodes[node_index].left_or_first;
            float t_left = bvhSlabEntry(left, origin, inverse_direction, t_closest);
            float t_right = bvhSlabEntry(left + 1u, origin, inverse_direction, t_closest);
            bool hit_left = t_left != kBvhMiss;
            bool hit_right = t_right != kBvhMiss;
            if (hit_left && hit_right) {
                bool left_first = t_left <= t_right;
                if (stack_size < uint(BVH_STACK_SIZE)) {
                    stack[stack_size] = left_first ? left + 1u : left;
                    ++stack_size;
                }
                node_index = left_first ? left : left + 1u;
            } else if (hit_left || hit_right) {
                node_index = hit_left ? left : left + 1u;
            } else if (stack_size == 0u) {
                node_index = kNoNode;
                break;
            } else {
                --stack_size;
                node_index = stack[stack_size];
            }
        }
        if (node_index == kNoNode) break;
        uint first = bvh_nodes[node_index].left_or_first;
        uint last = first + bvh_nodes[node_index].triangle_count;
        for (uint i = first; i < last; ++i) {
            BvhTriangle triangle = bvh_triangles[i];
            if ((triangle.flags & skip_flags) != 0u) continue;
            float t, u, v;
            if (!bvhIntersectTriangle(triangle, origin, direction, t_closest, t, u, v)) continue;
            found = true;
            t_closest = t;
            hit.t = t;
            hit.triangle_index = triangle.triangle_index;
            hit.barycentric_u = u;
            hit.barycentric_v = v;
            hit.front_face = dot(cross(triangle.edge1, triangle.edge2), direction) < 0.0;
            if (any_hit) return true;
        }
        if (stack_size == 0u) break;
        --stack_size;
        node_index = stack[stack_size];
    }
    return found;
}

bool bvhTraceClosest(vec3 origin, vec3 direction, float t_max, uint skip_flags, out BvhHit hit) {
    return bvhTraverse(origin, direction, t_max, skip_flags, false, hit);
}

bool bvhOccluded(vec3 origin, vec3 direction, float t_max, uint skip_flags) {
    BvhHit ignored;
    return bvhTraverse(origin, direction, t_max, skip_flags, true, ignored);
}

#endif

// Software ray tracing against the baker's BVH (lavapipe has no ray queries, docs/design.md 5). Same tests and
// same node visiting order as baker/src/bvh_cpu_trace.cpp; tests/test_bvh.cpp holds the two together, hit for
// hit and bit for bit.
//
// Usage: #define BVH_NODE_BINDING and BVH_TRIANGLE_BINDING (set 0 uniform texel buffers, bvh_layout.glsl),
// then include.
//   bool bvhTraceClosest(origin, direction, t_max, skip_flags, out BvhHit hit): closest hit, 0 < t < t_max.
//   bool bvhOccluded(origin, direction, t_max, skip_flags): any hit, 0 < t < t_max.
// Triangles with (flags & skip_flags) != 0 are ignored, and so are hits in the holes of alpha-masked triangles
// (bvh_alpha_mask.glsl). Both faces are hit (no culling). Among hits at exactly
// the same t, the one with the smallest source triangle index is the closest. t is in units of
// |direction|. hit.front_face = dot(cross(edge1, edge2), direction) < 0. Barycentrics: position =
// v0 + u*edge1 + v*edge2, attributes interpolate as (1-u-v)*a0 + u*a1 + v*a2 in the source vertex order.
// Rays must have finite components; the ray's origin should already be offset off the surface it leaves.
#ifndef GUSUKU_BVH_TRAVERSE_GLSL
#define GUSUKU_BVH_TRAVERSE_GLSL

#include "bvh_layout.glsl"
#include "bvh_alpha_mask.glsl"  // bvhHitIsOpaque: the alpha test of masked triangles

// The builder bounds the tree depth by kBvhMaxDepth (bvh.h), and nearest-first traversal pushes at most one
// child per inner level, so this stack cannot overflow on a BVH from buildBvh.
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

// Entry distance into the box [box_min, box_max], or kBvhMiss when the ray misses it or enters beyond t_limit.
float bvhSlabEntry(vec3 box_min, vec3 box_max, vec3 origin, vec3 inverse_direction, float t_limit) {
    vec3 t0 = (box_min - origin) * inverse_direction;
    vec3 t1 = (box_max - origin) * inverse_direction;
    vec3 t_small = min(t0, t1);
    vec3 t_large = max(t0, t1);
    float t_enter = max(max(t_small.x, t_small.y), max(t_small.z, 0.0));
    float t_exit = min(min(t_large.x, t_large.y), min(t_large.z, t_limit)) * kBvhSlabFarScale;
    return t_enter <= t_exit ? t_enter : kBvhMiss;
}

// Moller-Trumbore on (v0, edge1, edge2). Returns true with t, u, v when the ray meets the triangle at t > 0
// (the caller compares t with its closest hit).
bool bvhIntersectTriangle(vec3 v0, vec3 edge1, vec3 edge2, vec3 origin, vec3 direction,
                          out float t, out float u, out float v) {
    t = 0.0;
    u = 0.0;
    v = 0.0;
    vec3 p = cross(direction, edge2);
    float determinant = dot(edge1, p);
    if (determinant == 0.0) return false;
    float inverse_determinant = 1.0 / determinant;
    vec3 to_origin = origin - v0;
    u = dot(to_origin, p) * inverse_determinant;
    if (!(u >= -kBvhBarycentricSlack && u <= 1.0 + kBvhBarycentricSlack)) return false;
    vec3 q = cross(to_origin, edge1);
    v = dot(direction, q) * inverse_determinant;
    if (!(v >= -kBvhBarycentricSlack && u + v <= 1.0 + kBvhBarycentricSlack)) return false;
    t = dot(edge2, q) * inverse_determinant;
    return t > 0.0;
}

const uint kBvhNoReference = 0xffffffffu;  // a leaf reference of 7 triangles, which the builder never makes

// One traversal for both queries: any_hit stops at the first accepted triangle. Nearest child first, the
// farther one on the stack with its entry distance (skipped when popped beyond the closest hit). Loop shape
// "while-while" (Aila and Laine 2009, "Understanding the Efficiency of Ray Traversal on GPUs"): descend to a
// leaf, then test its triangles; on lavapipe, whose SIMD lanes run in step, this ran faster than one loop
// with an if (leaf) branch. lavapipe runs each storage-buffer load as a loop over the lanes, so
// the nodes and triangles are fetched from texel buffers: three per node (both children), three per triangle
// (bvh_layout.glsl).
// Ties: among hits at exactly equal t the smallest source triangle index wins, whatever the visiting order (a
// triangle referenced from several leaves gives the same t from each copy).
bool bvhTraverse(vec3 origin, vec3 direction, float t_max, uint skip_flags, bool any_hit, out BvhHit hit) {
    hit.t = t_max;
    hit.triangle_index = 0xffffffffu;
    hit.barycentric_u = 0.0;
    hit.barycentric_v = 0.0;
    hit.front_face = false;
    if (!(t_max > 0.0)) return false;

    vec3 inverse_direction = bvhSafeInverse(direction);
    float t_closest = t_max;
    uint closest_index = 0u;  // with t_closest = t_max, no triangle index is below it: a hit at t_max is refused
    bool found = false;
    uint stack_reference[BVH_STACK_SIZE];
    float stack_entry[BVH_STACK_SIZE];
    uint stack_size = 0u;
    uint reference = 0u;  // the root, an inner node
    while (reference != kBvhNoReference) {
        // Descend through inner nodes until a leaf (while-while: lanes of a SIMD group stay in step).
        while ((reference & BVH_CHILD_LEAF) == 0u) {
            uvec4 children_x = bvhNodeTexel(reference, 1u);
            vec3 min0, max0, min1, max1;
            bvhChildBoxes(bvhNodeTexel(reference, 0u), children_x, bvhNodeTexel(reference, 2u), min0, max0, min1,
                          max1);
            uint child0 = children_x.x;
            uint child1 = children_x.y;
            float t0 = bvhSlabEntry(min0, max0, origin, inverse_direction, t_closest);
            float t1 = bvhSlabEntry(min1, max1, origin, inverse_direction, t_closest);
            bool hit0 = t0 != kBvhMiss;
            bool hit1 = t1 != kBvhMiss;
            if (hit0 && hit1) {
                bool first0 = t0 <= t1;
                if (stack_size < uint(BVH_STACK_SIZE)) {
                    stack_reference[stack_size] = first0 ? child1 : child0;
                    if (!any_hit) stack_entry[stack_size] = first0 ? t1 : t0;
                    ++stack_size;
                }
                reference = first0 ? child0 : child1;
            } else if (hit0 || hit1) {
                reference = hit0 ? child0 : child1;
            } else {
                reference = kBvhNoReference;  // a dead end: pop below
            }
        }
        uint first = reference & BVH_LEAF_FIRST_MASK;
        uint last = reference == kBvhNoReference ? first : first + ((reference >> BVH_LEAF_COUNT_SHIFT) & 7u);
        for (uint i = first; i < last; ++i) {
            uvec4 edge1_flags = bvhTriangleTexel(i, 1u);
            if ((edge1_flags.w & skip_flags) != 0u) continue;
            uvec4 v0_index = bvhTriangleTexel(i, 0u);
            vec3 edge1 = uintBitsToFloat(edge1_flags.xyz);
            vec3 edge2 = uintBitsToFloat(bvhTriangleTexel(i, 2u).xyz);
            float t, u, v;
            if (!bvhIntersectTriangle(uintBitsToFloat(v0_index.xyz), edge1, edge2, origin, direction, t, u, v))
                continue;
            if (!(t < t_closest || (t == t_closest && v0_index.w < closest_index))) continue;
            if (BVH_ALPHA_MASKS && (edge1_flags.w & BVH_TRIANGLE_FLAG_ALPHA_MASKED) != 0u &&
                !bvhHitIsOpaque(v0_index.w, u, v))
                continue;
            found = true;
            t_closest = t;
            closest_index = v0_index.w;
            hit.triangle_index = v0_index.w;
            hit.t = t;
            hit.barycentric_u = u;
            hit.barycentric_v = v;
            hit.front_face = dot(cross(edge1, edge2), direction) < 0.0;
            if (any_hit) return true;
        }
        // Pop the nearest stacked child the ray may still reach before the closest hit. An any-hit query stops at
        // its first hit, so t_closest is still t_max and every stacked entry (at most t_max * kBvhSlabFarScale)
        // passes: its entries are neither stored nor read (any_hit is a constant where bvhOccluded inlines this,
        // so the compiler drops that array and the loop's test: fewer stores and gathers per node).
        reference = kBvhNoReference;
        while (stack_size > 0u) {
            --stack_size;
            if (any_hit || stack_entry[stack_size] <= t_closest * kBvhSlabFarScale) {
                reference = stack_reference[stack_size];
                break;
            }
        }
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

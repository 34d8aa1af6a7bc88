// CPU traversal of the GPU-layout BVH, written to mirror shaders/include/bvh_traverse.glsl (same slab test,
// same Moller-Trumbore, same nearest-child-first visiting order, same tie rule), so tests can hold the shader
// to it bit for bit.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>

#include "gusuku_bake/bvh.h"

namespace gusuku::bake {
namespace {

// Barycentric slack: adjacent triangles store their shared edge through different v0 and rounded edges, so
// an exact inside test can let a ray through the crack between them; a 1e-7 overlap closes it.
constexpr float kBarycentricSlack = 1e-7f;
// The far slab distance grows by 4 ulps so rounding in the box test cannot cull a box the ray touches
// (Ize 2013, "Robust BVH Ray Traversal").
constexpr float kSlabFarScale = 1.0f + 4.0f * 1.1920929e-7f;

glm::vec3 load(const float (&values)[3]) { return {values[0], values[1], values[2]}; }

// 1/direction with zero (or denormal) components replaced by a huge finite value of the same sign: the slab
// test then needs no special case and never computes 0 * inf.
glm::vec3 safeInverse(const glm::vec3& direction) {
    glm::vec3 inverse;
    for (int axis = 0; axis < 3; ++axis) {
        const float d = direction[axis];
        inverse[axis] = std::fabs(d) < 1e-20f ? std::copysign(1e20f, d) : 1.0f / d;
    }
    return inverse;
}

// Entry distance of the ray into the box, or +inf when it misses or enters beyond t_limit.
float slabEntry(const BvhBox& box, const glm::vec3& origin, const glm::vec3& inverse_direction, float t_limit) {
    const glm::vec3 t0 = (box.min - origin) * inverse_direction;
    const glm::vec3 t1 = (box.max - origin) * inverse_direction;
    const glm::vec3 t_small = glm::min(t0, t1);
    const glm::vec3 t_large = glm::max(t0, t1);
    const float t_enter = std::max(std::max(t_small.x, t_small.y), std::max(t_small.z, 0.0f));
    const float t_exit = std::min(std::min(t_large.x, t_large.y), std::min(t_large.z, t_limit)) * kSlabFarScale;
    return t_enter <= t_exit ? t_enter : std::numeric_limits<float>::infinity();
}

// Moller-Trumbore without the t_max test: true with t, u, v when the ray meets the triangle at t > 0.
bool intersectTriangleAhead(const BvhTriangleGpu& triangle, const glm::vec3& origin, const glm::vec3& direction,
                            float& t, float& u, float& v) {
    const glm::vec3 edge1 = load(triangle.edge1);
    const glm::vec3 edge2 = load(triangle.edge2);
    const glm::vec3 p = glm::cross(direction, edge2);
    const float determinant = glm::dot(edge1, p);
    if (determinant == 0.0f) return false;  // ray parallel to the plane: no culling, so only exact zero
    const float inverse_determinant = 1.0f / determinant;
    const glm::vec3 to_origin = origin - load(triangle.v0);
    u = glm::dot(to_origin, p) * inverse_determinant;
    // Written as !(inside) so that NaN (from a non-finite ray) counts as a miss.
    if (!(u >= -kBarycentricSlack && u <= 1.0f + kBarycentricSlack)) return false;
    const glm::vec3 q = glm::cross(to_origin, edge1);
    v = glm::dot(direction, q) * inverse_determinant;
    if (!(v >= -kBarycentricSlack && u + v <= 1.0f + kBarycentricSlack)) return false;
    t = glm::dot(edge2, q) * inverse_determinant;
    return t > 0.0f;
}

constexpr uint32_t kNoReference = 0xffffffffu;  // a leaf reference of 7 triangles, never built

template <bool kAnyHit>
bool traverse(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction, float t_max,
              uint32_t skip_flags, BvhHit& hit) {
    if (bvh.nodes.empty() || !(t_max > 0.0f)) return false;
    const glm::vec3 inverse_direction = safeInverse(direction);
    constexpr float kMiss = std::numeric_limits<float>::infinity();
    float t_closest = t_max;
    // With t_closest = t_max no triangle index is below closest_index: a hit at exactly t_max is refused.
    uint32_t closest_index = 0;
    bool found = false;
    uint32_t stack_reference[kBvhMaxDepth];
    float stack_entry[kBvhMaxDepth];
    uint32_t stack_size = 0;
    uint32_t reference = 0;  // the root, an inner node
    while (reference != kNoReference) {
        while ((reference & kBvhChildLeaf) == 0) {
            const BvhNodeGpu& node = bvh.nodes[reference];
            const float t0 = slabEntry(decodeBvhChildBox(node, 0), origin, inverse_direction, t_closest);
            const float t1 = slabEntry(decodeBvhChildBox(node, 1), origin, inverse_direction, t_closest);
            const bool hit0 = t0 != kMiss, hit1 = t1 != kMiss;
            if (hit0 && hit1) {
                const bool first0 = t0 <= t1;
                // kBvhMaxDepth bounds the tree depth, so the stack never overflows; the guard only keeps a
                // corrupt buffer from writing out of bounds.
                if (stack_size < kBvhMaxDepth) {
                    stack_reference[stack_size] = first0 ? node.child[1] : node.child[0];
                    if (!kAnyHit) stack_entry[stack_size] = first0 ? t1 : t0;
                    ++stack_size;
                }
                reference = first0 ? node.child[0] : node.child[1];
            } else if (hit0 || hit1) {
                reference = hit0 ? node.child[0] : node.child[1];
            } else {
                reference = kNoReference;
            }
        }
        if (reference != kNoReference) {
            const uint32_t first = bvhLeafFirst(reference), last = first + bvhLeafCount(reference);
            for (uint32_t i = first; i < last; ++i) {
                const BvhTriangleGpu& triangle = bvh.triangles[i];
                if (skip_flags != 0 && (triangle.flags & skip_flags) != 0) continue;
                float t, u, v;
                if (!intersectTriangleAhead(triangle, origin, direction, t, u, v)) continue;
                // Equal t: the smallest source triangle index wins, whatever order the nodes were visited in
                // and whichever of a triangle's references (bvh.h) was reached (copies give the same t, u, v).
                if (!(t < t_closest || (t == t_closest && triangle.triangle_index < closest_index))) continue;
                found = true;
                t_closest = t;
                closest_index = triangle.triangle_index;
                hit.t = t;
                hit.barycentric_u = u;
                hit.barycentric_v = v;
                hit.front_face =
                    glm::dot(glm::cross(load(triangle.edge1), load(triangle.edge2)), direction) < 0.0f;
                if (kAnyHit) return true;
            }
        }
        // The nearest stacked child the ray may still reach before the closest hit. Any-hit: t_closest is still
        // t_max, which every stacked entry passes, so entries are neither stored nor read (as in the GLSL).
        reference = kNoReference;
        while (stack_size > 0) {
            --stack_size;
            if (kAnyHit || stack_entry[stack_size] <= t_closest * kSlabFarScale) {
                reference = stack_reference[stack_size];
                break;
            }
        }
    }
    if (found) hit.triangle_index = closest_index;
    return found;
}

}  // namespace

BvhBox decodeBvhChildBox(const BvhNodeGpu& node, int child) {
    BvhBox box;
    for (int axis = 0; axis < 3; ++axis) {
        const uint32_t exponent_bits = ((node.exponents >> (8 * axis)) & 0xffu) << 23;
        float scale;
        std::memcpy(&scale, &exponent_bits, sizeof scale);
        const uint32_t shift = 16 * static_cast<uint32_t>(child);
        box.min[axis] = node.origin[axis] + static_cast<float>((node.quantised[2 * axis] >> shift) & 0xffffu) * scale;
        box.max[axis] =
            node.origin[axis] + static_cast<float>((node.quantised[2 * axis + 1] >> shift) & 0xffffu) * scale;
    }
    return box;
}

bool intersectTriangleCpu(const BvhTriangleGpu& triangle, const glm::vec3& origin, const glm::vec3& direction,
                          float t_max, float& t, float& u, float& v) {
    return intersectTriangleAhead(triangle, origin, direction, t, u, v) && t < t_max;
}

std::optional<BvhHit> traceClosestCpu(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction,
                                      float t_max, uint32_t skip_flags) {
    BvhHit hit;
    if (traverse<false>(bvh, origin, direction, t_max, skip_flags, hit)) return hit;
    return std::nullopt;
}

bool occludedCpu(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction, float t_max,
                 uint32_t skip_flags) {
    BvhHit hit;
    return traverse<true>(bvh, origin, direction, t_max, skip_flags, hit);
}

}  // namespace gusuku::bake

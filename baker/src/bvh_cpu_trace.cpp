// CPU traversal of the GPU-layout BVH, written to mirror shaders/include/bvh_traverse.glsl (same slab test,
// same Moller-Trumbore, same nearest-child-first visiting order), so tests can hold the shader to it.

#include <algorithm>
#include <cmath>
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

// Entry distance of the ray into the node's box, or +inf when it misses or enters beyond t_limit.
float slabEntry(const BvhNodeGpu& node, const glm::vec3& origin, const glm::vec3& inverse_direction,
                float t_limit) {
    const glm::vec3 t0 = (load(node.bounds_min) - origin) * inverse_direction;
    const glm::vec3 t1 = (load(node.bounds_max) - origin) * inverse_direction;
    const glm::vec3 t_small = glm::min(t0, t1);
    const glm::vec3 t_large = glm::max(t0, t1);
    const float t_enter = std::max(std::max(t_small.x, t_small.y), std::max(t_small.z, 0.0f));
    const float t_exit = std::min(std::min(t_large.x, t_large.y), std::min(t_large.z, t_limit)) * kSlabFarScale;
    return t_enter <= t_exit ? t_enter : std::numeric_limits<float>::infinity();
}

template <bool kAnyHit>
bool traverse(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction, float t_max,
              uint32_t skip_flags, BvhHit& hit) {
    if (bvh.nodes.empty() || !(t_max > 0.0f)) return false;
    const glm::vec3 inverse_direction = safeInverse(direction);
    float t_closest = t_max;
    bool found = false;
    uint32_t stack[kBvhMaxDepth];
    uint32_t stack_size = 0;
    if (slabEntry(bvh.nodes[0], origin, inverse_direction, t_closest) == std::numeric_limits<float>::infinity())
        return false;
    uint32_t node_index = 0;
    for (;;) {
        const BvhNodeGpu& node = bvh.nodes[node_index];
        if (node.triangle_count > 0) {
            for (uint32_t i = node.left_or_first; i < node.left_or_first + node.triangle_count; ++i) {
                const BvhTriangleGpu& triangle = bvh.triangles[i];
                if ((triangle.flags & skip_flags) != 0) continue;
                float t, u, v;
                if (!intersectTriangleCpu(triangle, origin, direction, t_closest, t, u, v)) continue;
                found = true;
                t_closest = t;
                hit.t = t;
                hit.triangle_index = triangle.triangle_index;
                hit.barycentric_u = u;
                hit.barycentric_v = v;
                hit.front_face =
                    glm::dot(glm::cross(load(triangle.edge1), load(triangle.edge2)), direction) < 0.0f;
                if (kAnyHit) return true;
            }
        } else {
            const uint32_t left = node.left_or_first;
            const float t_left = slabEntry(bvh.nodes[left], origin, inverse_direction, t_closest);
            const float t_right = slabEntry(bvh.nodes[left + 1], origin, inverse_direction, t_closest);
            const bool hit_left = t_left != std::numeric_limits<float>::infinity();
            const bool hit_right = t_right != std::numeric_limits<float>::infinity();
            if (hit_left && hit_right) {
                const bool left_first = t_left <= t_right;
                // kBvhMaxDepth bounds the tree depth, so the stack never overflows; the guard only keeps a
                // corrupt buffer from writing out of bounds.
                if (stack_size < kBvhMaxDepth) stack[stack_size++] = left_first ? left + 1 : left;
                node_index = left_first ? left : left + 1;
                continue;
            }
            if (hit_left || hit_right) {
                node_index = hit_left ? left : left + 1;
                continue;
            }
        }
        if (stack_size == 0) break;
        node_index = stack[--stack_size];
    }
    return found;
}

}  // namespace

bool intersectTriangleCpu(const BvhTriangleGpu& triangle, const glm::vec3& origin, const glm::vec3& direction,
                          float t_max, float& t, float& u, float& v) {
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
    return t > 0.0f && t < t_max;
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

#pragma once
// The baker's ray-tracing structure: a binary BVH built on the CPU with binned SAH and traversed in GLSL
// compute (shaders/include/bvh_traverse.glsl) from two storage buffers, because lavapipe has no ray queries
// or acceleration structures (DESIGN.md 5). The CPU traversal here mirrors the GLSL one operation for
// operation, so tests can compare the two and tools can trace a few rays without a GPU.
//
// Layout contract (std430, shared with bvh_traverse.glsl):
// - nodes[0] is the root. An inner node has triangle_count == 0 and left_or_first = index of its left
//   child; its right child is ALWAYS left_or_first + 1 (children are allocated in pairs).
//   A leaf has 1..kBvhMaxLeafTriangles triangles: triangles[left_or_first .. left_or_first+triangle_count).
// - An empty BVH (no usable triangle) is one leaf holding one placeholder triangle that no ray can hit
//   (zero edges, triangle_index kBvhNoTriangle), so both buffers are never empty and need no special case.
// - Node bounds are padded by ~1e-6 relative so that rounding in the triangle test never puts a hit just
//   outside its leaf's box. The tree depth is at most kBvhMaxDepth, so the GLSL stack cannot overflow.
// - Ray/triangle: Moller-Trumbore on (v0, edge1, edge2), both faces, hits with 0 < t < t_max.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/mesh.h"

namespace gusuku::bake {

/// Most triangles in one leaf.
inline constexpr uint32_t kBvhMaxLeafTriangles = 4;
/// triangle_index of the placeholder in an empty BVH (never reported as a hit).
inline constexpr uint32_t kBvhNoTriangle = 0xffffffffu;
/// Deepest node level (root = 1). Equals the GLSL traversal stack size (BVH_STACK_SIZE).
inline constexpr uint32_t kBvhMaxDepth = 64;

/// One BVH node as the GPU reads it (std430: vec3 + uint, vec3 + uint = 32 bytes).
struct BvhNodeGpu {
    float bounds_min[3];
    uint32_t left_or_first;   ///< inner: left child index (right = left + 1); leaf: first triangle index
    float bounds_max[3];
    uint32_t triangle_count;  ///< 0 for an inner node
};
static_assert(sizeof(BvhNodeGpu) == 32, "BvhNodeGpu must match the std430 layout in bvh_traverse.glsl");

/// One triangle in leaf order, pre-transformed for Moller-Trumbore (48 bytes, std430).
/// edge1 = p1 - p0 and edge2 = p2 - p0 in the ORIGINAL vertex order, so a hit's barycentrics (u, v)
/// interpolate vertex attributes as (1-u-v)*a0 + u*a1 + v*a2.
struct BvhTriangleGpu {
    float v0[3];
    uint32_t triangle_index;  ///< index of the triangle in the source TriangleMesh
    float edge1[3];
    uint32_t flags;           ///< the caller's per-triangle flags (0 when none were given)
    float edge2[3];
    float pad;
};
static_assert(sizeof(BvhTriangleGpu) == 48, "BvhTriangleGpu must match the std430 layout in bvh_traverse.glsl");

struct Bvh {
    std::vector<BvhNodeGpu> nodes;          ///< upload as-is to the node storage buffer
    std::vector<BvhTriangleGpu> triangles;  ///< upload as-is to the triangle storage buffer (never empty)
    size_t dropped_triangle_count = 0;      ///< zero-area or non-finite triangles left out
    uint32_t depth = 0;                     ///< levels in the tree (root only = 1)
};

/// Builds a binned-SAH BVH (16 bins, leaves of <= 4 triangles) over every triangle of `mesh`.
/// triangle_flags: one per triangle, or empty for all zero. Triangles with a zero-area cross product or a
/// non-finite vertex are dropped (counted in dropped_triangle_count). Cost: O(n log n), ~0.1 s per 100k
/// triangles on one core. Throws InputError("mesh", ...) for a vertex index out of range or a flag count
/// that does not match the triangle count.
Bvh buildBvh(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_flags);

/// A ray hit, as the GLSL BvhHit.
struct BvhHit {
    float t = 0.0f;               ///< distance along direction, in units of |direction|
    uint32_t triangle_index = 0;  ///< index in the source mesh
    float barycentric_u = 0.0f;   ///< weight of the triangle's second vertex
    float barycentric_v = 0.0f;   ///< weight of the triangle's third vertex
    bool front_face = false;      ///< dot(cross(edge1, edge2), direction) < 0 (counter-clockwise side seen)
};

/// Closest hit with 0 < t < t_max, ignoring triangles with (flags & skip_flags) != 0. No back-face culling.
std::optional<BvhHit> traceClosestCpu(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction,
                                      float t_max, uint32_t skip_flags = 0);

/// True if any triangle not skipped is hit with 0 < t < t_max (stops at the first one found).
bool occludedCpu(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& direction, float t_max,
                 uint32_t skip_flags = 0);

/// The single ray/triangle test both traversals use (exposed so tests can brute-force against it).
/// Returns true and fills t, u, v when the ray hits the triangle with 0 < t < t_max.
bool intersectTriangleCpu(const BvhTriangleGpu& triangle, const glm::vec3& origin, const glm::vec3& direction,
                          float t_max, float& t, float& u, float& v);

}  // namespace gusuku::bake

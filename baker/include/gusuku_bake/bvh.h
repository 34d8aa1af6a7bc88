#pragma once
// The baker's ray-tracing structure: a binary BVH built on the CPU with binned SAH and traversed in GLSL
// compute (shaders/include/bvh_traverse.glsl) from two uniform texel buffers, because lavapipe has no ray queries
// or acceleration structures (docs/design.md 5). The CPU traversal here mirrors the GLSL one operation for
// operation, so tests can compare the two and tools can trace a few rays without a GPU.
//
// Layout contract (std430, shared with bvh_layout.glsl, which reads both arrays as RGBA32UI texels). Why this
// shape: the traversal's cost on lavapipe is mostly the number of load instructions per node and per triangle
// (a storage-buffer load of a divergent address ran as an 8-iteration loop of scalar loads, whatever its width
// up to 16 bytes; a texel fetch gathers the lanes in vector code). Both children's boxes, quantised to 16 bits on the parent's grid, and the child references fit in
// three 16-byte texels per node visit (the float layout of one box per node took six); a triangle is three.
// - nodes[0] is the root. Every node is an inner node with two children, each given by a child reference
//   (kBvhChildLeaf set: a leaf of bvhLeafCount(ref) triangles from bvhLeafFirst(ref), 0..kBvhMaxLeafTriangles;
//   else: the index of an inner node) and a box quantised to 16 bits per face on the node's grid
//   (decodeBvhChildBox). A tree of one leaf is a root whose second child is an empty leaf.
// - An empty BVH (no usable triangle) is a root with one leaf holding one placeholder triangle that no ray can
//   hit (zero edges, triangle_index kBvhNoTriangle), so both buffers are never empty and need no special case.
// - A leaf slot in `triangles` is a reference to a source triangle. Spatial splits reference one triangle from
//   several leaves (never twice in one leaf; at most 2 x as many slots as usable triangles), each leaf's box
//   holding only the triangle's piece on its side of the split; every point of the triangle is inside the boxes
//   down to at least one of its leaves. The copies are identical, so each gives the same t, u, v.
// - Child boxes enclose the child's triangles (or pieces) padded by ~1e-6 of the triangle's and of the box's
//   largest coordinate, so that rounding in the triangle test never puts a hit just outside its leaf's box; the
//   decoded (quantised) box always encloses the padded one. The tree depth is at most kBvhMaxDepth, so the
//   GLSL stack cannot overflow.
// - Ray/triangle: Moller-Trumbore on (v0, edge1, edge2), both faces, hits with 0 < t < t_max. The closest hit
//   is the triangle with the smallest t; among exactly equal t, the one with the smallest triangle_index. So the
//   answer depends neither on the order the traversal visits nodes in nor on the tree: a leaf whose box the
//   ray enters beyond the closest hit may or may not be visited, but every triangle hit at the closest t has a
//   leaf whose box holds the hit point, which is always visited. (A rule by slot in `triangles` would break
//   with references: whether a tying triangle's first slot is reached would depend on the visiting order.)

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake {

/// Most triangles in one leaf.
inline constexpr uint32_t kBvhMaxLeafTriangles = 4;
/// triangle_index of the placeholder in an empty BVH (never reported as a hit).
inline constexpr uint32_t kBvhNoTriangle = 0xffffffffu;
/// Most usable triangles in one BVH: the median splits below depth 40 then stay within kBvhMaxDepth.
inline constexpr uint32_t kBvhMaxTriangles = 1u << 24;
/// Deepest node level (root = 1). Equals the GLSL traversal stack size (BVH_STACK_SIZE).
inline constexpr uint32_t kBvhMaxDepth = 64;

/// Child reference flag: the child is a leaf (else an inner node index).
inline constexpr uint32_t kBvhChildLeaf = 0x80000000u;
inline constexpr uint32_t kBvhLeafCountShift = 28;  ///< leaf reference: bits 28..30 hold the triangle count
inline constexpr uint32_t kBvhLeafFirstMask = (1u << kBvhLeafCountShift) - 1u;  ///< bits 0..27: first triangle
inline uint32_t bvhLeafCount(uint32_t ref) { return (ref >> kBvhLeafCountShift) & 7u; }
inline uint32_t bvhLeafFirst(uint32_t ref) { return ref & kBvhLeafFirstMask; }

/// One inner BVH node as the GPU reads it (std430, three 16-byte words). Child c's box on axis a is
///   min = origin[a] + float(half(quantised[2a], c))     * scale[a]
///   max = origin[a] + float(half(quantised[2a + 1], c)) * scale[a]
/// (half(w, c): bits 16c..16c+15 of w) with scale[a] = 2^(byte(exponents, a) - 127), the float whose exponent
/// bits are that byte. The product is exact (16-bit integer times a power of two), so only the sum rounds, the
/// same on the CPU and in GLSL.
struct BvhNodeGpu {
    float origin[3];
    uint32_t exponents;     ///< bytes 0..2: biased float exponents of the x, y, z grid steps
    uint32_t child[2];      ///< child references (kBvhChildLeaf | count << 28 | first, or an inner node index)
    uint32_t quantised[6];  ///< per axis: mins of children 0 and 1 (low, high 16 bits), then their maxima
};
static_assert(sizeof(BvhNodeGpu) == 48, "BvhNodeGpu must match the std430 layout in bvh_layout.glsl");

/// An axis-aligned box in float.
struct BvhBox {
    glm::vec3 min;
    glm::vec3 max;
};

/// Child `child` (0 or 1) of `node`'s box as the traversal decodes it (GLSL bvhChildBoxes does the same).
BvhBox decodeBvhChildBox(const BvhNodeGpu& node, int child);

/// One leaf slot (a reference to a triangle), pre-transformed for Moller-Trumbore (48 bytes, std430).
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
    std::vector<BvhNodeGpu> nodes;          ///< upload as-is to the node texel buffer
    std::vector<BvhTriangleGpu> triangles;  ///< leaf slots (references) in leaf order, upload as-is to the
                                            ///< triangle texel buffer (never empty; up to 2 x the triangles)
    size_t dropped_triangle_count = 0;      ///< zero-area or non-finite triangles left out
    uint32_t depth = 0;                     ///< levels in the tree, leaves included (one leaf under the root = 2)
};

/// Builds a binned-SAH BVH with spatial splits (SBVH: 32 object bins, 16 spatial bins, leaves of <= 4
/// references) over every triangle of `mesh`. Up to kBvhMaxTriangles usable triangles (more throws InputError;
/// a device's maxTexelBufferElements may cap lower, and the triangle buffer holds up to 2 slots a triangle).
/// triangle_flags: one per triangle, or empty for all zero. Triangles with a zero-area cross product or a
/// non-finite vertex are dropped (counted in dropped_triangle_count). Deterministic (the same mesh gives the
/// same bytes). Cost: O(n log n) on one core; the spatial split search is most of it. Throws InputError("mesh", ...) for a vertex index out of range or a
/// flag count that does not match the triangle count.
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
/// Ties (equal t) go to the smallest triangle_index.
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

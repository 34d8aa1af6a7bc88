// The BVH's two storage buffers, in the std430 layout of baker/include/gusuku_bake/bvh.h (BvhNodeGpu,
// BvhTriangleGpu). The includer #defines BVH_NODE_BINDING and BVH_TRIANGLE_BINDING (set 0) first.
// Node: an inner node with two children, each a child reference (BVH_CHILD_LEAF set: a leaf of
// (ref >> 28) & 7 triangles from ref & 0x0fffffff; else an inner node index) and a box quantised to 16 bits on
// the node's grid (bvhChildBoxes). nodes[0] is the root.
// Why 16-byte members: lavapipe runs each storage-buffer load instruction as a loop over its SIMD lanes, one
// scalar load per lane, whatever the width up to 16 bytes; so a node is three uvec4 loads and a triangle
// three vec4 loads, with nothing loaded that the traversal does not use.
#ifndef GUSUKU_BVH_LAYOUT_GLSL
#define GUSUKU_BVH_LAYOUT_GLSL

#if !defined(BVH_NODE_BINDING) || !defined(BVH_TRIANGLE_BINDING)
#error "#define BVH_NODE_BINDING and BVH_TRIANGLE_BINDING before including the BVH"
#endif

struct BvhNode {
    uvec4 origin_exponents;  // xyz: the grid origin (float bits); w: bytes 0..2, biased exponents of the steps
    uvec4 children_x;        // x, y: child references; z: x minima of children 0 | 1 << 16; w: x maxima
    uvec4 quantised_yz;      // y minima, y maxima, z minima, z maxima, each child 0 | child 1 << 16
};

const uint BVH_CHILD_LEAF = 0x80000000u;
const uint BVH_LEAF_COUNT_SHIFT = 28u;
const uint BVH_LEAF_FIRST_MASK = 0x0fffffffu;

// edge1 = p1 - p0, edge2 = p2 - p0 in the source triangle's vertex order; triangle_index is its index in the
// source mesh.
struct BvhTriangle {
    vec4 v0_index;     // xyz: v0; w: triangle_index (uint bits)
    vec4 edge1_flags;  // xyz: edge1; w: flags (uint bits)
    vec4 edge2_pad;    // xyz: edge2
};

layout(std430, set = 0, binding = BVH_NODE_BINDING) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = BVH_TRIANGLE_BINDING) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };

// Both children's boxes of a node whose first two loads are given: origin + q * 2^(exponent - 127) per axis.
// The product is exact (16-bit integer times a power of two), so only the sum rounds, as in decodeBvhChildBox.
void bvhChildBoxes(uvec4 origin_exponents, uvec4 children_x, uvec4 quantised_yz, out vec3 min0, out vec3 max0,
                   out vec3 min1, out vec3 max1) {
    vec3 grid_origin = uintBitsToFloat(origin_exponents.xyz);
    uint exponents = origin_exponents.w;
    vec3 scale = uintBitsToFloat(uvec3(exponents & 0xffu, (exponents >> 8u) & 0xffu, (exponents >> 16u) & 0xffu) << 23u);
    uvec3 minima = uvec3(children_x.z, quantised_yz.x, quantised_yz.z);
    uvec3 maxima = uvec3(children_x.w, quantised_yz.y, quantised_yz.w);
    min0 = grid_origin + vec3(minima & 0xffffu) * scale;
    min1 = grid_origin + vec3(minima >> 16u) * scale;
    max0 = grid_origin + vec3(maxima & 0xffffu) * scale;
    max1 = grid_origin + vec3(maxima >> 16u) * scale;
}

#endif

// The BVH's two buffers, in the std430 layout of baker/include/gusuku_bake/bvh.h (BvhNodeGpu, BvhTriangleGpu),
// read as uniform texel buffers of RGBA32UI texels (16 bytes each). The includer #defines BVH_NODE_BINDING and
// BVH_TRIANGLE_BINDING (set 0) first, and binds views of format VK_FORMAT_R32G32B32A32_UINT there.
// Node: an inner node with two children, each a child reference (BVH_CHILD_LEAF set: a leaf of
// (ref >> 28) & 7 triangles from ref & 0x0fffffff; else an inner node index) and a box quantised to 16 bits on
// the node's grid (bvhChildBoxes). nodes[0] is the root.
// Why texel buffers of 16-byte texels: lavapipe runs each storage-buffer load instruction at a per-lane address
// as a loop over its SIMD lanes, one scalar load per lane (whatever the width up to 16 bytes), while texelFetch
// gathers all lanes in straight-line vector code. So a node is three texel fetches and a triangle three, with
// nothing fetched that the traversal does not use; the uint view returns the stored bits exactly.
#ifndef GUSUKU_BVH_LAYOUT_GLSL
#define GUSUKU_BVH_LAYOUT_GLSL

#if !defined(BVH_NODE_BINDING) || !defined(BVH_TRIANGLE_BINDING)
#error "#define BVH_NODE_BINDING and BVH_TRIANGLE_BINDING before including the BVH"
#endif

// Texels of one node (BvhNodeGpu): node * 3 + 0: origin_exponents, xyz the grid origin (float bits), w bytes
// 0..2 the biased exponents of the steps; + 1: children_x, x, y the child references, z the x minima of
// children 0 | 1 << 16, w the x maxima; + 2: quantised_yz, the y minima, y maxima, z minima, z maxima, each
// child 0 | child 1 << 16.
const uint BVH_NODE_TEXELS = 3u;

const uint BVH_CHILD_LEAF = 0x80000000u;
const uint BVH_LEAF_COUNT_SHIFT = 28u;
const uint BVH_LEAF_FIRST_MASK = 0x0fffffffu;

// Texels of one triangle (BvhTriangleGpu), edge1 = p1 - p0, edge2 = p2 - p0 in the source triangle's vertex
// order: triangle * 3 + 0: v0 (xyz, float bits), w the source mesh's triangle_index; + 1: edge1, w the flags;
// + 2: edge2.
const uint BVH_TRIANGLE_TEXELS = 3u;

#ifdef TRACE_INPUTS_STORAGE_BUFFERS
// The kernels' storage-buffer variant (trace_inputs_gpu.h, TraceInputKind): the same 16-byte words read from
// storage buffers, for a scene that holds more texels than the device's maxTexelBufferElements (65536 on many
// phones and SwiftShader). The loads return the same bits, so both variants compute the same results.
layout(std430, set = 0, binding = BVH_NODE_BINDING) readonly buffer BvhNodeWords { uvec4 bvh_node_words[]; };
layout(std430, set = 0, binding = BVH_TRIANGLE_BINDING) readonly buffer BvhTriangleWords { uvec4 bvh_triangle_words[]; };

uvec4 bvhNodeTexel(uint node, uint word) { return bvh_node_words[node * BVH_NODE_TEXELS + word]; }
uvec4 bvhTriangleTexel(uint triangle, uint word) { return bvh_triangle_words[triangle * BVH_TRIANGLE_TEXELS + word]; }
#else
layout(set = 0, binding = BVH_NODE_BINDING) uniform usamplerBuffer bvh_node_texels;
layout(set = 0, binding = BVH_TRIANGLE_BINDING) uniform usamplerBuffer bvh_triangle_texels;

uvec4 bvhNodeTexel(uint node, uint word) { return texelFetch(bvh_node_texels, int(node * BVH_NODE_TEXELS + word)); }
uvec4 bvhTriangleTexel(uint triangle, uint word) {
    return texelFetch(bvh_triangle_texels, int(triangle * BVH_TRIANGLE_TEXELS + word));
}
#endif

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

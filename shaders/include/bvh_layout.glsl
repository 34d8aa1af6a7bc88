// The BVH's two storage buffers, in the std430 layout of baker/include/gusuku_bake/bvh.h (BvhNodeGpu,
// BvhTriangleGpu). The includer #defines BVH_NODE_BINDING and BVH_TRIANGLE_BINDING (set 0) first.
// Node: inner when triangle_count == 0, children at left_or_first and left_or_first + 1; leaf: triangles
// [left_or_first, left_or_first + triangle_count). nodes[0] is the root.
#ifndef GUSUKU_BVH_LAYOUT_GLSL
#define GUSUKU_BVH_LAYOUT_GLSL

#if !defined(BVH_NODE_BINDING) || !defined(BVH_TRIANGLE_BINDING)
#error "#define BVH_NODE_BINDING and BVH_TRIANGLE_BINDING before including the BVH"
#endif

struct BvhNode {
    vec3 bounds_min;
    uint left_or_first;
    vec3 bounds_max;
    uint triangle_count;
};

// edge1 = p1 - p0, edge2 = p2 - p0 in the source triangle's vertex order; triangle_index is its index in the
// source mesh.
struct BvhTriangle {
    vec3 v0;
    uint triangle_index;
    vec3 edge1;
    uint flags;
    vec3 edge2;
    float pad;
};

layout(std430, set = 0, binding = BVH_NODE_BINDING) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = BVH_TRIANGLE_BINDING) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };

#endif

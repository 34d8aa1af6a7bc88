// The alpha test at a BVH hit (glTF alphaMode MASK, issue 21 item 3): a triangle flagged
// BVH_TRIANGLE_FLAG_ALPHA_MASKED (baker/include/gusuku_bake/trace_scene.h, kTriangleFlagAlphaMasked) is a hole
// where its base colour's alpha (factor times the texture's, bilinear at the hit's uv0) is below the material's
// cutoff: bvhTraverse skips such a hit, so bounces, sun and sky shadow rays and camera rays all pass through.
// Only a scene with a masked triangle compiles the test in (BVH_ALPHA_MASKS below), and only flagged triangles run
// it; an opaque scene traces exactly as without it.
//
// With SHADING_TRIANGLE_BINDING defined (the includer traces a scene with materials: the bake and camera
// kernels), the test reads scene_shading.glsl's buffers; without (a probe of the BVH alone) every hit is opaque.
// The CPU traversal (baker/src/bvh_cpu_trace.cpp) has no alpha test yet: docs/baker.md says where that shows.
#ifndef GUSUKU_BVH_ALPHA_MASK_GLSL
#define GUSUKU_BVH_ALPHA_MASK_GLSL

const uint BVH_TRIANGLE_FLAG_ALPHA_MASKED = 2u;

// Set by the tracer (traceKernelSpecialization, baker/include/gusuku_bake/trace_inputs_gpu.h) only for a scene
// with a masked triangle. Why a specialisation constant and not the flag test alone: llvmpipe runs a branch's
// body masked for the whole SIMD group even when no lane takes it, so the alpha test's fetches inside the
// traversal loop cost every candidate hit (the opaque sample traced 1.6x slower); a false constant folds the
// test away, and an opaque scene runs the kernel it ran before masks existed.
layout(constant_id = 0) const bool BVH_ALPHA_MASKS = false;

#ifdef SHADING_TRIANGLE_BINDING
#include "scene_shading.glsl"

bool bvhHitIsOpaque(uint triangle_index, float barycentric_u, float barycentric_v) {
    TriangleShadingGpu shading = loadTriangleShading(triangle_index);
    MaterialGpu material = loadMaterial(floatBitsToUint(shading.normal2_material.w));
    float alpha = material.base_color_factor.a;
    if (material.texture_info.z > 0u) {
        float w0 = 1.0 - barycentric_u - barycentric_v;
        vec2 uv = w0 * vec2(shading.normal0_u0.w, shading.normal1_v0.w) +
                  barycentric_u * shading.uv0_vertex1_vertex2.xy + barycentric_v * shading.uv0_vertex1_vertex2.zw;
        alpha *= sampleBaseColorAlpha(material.texture_info, uv);
    }
    return alpha >= materialAlphaCutoff(material);
}
#else
bool bvhHitIsOpaque(uint triangle_index, float barycentric_u, float barycentric_v) { return true; }
#endif

#endif

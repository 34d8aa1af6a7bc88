#pragma once
// Which alpha-masked triangles can show a hole to the tracer. A masked material's flag makes every hit on its
// triangles run the alpha test (shaders/include/bvh_alpha_mask.glsl: a texture fetch and a bilinear mix inside the
// traversal loop), and a masked material may cover far more than its cut-outs (an atlas marked MASK for one
// foliage card). A triangle whose bilinear footprint reads no texel below the cutoff can never be a hole, so it
// need not be tested. (On the shared house 3,269 of 4,462 masked triangles do read one: docs/measurements.md.)

#include <cstdint>
#include <vector>

#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

/// The triangle flags with kTriangleFlagAlphaMasked kept only where a hit may be a hole: a flagged triangle keeps
/// it unless base_color_factor.a times every texel its bilinear lookups can read (the texels whose read square its uv0 triangle meets,
/// plus the neighbour each lookup mixes, wrapped as the shader wraps) is at or above its material's cutoff. Exact
/// for the tracer: the test skipped is one that would have passed, so every hit and every bake byte stays the
/// same. `shading` is what the tracer uploads (packSceneShading: the texture as downsampled, its 8-bit alpha).
/// A triangle with non-finite uv0 keeps its flag.
std::vector<uint32_t> narrowAlphaMaskFlags(const PackedSceneShading& shading,
                                           const std::vector<uint32_t>& triangle_flags);

}  // namespace gusuku::bake

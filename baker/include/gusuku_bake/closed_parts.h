#pragma once
// Which triangles bound a closed part of a mesh, so that seeing one from behind is evidence of being inside
// geometry. A double-sided material shows both sides of its faces: the back of an open sheet (a roof of one
// layer, a fence, a leaf) is its other visible side, and a texel that sees it is in the open. Only a face of a
// watertight part whose winding faces outward has an inside, where a texel is hidden (texel validity, docs/baker.md
// "Invalid texels"). Vertices are welded by position (glTF splits them at UV and normal seams).

#include <cstdint>
#include <vector>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake {

/// Positions closer than this (metres, per axis on a grid) are one vertex for closure.
inline constexpr float kClosedPartWeldM = 1e-5f;

/// Per triangle of `mesh`: true when it belongs to a closed, outward-wound part: a set of triangles joined by
/// edges (after welding) in which every edge is shared by exactly two triangles that run it in opposite
/// directions, enclosing a positive signed volume. Degenerate triangles (two corners welded) are never closed and
/// are skipped when deciding a part's closure. O(n) expected (hashing).
std::vector<bool> closedOutwardTriangles(const TriangleMesh& mesh);

}  // namespace gusuku::bake

#pragma once
// The bake set's occluder (docs/bakeset.md, docs/design.md 8 pass 4): the site's SfM mesh simplified to what a
// depth-only pass needs, so real walls in front of the building hide it. Positions and indices only.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace gusuku::bake {

/// The simplifier's error bound for the occluder, metres. The depth test only needs silhouettes and depths
/// right, and the SfM mesh itself is no truer than a few centimetres; 2 cm is 2 pixels at 10 m in the runtime's
/// default 1280-wide frame with a phone's ~1000-pixel focal length, and below 1 pixel from 20 m on.
inline constexpr double kOccluderTargetErrorM = 0.02;

struct OccluderMesh {
    std::vector<glm::vec3> positions;  ///< ENU metres, only the vertices the triangles use
    std::vector<uint32_t> indices;     ///< three per triangle, the source's winding
    size_t source_triangles = 0;       ///< triangles handed in
    double error_m = 0.0;              ///< the simplifier's estimate of the error it reached, metres

    size_t triangleCount() const { return indices.size() / 3; }
};

/// Welds exactly coincident vertices (a glTF loader un-shares corners where normals or UVs differ, which the
/// simplifier would see as cracks), then simplifies with meshoptimizer's edge-collapse simplifier until the
/// next collapse would move the surface by more than target_error_m (open borders stay in place), then orders
/// for the vertex cache and compacts the vertices. `indices` index `positions` (three per triangle; only the
/// vertices they use are kept). Deterministic: the same input gives the same output.
OccluderMesh simplifyOccluder(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                              double target_error_m = kOccluderTargetErrorM);

}  // namespace gusuku::bake

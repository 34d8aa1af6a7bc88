// simplifyOccluder (gusuku_bake/occluder.h) through meshoptimizer: weld, simplify to an error bound, reorder.
#include "gusuku_bake/occluder.h"

#include <stdexcept>
#include <string>

#include <meshoptimizer.h>

namespace gusuku::bake {

OccluderMesh simplifyOccluder(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                              double target_error_m) {
    if (indices.size() % 3 != 0) throw std::invalid_argument("simplifyOccluder: index count is not a multiple of 3");
    for (const uint32_t index : indices)
        if (index >= positions.size())
            throw std::invalid_argument("simplifyOccluder: index " + std::to_string(index) + " out of range");
    OccluderMesh result;
    result.source_triangles = indices.size() / 3;
    if (indices.empty()) return result;

    // Weld by position alone: vertices the loader split for normals, UVs or materials become one again.
    std::vector<uint32_t> remap(positions.size());
    const size_t welded_count = meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(),
                                                            positions.data(), positions.size(), sizeof(glm::vec3));
    std::vector<glm::vec3> welded(welded_count);
    meshopt_remapVertexBuffer(welded.data(), positions.data(), positions.size(), sizeof(glm::vec3), remap.data());
    std::vector<uint32_t> welded_indices(indices.size());
    meshopt_remapIndexBuffer(welded_indices.data(), indices.data(), indices.size(), remap.data());

    // meshoptimizer's error is relative to the mesh's extent: metres divided by its scale.
    const float scale = meshopt_simplifyScale(&welded[0].x, welded.size(), sizeof(glm::vec3));
    const float relative_target = scale > 0.0f ? float(target_error_m / double(scale)) : 0.0f;
    std::vector<uint32_t> simplified(welded_indices.size());
    float relative_error = 0.0f;
    // Target count 0: collapse as far as the error bound allows.
    const size_t index_count =
        meshopt_simplify(simplified.data(), welded_indices.data(), welded_indices.size(), &welded[0].x, welded.size(),
                         sizeof(glm::vec3), 0, relative_target, 0, &relative_error);
    simplified.resize(index_count);
    result.error_m = double(relative_error) * double(scale);

    meshopt_optimizeVertexCache(simplified.data(), simplified.data(), simplified.size(), welded.size());
    result.positions.resize(welded.size());
    const size_t used = meshopt_optimizeVertexFetch(result.positions.data(), simplified.data(), simplified.size(),
                                                    welded.data(), welded.size(), sizeof(glm::vec3));
    result.positions.resize(used);
    result.indices = std::move(simplified);
    return result;
}

}  // namespace gusuku::bake

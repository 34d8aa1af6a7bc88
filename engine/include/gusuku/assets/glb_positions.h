#pragma once
// A bare triangle mesh (positions and indices, no normals, UVs or materials) as a .glb: the bake set's
// occluder.glb (docs/bakeset.md), which the runtime draws into depth only. Read it back with loadGltf
// (gusuku/assets/gltf_loader.h). Part of gusuku_assets.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace gusuku {

/// Writes one primitive with POSITION (with its bounds) and 32-bit indices, positions converted by
/// model_from_enu (for a bake set: inverse(enuFromGltfYUp())); a transform that mirrors flips the winding so the
/// front faces stay front faces. No material: a glTF reader gives it the default one. Atomic
/// (gusuku/assets/atomic_file.h). Throws std::invalid_argument for an index count that is not a multiple of 3 or an
/// index out of range; the same mesh always gives the same bytes.
void writePositionsGlb(const std::string& path, const std::vector<glm::vec3>& positions_enu,
                       const std::vector<uint32_t>& indices, const glm::dmat4& model_from_enu);

}  // namespace gusuku

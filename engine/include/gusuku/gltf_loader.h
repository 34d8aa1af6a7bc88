#pragma once
// glTF 2.0 (.gltf or .glb) through tinygltf, flattened into one TriangleMesh in ENU. Images are decoded by
// OpenImageIO (never by tinygltf's built-in loader).

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gusuku/mesh.h"

namespace gusuku {

struct GltfLoadOptions {
    /// Applied to positions after the node hierarchy: model coordinates -> ENU metres. For a building this is
    /// placement * enuFromGltfYUp(); for an SfM mesh it is site.json's similarity transform as given.
    glm::dmat4 enu_from_model{1.0};
    /// Textures larger than this on either side are box-downsampled on load (the bake needs albedo, not
    /// detail). 0 keeps full size.
    int max_texture_size = 0;
};

/// The glTF Y-up to ENU axis change: glTF (x, y, z) -> ENU (x, -z, y).
glm::dmat4 enuFromGltfYUp();

/// Loads every triangle primitive of the default scene (all scenes' roots if none is default).
/// Checks what it reads: accessor and index ranges, NaN or infinite positions, missing attributes. Missing
/// texture files fall back to the material's factor and add a warning to `warnings` (if not null). Bad input
/// throws InputError naming the file and the glTF element ("meshes[2].primitives[0].indices").
/// Missing normals are computed per face (flat). Non-triangle primitives are skipped with a warning.
TriangleMesh loadGltf(const std::string& path, const GltfLoadOptions& options,
                      std::vector<std::string>* warnings = nullptr);

/// Writes a TriangleMesh as a .glb (positions converted back ENU -> glTF Y-up by `gltf_from_enu`), with its
/// materials and textures (PNG-encoded, embedded). Used by the sample-site generator. Atomic.
void writeGlb(const std::string& path, const TriangleMesh& mesh, const glm::dmat4& model_from_enu);

}  // namespace gusuku

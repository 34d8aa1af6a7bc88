#pragma once
// glTF 2.0 (.gltf or .glb) through tinygltf, flattened into one TriangleMesh in ENU. Images are decoded by
// OpenImageIO (never by tinygltf's built-in loader).

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku {

/// Scene size limits, checked on the node hierarchy before anything is expanded or read: nodes used by several
/// parents repeat their subtree, so a file of a few kilobytes can describe billions of triangles. At the default
/// limits the flattened mesh takes at most about 0.6 GB (40 bytes per vertex, 16 per triangle).
constexpr uint64_t kMaxGltfInstancedTriangles = uint64_t(1) << 22;  ///< 4,194,304 triangles after instancing
constexpr uint64_t kMaxGltfInstancedVertices = 3 * kMaxGltfInstancedTriangles;  ///< 12,582,912 vertices
constexpr uint64_t kMaxNodeInstances = uint64_t(1) << 20;  ///< node visits after instancing, meshes or not

struct GltfLoadOptions {
    /// Applied to positions after the node hierarchy: model coordinates -> ENU metres. For a building this is
    /// placement * enuFromGltfYUp(); for an SfM mesh it is site.json's similarity transform as given.
    glm::dmat4 enu_from_model{1.0};
    /// Textures larger than this on either side are box-downsampled while they are decoded (the bake needs
    /// albedo, not detail). 0 or more than kMaxImageSide (8192, gusuku/assets/image.h) means kMaxImageSide.
    int max_texture_size = 0;
    /// The flattened scene's limits (counted from accessor counts with every instance, before expansion); a
    /// larger scene is an InputError naming the limit. A primitive without normals counts one vertex per corner.
    uint64_t max_instanced_triangles = kMaxGltfInstancedTriangles;
    uint64_t max_instanced_vertices = kMaxGltfInstancedVertices;
};

/// The glTF Y-up to ENU axis change: glTF (x, y, z) -> ENU (x, -z, y).
glm::dmat4 enuFromGltfYUp();

/// Loads every triangle primitive of the default scene (all scenes' roots if none is default).
/// Checks what it reads: accessor and index ranges, NaN or infinite positions and node transforms (matrix, TRS,
/// and their composition), colour and emissive factors beyond float range, missing attributes, the scene's size
/// after instancing (above), any extension in extensionsRequired (none is supported: Draco, meshopt and
/// KTX2/Basis are named as such). The file, its buffers and its images must be regular files: a URI naming a
/// FIFO, a device or a directory is refused before anything is opened. Missing texture files fall back to the
/// material's factor and add a warning to `warnings` (if not null). Bad input throws InputError naming the file
/// and the glTF element ("meshes[2].primitives[0].indices"), on one line.
/// Missing normals are computed per face (flat). Non-triangle primitives are skipped with a warning.
TriangleMesh loadGltf(const std::string& path, const GltfLoadOptions& options,
                      std::vector<std::string>* warnings = nullptr);

/// Writes a TriangleMesh as a .glb (positions converted back ENU -> glTF Y-up by `gltf_from_enu`), with its
/// materials and textures (PNG-encoded, embedded). Used by the sample-site generator. Atomic.
void writeGlb(const std::string& path, const TriangleMesh& mesh, const glm::dmat4& model_from_enu);

}  // namespace gusuku

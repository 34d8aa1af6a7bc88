#pragma once
// The scene the baker traces: the building and the site's SfM mesh in one triangle list with per-triangle
// flags (so a pass can make the building invisible), packed into the GPU layouts that
// shaders/include/scene_shading.glsl reads.

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake {

struct Bvh;

/// Triangle flag: the triangle belongs to the building (skipped by "without building" passes).
constexpr uint32_t kTriangleFlagBuilding = 1u;
/// Triangle flag: the triangle's material is alpha-masked (Material::alpha_masked): a ray passes through where
/// its base colour's alpha is below the cutoff (shaders/include/bvh_alpha_mask.glsl). Set by makeTraceScene;
/// unflagged triangles are never alpha-tested, so an opaque scene traces as it did before masks existed.
constexpr uint32_t kTriangleFlagAlphaMasked = 2u;

struct TraceScene {
    TriangleMesh mesh;                     ///< building triangles first, then the site's
    std::vector<uint32_t> triangle_flags;  ///< one per triangle of mesh
    size_t building_triangle_count = 0;
    /// The BVH over exactly this mesh and these flags, when the caller has built one already (the bake's geometry
    /// builds it for its CPU work): the tracers upload it instead of building their own (with spatial splits a
    /// build of a detailed site costs a few tenths of a second). Null: the tracer builds it. Whoever changes
    /// mesh or triangle_flags afterwards must reset it.
    std::shared_ptr<const Bvh> bvh;
};

/// Merges the building and (optionally) the site mesh. Either may be empty, not both.
TraceScene makeTraceScene(const TriangleMesh& building, const TriangleMesh* site);

/// GPU layouts; must match shaders/include/scene_shading.glsl.
struct TriangleShadingGpu {
    glm::vec4 normal0_u0;
    glm::vec4 normal1_v0;
    glm::vec4 normal2_material;  ///< w: material index as float bits
    glm::vec4 uv0_vertex1_vertex2;
    glm::vec4 geometric_normal;  ///< xyz unit face normal; w 1 on a face of a closed part (closed_parts.h), else 0
};
static_assert(sizeof(TriangleShadingGpu) == 80);

struct MaterialGpu {
    glm::vec4 base_color_factor;
    glm::vec4 emission;           ///< xyz emitted radiance; w the alpha cutoff when masked, else 0
    uint32_t texture_first_word = 0;
    uint32_t texture_width = 0;
    uint32_t texture_height = 0;  ///< 0: no texture
    uint32_t flags = 0;           ///< bit 0: double-sided
};
static_assert(sizeof(MaterialGpu) == 48);

struct PackedSceneShading {
    std::vector<TriangleShadingGpu> triangles;  ///< indexed by the mesh's triangle order
    std::vector<MaterialGpu> materials;
    std::vector<uint32_t> texture_words;        ///< RGBA8, sRGB-encoded (decoded in the shader)
};

/// Packs normals, texture coordinates, materials and textures. Textures larger than max_texture_size are
/// box-downsampled (indirect light needs albedo, not detail; it also keeps the buffer under lavapipe's 128 MiB
/// storage-buffer cap). Non-finite normals are replaced by the face normal.
PackedSceneShading packSceneShading(const TriangleMesh& mesh, int max_texture_size = 512);

}  // namespace gusuku::bake

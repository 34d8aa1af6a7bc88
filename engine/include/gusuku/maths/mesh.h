#pragma once
// A triangle mesh in the site's east-north-up frame (metres), with what the baker and runtime need of its
// materials: base colour (factor times texture) and emission. Nothing else: diffuse surfaces only (docs/design.md 6).

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/maths/image_rgba.h"

namespace gusuku {

struct Material {
    std::string name;
    glm::vec4 base_color_factor{1.0f};  ///< linear RGBA, multiplies the texture
    int base_color_texture = -1;        ///< index into TriangleMesh::textures, -1 for none
    glm::vec3 emissive_factor{0.0f};    ///< linear emitted radiance (glTF emissiveFactor)
    bool double_sided = false;
    /// glTF alphaMode MASK (BLEND is read as MASK): the surface is a hole where the base colour's alpha
    /// (factor times texture, at the point's uv0) is below alpha_cutoff. The baker's rays pass through holes and
    /// the runtime discards them. False: opaque, alpha ignored (glTF OPAQUE).
    bool alpha_masked = false;
    float alpha_cutoff = 0.5f;  ///< glTF alphaCutoff, in [0, 1]; read only when alpha_masked
};

struct TriangleMesh {
    std::vector<glm::vec3> positions;  ///< ENU metres
    std::vector<glm::vec3> normals;    ///< unit, ENU; per vertex
    std::vector<glm::vec2> uv0;        ///< TEXCOORD_0 (texture), one per vertex (zeros when absent)
    std::vector<glm::vec2> uv1;        ///< TEXCOORD_1 (lightmap), one per vertex when has_uv1
    bool has_uv1 = false;
    std::vector<uint32_t> indices;             ///< three per triangle, counter-clockwise front faces
    std::vector<uint32_t> triangle_material;   ///< one per triangle, index into materials
    std::vector<Material> materials;           ///< at least one
    std::vector<ImageRGBA> textures;           ///< linear RGBA (sRGB base colour decoded on load)
    std::vector<std::string> texture_names;    ///< file or embedded name per texture, for messages

    size_t triangleCount() const { return indices.size() / 3; }
    size_t vertexCount() const { return positions.size(); }
};

/// Appends `other` to `mesh`, re-indexing vertices, materials and textures.
void appendMesh(TriangleMesh& mesh, const TriangleMesh& other);

/// Axis-aligned bounds of a mesh's positions.
struct Bounds3 {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    void extend(const glm::vec3& p);
    bool empty() const { return min.x > max.x; }
};
Bounds3 meshBounds(const TriangleMesh& mesh);

}  // namespace gusuku

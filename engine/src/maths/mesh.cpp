#include "gusuku/maths/mesh.h"

#include <glm/common.hpp>

namespace gusuku {

void appendMesh(TriangleMesh& mesh, const TriangleMesh& other) {
    const uint32_t vertex_offset = uint32_t(mesh.positions.size());
    const uint32_t material_offset = uint32_t(mesh.materials.size());
    const int texture_offset = int(mesh.textures.size());

    // uv1 stays meaningful only if both parts have it; otherwise the result has none (a lightmap channel on
    // half the triangles is no lightmap channel).
    const bool both_have_uv1 = (mesh.positions.empty() || mesh.has_uv1) && other.has_uv1;
    const bool first_is_empty = mesh.positions.empty();

    mesh.positions.insert(mesh.positions.end(), other.positions.begin(), other.positions.end());
    mesh.normals.insert(mesh.normals.end(), other.normals.begin(), other.normals.end());
    mesh.uv0.insert(mesh.uv0.end(), other.uv0.begin(), other.uv0.end());
    if (both_have_uv1) {
        if (first_is_empty) mesh.uv1.clear();
        mesh.uv1.insert(mesh.uv1.end(), other.uv1.begin(), other.uv1.end());
        mesh.has_uv1 = true;
    } else {
        mesh.uv1.clear();
        mesh.has_uv1 = false;
    }

    mesh.indices.reserve(mesh.indices.size() + other.indices.size());
    for (uint32_t index : other.indices) mesh.indices.push_back(index + vertex_offset);
    mesh.triangle_material.reserve(mesh.triangle_material.size() + other.triangle_material.size());
    for (uint32_t material : other.triangle_material) mesh.triangle_material.push_back(material + material_offset);

    for (Material material : other.materials) {
        if (material.base_color_texture >= 0) material.base_color_texture += texture_offset;
        mesh.materials.push_back(std::move(material));
    }
    mesh.textures.insert(mesh.textures.end(), other.textures.begin(), other.textures.end());
    mesh.texture_names.insert(mesh.texture_names.end(), other.texture_names.begin(), other.texture_names.end());
}

void Bounds3::extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

Bounds3 meshBounds(const TriangleMesh& mesh) {
    Bounds3 bounds;
    for (const glm::vec3& p : mesh.positions) bounds.extend(p);
    return bounds;
}

}  // namespace gusuku

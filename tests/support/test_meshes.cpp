#include "test_meshes.h"

#include <glm/geometric.hpp>

namespace gusuku::testing {

TriangleMesh emptyMesh(const glm::vec3& albedo, const glm::vec3& emission) {
    TriangleMesh mesh;
    Material material;
    material.name = "test";
    material.base_color_factor = glm::vec4(albedo, 1.0f);
    material.emissive_factor = emission;
    mesh.materials.push_back(material);
    return mesh;
}

void addQuad(TriangleMesh& mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
    const uint32_t first = uint32_t(mesh.positions.size());
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, d - a));
    mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
    mesh.normals.insert(mesh.normals.end(), 4, normal);
    mesh.uv0.insert(mesh.uv0.end(), {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
    mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    mesh.triangle_material.insert(mesh.triangle_material.end(), 2, 0u);
}

TriangleMesh horizontalPlane(float half_size, float z, const glm::vec3& albedo) {
    TriangleMesh mesh = emptyMesh(albedo);
    const float h = half_size;
    addQuad(mesh, {-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z});
    return mesh;
}

TriangleMesh closedBox(const glm::vec3& min, const glm::vec3& max, bool facing_inward, const glm::vec3& albedo,
                       const glm::vec3& emission) {
    TriangleMesh mesh = emptyMesh(albedo, emission);
    const auto corner = [&](int x, int y, int z) {
        return glm::vec3(x ? max.x : min.x, y ? max.y : min.y, z ? max.z : min.z);
    };
    // Each face listed counter-clockwise as seen from outside.
    const int faces[6][4][3] = {
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},  // bottom (-z)
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},  // top (+z)
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},  // south (-y)
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},  // north (+y)
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},  // west (-x)
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},  // east (+x)
    };
    for (const auto& face : faces) {
        glm::vec3 p[4];
        for (int i = 0; i < 4; ++i) p[i] = corner(face[i][0], face[i][1], face[i][2]);
        if (facing_inward)
            addQuad(mesh, p[0], p[3], p[2], p[1]);
        else
            addQuad(mesh, p[0], p[1], p[2], p[3]);
    }
    return mesh;
}

ImageRGBA uniformSky(int width, int height, const glm::vec3& radiance) {
    ImageRGBA sky;
    sky.width = width;
    sky.height = height;
    sky.texels.resize(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
        sky.texels[4 * i + 0] = radiance.r;
        sky.texels[4 * i + 1] = radiance.g;
        sky.texels[4 * i + 2] = radiance.b;
        sky.texels[4 * i + 3] = 1.0f;
    }
    return sky;
}

}  // namespace gusuku::testing

#pragma once
// Small meshes and skies built in code for analytic tests: planes, walls, closed boxes, uniform skies.

#include <glm/vec3.hpp>

#include "gusuku/assets/image.h"
#include "gusuku/maths/mesh.h"

namespace gusuku::testing {

/// A one-material mesh with the given albedo (and emission), no textures.
TriangleMesh emptyMesh(const glm::vec3& albedo, const glm::vec3& emission = glm::vec3(0.0f));

/// Appends a quad with corners a, b, c, d (counter-clockwise seen from the front, which faces
/// cross(b - a, d - a)), flat normals, uv0 = corners of the unit square.
void addQuad(TriangleMesh& mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d);

/// A horizontal square at height z, facing up, of half size h centred at the origin.
TriangleMesh horizontalPlane(float half_size, float z, const glm::vec3& albedo);

/// An axis-aligned closed box whose faces face INWARD (a furnace) or outward.
TriangleMesh closedBox(const glm::vec3& min, const glm::vec3& max, bool facing_inward, const glm::vec3& albedo,
                       const glm::vec3& emission = glm::vec3(0.0f));

/// An equirect map of constant radiance (both hemispheres).
ImageRGBA uniformSky(int width, int height, const glm::vec3& radiance);

/// A white texture for alpha masks: alpha 0 on the texels where open(x, y) (x, y texel indices, row 0 the top:
/// v = 0), 1 elsewhere.
template <typename Open>
ImageRGBA alphaMask(int width, int height, Open open) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, 1.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.texel(x, y)[3] = open(x, y) ? 0.0f : 1.0f;
    return image;
}

}  // namespace gusuku::testing

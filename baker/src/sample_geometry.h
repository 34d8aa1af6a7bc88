#pragma once
// Building blocks for the sample site's meshes: flat-shaded quads and triangles with planar texture
// coordinates, appended to a TriangleMesh, and small procedural base-colour textures. Private to the baker.

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gusuku/assets/image.h"
#include "gusuku/maths/mesh.h"

namespace gusuku::bake::sample {

/// Appends flat-shaded faces to a mesh. Every face's normal comes from its winding (counter-clockwise seen
/// from the side it faces), so stored normals and winding can never disagree.
class MeshBuilder {
public:
    explicit MeshBuilder(TriangleMesh& mesh) : mesh_(mesh) {}

    /// Adds a material with a texture (moved into the mesh); returns the material index.
    uint32_t addTexturedMaterial(const std::string& name, ImageRGBA texture);

    /// Texture coordinates: metres along two axes of the face's plane divided by the tile size (the glTF
    /// sampler repeats). On walls and slopes u runs horizontally and v up the face, negated so that the
    /// texture stands upright (glTF v grows downwards in the image); on flat faces u is east, v is -north.
    void setTileSize(double metres) { tile_size_m_ = metres; }

    /// Triangle a, b, c counter-clockwise seen from its front. Degenerate triangles are dropped.
    void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, uint32_t material);
    /// Planar quad a, b, c, d counter-clockwise seen from its front (split along a-c).
    void quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d,
              uint32_t material);
    /// Axis-aligned rectangle in the plane x = const (facing +x when facing_positive, else -x), spanning
    /// y0..y1, z0..z1. Likewise for y = const and z = const below.
    void rectX(double x, double y0, double y1, double z0, double z1, bool facing_positive, uint32_t material);
    void rectY(double y, double x0, double x1, double z0, double z1, bool facing_positive, uint32_t material);
    void rectZ(double z, double x0, double x1, double y0, double y1, bool facing_positive, uint32_t material);

private:
    glm::vec2 texcoord(const glm::dvec3& p, const glm::dvec3& normal) const;

    TriangleMesh& mesh_;
    double tile_size_m_ = 2.0;
};

/// Procedural base-colour textures, linear RGBA, `size` x `size` (<= 256), seamless when tiled.
ImageRGBA grassTexture(int size);
ImageRGBA limestoneTexture(int size);  ///< coursed Ryukyu limestone blocks
ImageRGBA plasterTexture(int size);
ImageRGBA woodTexture(int size);       ///< planks along u
ImageRGBA thatchTexture(int size);     ///< straw along v

}  // namespace gusuku::bake::sample

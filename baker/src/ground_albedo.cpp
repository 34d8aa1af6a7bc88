// The ground's albedo per cell: see ground_albedo.h.
#include "ground_albedo.h"

#include <algorithm>
#include <cmath>

#include "gusuku_bake/bvh.h"
#include "gusuku_bake/ground_grid.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

namespace {

// Points per cell side whose base colours are averaged (16 rays per cell on the CPU).
constexpr int kGroundAlbedoSubsamples = 4;

glm::vec3 baseColourAt(const TriangleMesh& mesh, uint32_t triangle, float u, float v) {
    const uint32_t material_index = triangle < mesh.triangle_material.size() ? mesh.triangle_material[triangle] : 0u;
    const Material fallback;
    const Material& material = material_index < mesh.materials.size() ? mesh.materials[material_index] : fallback;
    glm::vec3 albedo(material.base_color_factor);
    if (material.base_color_texture < 0 || size_t(material.base_color_texture) >= mesh.textures.size() ||
        mesh.uv0.size() < mesh.positions.size())
        return albedo;
    const uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                   i2 = mesh.indices[3 * triangle + 2];
    const glm::vec2 uv = (1.0f - u - v) * mesh.uv0[i0] + u * mesh.uv0[i1] + v * mesh.uv0[i2];
    const ImageRGBA& texture = mesh.textures[size_t(material.base_color_texture)];
    if (texture.width <= 0 || texture.height <= 0) return albedo;
    // Repeat wrapping, the texel whose cell holds uv (as bake_statistics.cpp's albedoAtTexel).
    const auto wrap = [](float coordinate, int size) {
        const int index = int(std::floor((coordinate - std::floor(coordinate)) * float(size)));
        return std::clamp(index, 0, size - 1);
    };
    const float* rgba = texture.texel(wrap(uv.x, texture.width), wrap(uv.y, texture.height));
    return albedo * glm::vec3(rgba[0], rgba[1], rgba[2]);
}

}  // namespace

std::vector<glm::vec4> sampleGroundAlbedo(const BakeGeometry& geometry) {
    const GroundRegion& region = geometry.ground_region;
    std::vector<glm::vec4> albedo(region.cellCount(), glm::vec4(0.0f));
    const TriangleMesh& mesh = geometry.scene.mesh;
    float top_z = -1e30f;
    for (const glm::vec3& p : mesh.positions) top_z = std::max(top_z, p.z);
    top_z += 1.0f;
    const glm::vec3 down(0.0f, 0.0f, -1.0f);
    for (int row = 0; row < region.rows; ++row)
        for (int column = 0; column < region.columns; ++column) {
            const size_t index = groundCellIndex(region, {column, row});
            if (index >= geometry.ground_cells.size() || !geometry.ground_cells[index].valid) continue;
            const glm::dvec2 centre = groundCellCentre(region, column, row);
            // The mean over kGroundAlbedoSubsamples^2 points spread over the cell: a camera pixel sees an area of
            // ground, and the match compares it with its cell's value (a point would carry the texture's detail).
            glm::dvec3 sum(0.0);
            int hits = 0;
            for (int j = 0; j < kGroundAlbedoSubsamples; ++j)
                for (int i = 0; i < kGroundAlbedoSubsamples; ++i) {
                    const double dx = ((i + 0.5) / kGroundAlbedoSubsamples - 0.5) * region.cell_m;
                    const double dy = ((j + 0.5) / kGroundAlbedoSubsamples - 0.5) * region.cell_m;
                    const auto hit = traceClosestCpu(geometry.cpuBvh(),
                                                     glm::vec3(float(centre.x + dx), float(centre.y + dy), top_z),
                                                     down, 1e30f, kTriangleFlagBuilding);
                    if (!hit) continue;
                    const glm::vec3 colour =
                        baseColourAt(mesh, hit->triangle_index, hit->barycentric_u, hit->barycentric_v);
                    if (!(std::isfinite(colour.r) && std::isfinite(colour.g) && std::isfinite(colour.b))) continue;
                    sum += glm::dvec3(glm::max(colour, glm::vec3(0.0f)));
                    ++hits;
                }
            if (hits > 0) albedo[index] = glm::vec4(glm::vec3(sum / double(hits)), 1.0f);
        }
    return albedo;
}

}  // namespace gusuku::bake

#include "bake_statistics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"

namespace gusuku::bake {

glm::vec3 albedoAtTexel(const TriangleMesh& mesh, const LightmapTexel& texel) {
    const uint32_t t = texel.triangle;
    const uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
    const uint32_t material_index = t < mesh.triangle_material.size() ? mesh.triangle_material[t] : 0u;
    const Material fallback;
    const Material& material = material_index < mesh.materials.size() ? mesh.materials[material_index] : fallback;
    glm::vec3 albedo(material.base_color_factor);
    if (material.base_color_texture < 0 || size_t(material.base_color_texture) >= mesh.textures.size()) return albedo;
    // Barycentrics of the texel's position in its triangle (the position lies on it by construction).
    const glm::vec3 p0 = mesh.positions[i0], e1 = mesh.positions[i1] - p0, e2 = mesh.positions[i2] - p0;
    const glm::vec3 d = texel.position - p0;
    const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    const float d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
    const float denominator = d11 * d22 - d12 * d12;
    if (!(std::fabs(denominator) > 0.0f)) return albedo;
    const float u = (d22 * d1 - d12 * d2) / denominator, v = (d11 * d2 - d12 * d1) / denominator;
    const glm::vec2 uv = (1.0f - u - v) * mesh.uv0[i0] + u * mesh.uv0[i1] + v * mesh.uv0[i2];
    const ImageRGBA& texture = mesh.textures[size_t(material.base_color_texture)];
    const auto wrap = [](float coordinate, int size) {
        const int index = int(std::floor((coordinate - std::floor(coordinate)) * float(size)));
        return std::clamp(index, 0, size - 1);
    };
    const float* texel_rgba = texture.texel(wrap(uv.x, texture.width), wrap(uv.y, texture.height));
    return albedo * glm::vec3(texel_rgba[0], texel_rgba[1], texel_rgba[2]);
}

LabStatistics bakedAppearanceStatistics(const BakeGeometry& geometry, const std::vector<glm::vec4>& irradiance,
                                        const SunLight& sun) {
    const glm::vec3 sun_direction(sun.direction_enu);
    glm::dvec3 sum(0.0), sum_squares(0.0);
    LabStatistics statistics;
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        if (irradiance[i].a <= 0.0f) continue;
        const LightmapTexel& texel = geometry.texels[i];
        glm::vec3 total_irradiance(irradiance[i]);
        if (sun.present) {
            const float cos_theta = glm::dot(texel.shading_normal, sun_direction);
            if (cos_theta > 0.0f &&
                !occludedCpu(geometry.cpuBvh(), texel.position + texel.geometric_normal * 1e-3f, sun_direction, 1e30f))
                total_irradiance += glm::vec3(sun.irradiance_rgb) * cos_theta;
        }
        const glm::vec3 radiance =
            albedoAtTexel(geometry.building, texel) * total_irradiance / std::numbers::pi_v<float>;
        const glm::dvec3 lab(labFromLinearRec709(radiance));
        sum += lab;
        sum_squares += lab * lab;
        ++statistics.texel_count;
    }
    if (statistics.texel_count == 0) return statistics;
    const glm::dvec3 mean = sum / double(statistics.texel_count);
    const glm::dvec3 variance = glm::max(sum_squares / double(statistics.texel_count) - mean * mean, glm::dvec3(0.0));
    statistics.mean = glm::vec3(mean);
    statistics.sigma = glm::vec3(glm::sqrt(variance));
    return statistics;
}

}  // namespace gusuku::bake

#include "gusuku_bake/trace_scene.h"

#include "gusuku_bake/closed_parts.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/assets/image.h"

namespace gusuku::bake {

TraceScene makeTraceScene(const TriangleMesh& building, const TriangleMesh* site) {
    TraceScene scene;
    appendMesh(scene.mesh, building);
    scene.building_triangle_count = building.triangleCount();
    if (site != nullptr) appendMesh(scene.mesh, *site);
    if (scene.mesh.triangleCount() == 0) throw std::invalid_argument("trace scene has no triangles");
    scene.triangle_flags.assign(scene.mesh.triangleCount(), 0u);
    std::fill(scene.triangle_flags.begin(), scene.triangle_flags.begin() + long(scene.building_triangle_count),
              kTriangleFlagBuilding);
    for (size_t t = 0; t < scene.mesh.triangle_material.size() && t < scene.triangle_flags.size(); ++t) {
        const uint32_t material = scene.mesh.triangle_material[t];
        if (material < scene.mesh.materials.size() && scene.mesh.materials[material].alpha_masked)
            scene.triangle_flags[t] |= kTriangleFlagAlphaMasked;
    }
    return scene;
}

namespace {

float floatFromBits(uint32_t bits) {
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

glm::vec3 finiteUnitOr(const glm::vec3& normal, const glm::vec3& fallback) {
    const float length = glm::length(normal);
    if (!std::isfinite(length) || length < 1e-6f) return fallback;
    return normal / length;
}

// Box filter by an integer factor until both sides fit; keeps albedo averages exact.
ImageRGBA downsampleToFit(const ImageRGBA& image, int max_size) {
    int factor = 1;
    while (max_size > 0 && (image.width / factor > max_size || image.height / factor > max_size)) factor *= 2;
    if (factor == 1) return image;
    ImageRGBA small;
    small.width = std::max(1, image.width / factor);
    small.height = std::max(1, image.height / factor);
    small.texels.assign(size_t(small.width) * size_t(small.height) * 4, 0.0f);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x) {
            float* out = small.texel(x, y);
            for (int dy = 0; dy < factor; ++dy)
                for (int dx = 0; dx < factor; ++dx) {
                    const float* in = image.texel(std::min(x * factor + dx, image.width - 1),
                                                  std::min(y * factor + dy, image.height - 1));
                    for (int c = 0; c < 4; ++c) out[c] += in[c];
                }
            for (int c = 0; c < 4; ++c) out[c] /= float(factor * factor);
        }
    return small;
}

uint32_t packSrgb8(const float* linear_rgba) {
    uint32_t word = 0;
    for (int c = 0; c < 4; ++c) {
        float value = std::clamp(linear_rgba[c], 0.0f, 1.0f);
        if (!std::isfinite(value)) value = 0.0f;
        const float encoded = c < 3 ? srgbEncode(value) : value;
        word |= uint32_t(std::lround(encoded * 255.0f)) << (8 * c);
    }
    return word;
}

}  // namespace

PackedSceneShading packSceneShading(const TriangleMesh& mesh, int max_texture_size) {
    PackedSceneShading packed;
    std::vector<uint32_t> texture_first_word(mesh.textures.size());
    std::vector<glm::ivec2> texture_size(mesh.textures.size());
    for (size_t t = 0; t < mesh.textures.size(); ++t) {
        const ImageRGBA small = downsampleToFit(mesh.textures[t], max_texture_size);
        texture_first_word[t] = uint32_t(packed.texture_words.size());
        texture_size[t] = {small.width, small.height};
        for (int y = 0; y < small.height; ++y)
            for (int x = 0; x < small.width; ++x) packed.texture_words.push_back(packSrgb8(small.texel(x, y)));
    }
    for (const Material& material : mesh.materials) {
        MaterialGpu gpu;
        gpu.base_color_factor = material.base_color_factor;
        gpu.emission = glm::vec4(material.emissive_factor, material.alpha_masked ? material.alpha_cutoff : 0.0f);
        if (material.base_color_texture >= 0 && size_t(material.base_color_texture) < mesh.textures.size()) {
            gpu.texture_first_word = texture_first_word[size_t(material.base_color_texture)];
            gpu.texture_width = uint32_t(texture_size[size_t(material.base_color_texture)].x);
            gpu.texture_height = uint32_t(texture_size[size_t(material.base_color_texture)].y);
        }
        gpu.flags = material.double_sided ? 1u : 0u;
        packed.materials.push_back(gpu);
    }
    if (packed.materials.empty()) packed.materials.push_back(MaterialGpu{glm::vec4(0.5f, 0.5f, 0.5f, 1.0f),
                                                                         glm::vec4(0.0f)});
    if (packed.texture_words.empty()) packed.texture_words.push_back(0u);

    const size_t triangle_count = mesh.triangleCount();
    packed.triangles.resize(triangle_count);
    const std::vector<bool> closed = closedOutwardTriangles(mesh);
    for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
        const glm::vec3 p0 = mesh.positions[i0], p1 = mesh.positions[i1], p2 = mesh.positions[i2];
        const glm::vec3 face = finiteUnitOr(glm::cross(p1 - p0, p2 - p0), glm::vec3(0.0f, 0.0f, 1.0f));
        const auto normal = [&](uint32_t i) {
            return i < mesh.normals.size() ? finiteUnitOr(mesh.normals[i], face) : face;
        };
        const auto uv = [&](uint32_t i) { return i < mesh.uv0.size() ? mesh.uv0[i] : glm::vec2(0.0f); };
        uint32_t material = t < mesh.triangle_material.size() ? mesh.triangle_material[t] : 0u;
        if (material >= packed.materials.size()) material = 0u;
        TriangleShadingGpu& gpu = packed.triangles[t];
        gpu.normal0_u0 = glm::vec4(normal(i0), uv(i0).x);
        gpu.normal1_v0 = glm::vec4(normal(i1), uv(i0).y);
        gpu.normal2_material = glm::vec4(normal(i2), floatFromBits(material));
        gpu.uv0_vertex1_vertex2 = glm::vec4(uv(i1), uv(i2));
        gpu.geometric_normal = glm::vec4(face, closed[t] ? 1.0f : 0.0f);
    }
    return packed;
}

}  // namespace gusuku::bake

#include "sample_geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace gusuku::bake::sample {

namespace {

// ---- faces ----

glm::dvec3 faceNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return glm::cross(b - a, c - a);
}

// ---- procedural textures ----

uint32_t hashLattice(int x, int y, uint32_t seed) {
    uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h;
}

double latticeValue(int x, int y, uint32_t seed) { return (hashLattice(x, y, seed) & 0xffffffu) / double(0x1000000); }

int wrap(int i, int period) { return ((i % period) + period) % period; }

// Smooth value noise on a lattice of period_x x period_y cells over the unit square, so the texture tiles.
double valueNoise(double u, double v, int period_x, int period_y, uint32_t seed) {
    const double x = u * period_x, y = v * period_y;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const double sx = fx * fx * (3.0 - 2.0 * fx), sy = fy * fy * (3.0 - 2.0 * fy);
    auto at = [&](int ix, int iy) { return latticeValue(wrap(ix, period_x), wrap(iy, period_y), seed); };
    const double top = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * sx;
    const double bottom = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * sx;
    return top + (bottom - top) * sy;
}

// Sum of octaves, each twice the frequency and half the amplitude; result in about [0, 1].
double fractalNoise(double u, double v, int period_x, int period_y, int octaves, uint32_t seed) {
    double sum = 0.0, amplitude = 0.5, weight = 0.0;
    for (int octave = 0; octave < octaves; ++octave) {
        sum += amplitude * valueNoise(u, v, period_x << octave, period_y << octave, seed + uint32_t(octave));
        weight += amplitude;
        amplitude *= 0.5;
    }
    return sum / weight;
}

glm::dvec3 mix(const glm::dvec3& a, const glm::dvec3& b, double t) { return a + (b - a) * t; }

template <typename Colour>
ImageRGBA makeTexture(int size, const Colour& colour_at) {
    if (size < 4 || size > 256) throw std::invalid_argument("sample texture size must be 4..256");
    ImageRGBA image;
    image.width = size;
    image.height = size;
    image.texels.assign(size_t(size) * size_t(size) * 4, 1.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 rgb = glm::clamp(colour_at((x + 0.5) / size, (y + 0.5) / size), 0.0, 1.0);
            float* texel = image.texel(x, y);
            texel[0] = float(rgb.x);
            texel[1] = float(rgb.y);
            texel[2] = float(rgb.z);
        }
    return image;
}

}  // namespace

uint32_t MeshBuilder::addTexturedMaterial(const std::string& name, ImageRGBA texture) {
    Material material;
    material.name = name;
    material.base_color_texture = int(mesh_.textures.size());
    mesh_.textures.push_back(std::move(texture));
    mesh_.texture_names.push_back(name + ".png");
    mesh_.materials.push_back(material);
    return uint32_t(mesh_.materials.size() - 1);
}

glm::vec2 MeshBuilder::texcoord(const glm::dvec3& p, const glm::dvec3& normal) const {
    glm::dvec3 u_axis, up_axis;
    if (std::abs(normal.z) < 0.9) {
        // Walls and roof slopes: u along the horizontal, v up the face.
        u_axis = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), normal));
        up_axis = glm::cross(normal, u_axis);
    } else {
        u_axis = {1, 0, 0};
        up_axis = {0, 1, 0};
    }
    return glm::vec2(float(glm::dot(p, u_axis) / tile_size_m_), float(-glm::dot(p, up_axis) / tile_size_m_));
}

void MeshBuilder::triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, uint32_t material) {
    const glm::dvec3 area_normal = faceNormal(a, b, c);
    const double twice_area = glm::length(area_normal);
    if (twice_area < 1e-12) return;
    const glm::dvec3 normal = area_normal / twice_area;
    const uint32_t first = uint32_t(mesh_.positions.size());
    for (const glm::dvec3& p : {a, b, c}) {
        mesh_.positions.emplace_back(p);
        mesh_.normals.emplace_back(normal);
        mesh_.uv0.push_back(texcoord(p, normal));
    }
    mesh_.indices.insert(mesh_.indices.end(), {first, first + 1, first + 2});
    mesh_.triangle_material.push_back(material);
}

void MeshBuilder::quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d,
                       uint32_t material) {
    const glm::dvec3 area_normal = faceNormal(a, b, c) + faceNormal(a, c, d);
    const double length = glm::length(area_normal);
    if (length < 1e-12) return;
    const glm::dvec3 normal = area_normal / length;
    const uint32_t first = uint32_t(mesh_.positions.size());
    for (const glm::dvec3& p : {a, b, c, d}) {
        mesh_.positions.emplace_back(p);
        mesh_.normals.emplace_back(normal);
        mesh_.uv0.push_back(texcoord(p, normal));
    }
    mesh_.indices.insert(mesh_.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    mesh_.triangle_material.push_back(material);
    mesh_.triangle_material.push_back(material);
}

void MeshBuilder::rectX(double x, double y0, double y1, double z0, double z1, bool facing_positive,
                        uint32_t material) {
    if (y1 <= y0 || z1 <= z0) return;
    if (facing_positive)
        quad({x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}, material);
    else
        quad({x, y1, z0}, {x, y0, z0}, {x, y0, z1}, {x, y1, z1}, material);
}

void MeshBuilder::rectY(double y, double x0, double x1, double z0, double z1, bool facing_positive,
                        uint32_t material) {
    if (x1 <= x0 || z1 <= z0) return;
    if (facing_positive)
        quad({x1, y, z0}, {x0, y, z0}, {x0, y, z1}, {x1, y, z1}, material);
    else
        quad({x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}, material);
}

void MeshBuilder::rectZ(double z, double x0, double x1, double y0, double y1, bool facing_positive,
                        uint32_t material) {
    if (x1 <= x0 || y1 <= y0) return;
    if (facing_positive)
        quad({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, material);
    else
        quad({x0, y1, z}, {x1, y1, z}, {x1, y0, z}, {x0, y0, z}, material);
}

ImageRGBA grassTexture(int size) {
    // Linear albedos: short grass about 0.1-0.15, bare earth about 0.2.
    const glm::dvec3 grass{0.075, 0.125, 0.035}, dry_grass{0.16, 0.16, 0.07}, earth{0.20, 0.14, 0.085};
    return makeTexture(size, [&](double u, double v) {
        const double patches = fractalNoise(u, v, 4, 4, 3, 11);
        const double blades = valueNoise(u, v, 64, 64, 12);
        glm::dvec3 colour = mix(grass, dry_grass, std::clamp(patches * 1.6 - 0.3, 0.0, 1.0));
        colour = mix(colour, earth, std::clamp((fractalNoise(u, v, 3, 3, 2, 13) - 0.62) * 4.0, 0.0, 1.0));
        return colour * (0.8 + 0.4 * blades);
    });
}

ImageRGBA limestoneTexture(int size) {
    // Coursed blocks of pale coral limestone (albedo about 0.45), four courses per tile, with darker joints.
    const glm::dvec3 stone{0.50, 0.47, 0.39}, weathered{0.36, 0.35, 0.31}, joint{0.20, 0.19, 0.17};
    return makeTexture(size, [&](double u, double v) {
        const int course = int(v * 4.0);
        const double course_v = v * 4.0 - course;
        const double shifted_u = u * 2.0 + (course % 2) * 0.5;
        const int block = int(std::floor(shifted_u));
        const double block_u = shifted_u - block;
        const double joint_width = 0.035;
        const bool in_joint = course_v < joint_width * 2.0 || block_u < joint_width;
        const double block_tint = latticeValue(wrap(block, 2), course, 21);
        const double grain = fractalNoise(u, v, 8, 8, 3, 22);
        glm::dvec3 colour = mix(stone, weathered, std::clamp(block_tint * 0.7 + (grain - 0.5), 0.0, 1.0));
        if (in_joint) colour = joint;
        return colour * (0.9 + 0.2 * valueNoise(u, v, 64, 64, 23));
    });
}

ImageRGBA plasterTexture(int size) {
    const glm::dvec3 plaster{0.62, 0.58, 0.50}, stained{0.48, 0.44, 0.37};
    return makeTexture(size, [&](double u, double v) {
        const double stain = std::clamp((fractalNoise(u, v, 4, 4, 4, 31) - 0.45) * 2.5, 0.0, 1.0);
        return mix(plaster, stained, stain) * (0.95 + 0.1 * valueNoise(u, v, 64, 64, 32));
    });
}

ImageRGBA woodTexture(int size) {
    // Four planks per tile along u; grain stretched along the plank.
    const glm::dvec3 wood{0.26, 0.16, 0.085}, dark{0.15, 0.09, 0.05};
    return makeTexture(size, [&](double u, double v) {
        const int plank = int(v * 4.0);
        const double plank_v = v * 4.0 - plank;
        const double grain = fractalNoise(u, v, 2, 32, 3, 41 + uint32_t(plank));
        glm::dvec3 colour = mix(wood, dark, grain * 0.8) * (0.85 + 0.3 * latticeValue(plank, 0, 42));
        if (plank_v < 0.04) colour = dark * 0.6;
        return colour;
    });
}

ImageRGBA thatchTexture(int size) {
    // Straw bundles running down the slope (along v), golden when fresh and grey-brown when weathered.
    const glm::dvec3 straw{0.36, 0.27, 0.13}, weathered{0.20, 0.17, 0.12};
    return makeTexture(size, [&](double u, double v) {
        const double strands = valueNoise(u, v, 96, 4, 51);
        const double age = fractalNoise(u, v, 4, 4, 3, 52);
        const double course = std::fmod(v * 6.0, 1.0);  // stepped courses of bundles
        glm::dvec3 colour = mix(straw, weathered, std::clamp(age * 1.4 - 0.2, 0.0, 1.0));
        colour *= 0.7 + 0.5 * strands;
        if (course > 0.9) colour *= 0.6;
        return colour;
    });
}

}  // namespace gusuku::bake::sample

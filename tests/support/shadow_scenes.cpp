// The shadow tests' buildings and CPU truth (shadow_scenes.h).

#include "shadow_scenes.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace gusuku::testing {
namespace {

constexpr double kSunAngularRadiusDeg = 0.2675;
constexpr double kSelfHitM = 1e-4;

// A box spanned by the edges a, b, c from `origin` (a right-handed frame): its six faces as twelve triangles, outward.
void addBox(std::vector<glm::vec3>& out, const glm::dvec3& origin, const glm::dvec3& a, const glm::dvec3& b,
            const glm::dvec3& c) {
    auto corner = [&](int i) { return glm::vec3(origin + ((i & 1) ? a : glm::dvec3(0)) + ((i & 2) ? b : glm::dvec3(0)) +
                                                 ((i & 4) ? c : glm::dvec3(0))); };
    // Faces as corner quads, counter-clockwise from outside for a right-handed (a, b, c).
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& face : faces)
        for (int index : {0, 1, 2, 0, 2, 3}) out.push_back(corner(face[index]));
}

}  // namespace

BakeSetData bakeSetWithBuilding(const std::vector<glm::vec3>& triangles, const SyntheticBakeSetOptions& options) {
    BakeSetData data = makeSyntheticBakeSet(options);
    BakeSetMesh mesh;
    for (size_t first = 0; first + 2 < triangles.size(); first += 3) {
        const glm::vec3 normal =
            glm::normalize(glm::cross(triangles[first + 1] - triangles[first], triangles[first + 2] - triangles[first]));
        for (size_t corner = 0; corner < 3; ++corner) {
            mesh.indices.push_back(uint32_t(mesh.positions.size()));
            mesh.positions.push_back(triangles[first + corner]);
            mesh.normals.push_back(normal);
            mesh.uv0.push_back(glm::vec2(0.5f));
            mesh.uv1.push_back(glm::vec2(0.5f));
        }
        mesh.triangle_material.push_back(0);
    }
    mesh.materials = data.building.materials;
    data.building = std::move(mesh);
    return data;
}

std::vector<glm::vec3> ribbedRoof(const RibbedRoofOptions& options) {
    const double pitch = options.pitch_deg * std::numbers::pi / 180.0;
    const double slope_m = 3.0, width_m = 4.0, eave_height_m = 2.0;
    // Down the slope towards the east, across it (north), and the roof's normal.
    const glm::dvec3 down(std::cos(pitch), 0.0, -std::sin(pitch));
    const glm::dvec3 across(0.0, 1.0, 0.0);
    const glm::dvec3 normal = glm::cross(down, across);  // (sin, 0, cos): up and east
    const glm::dvec3 ridge(-0.5 * slope_m * std::cos(pitch), -0.5 * width_m,
                           eave_height_m + slope_m * std::sin(pitch));
    std::vector<glm::vec3> out;
    // The roof as a slab 5 cm thick (closed, so it casts a proper shadow), then the battens on it.
    addBox(out, ridge - 0.05 * normal, slope_m * down, width_m * across, 0.05 * normal);
    if (!options.ribs) return out;
    for (double along = 0.5 * options.rib_spacing_m; along + options.rib_width_m < slope_m;
         along += options.rib_spacing_m)
        addBox(out, ridge + along * down, options.rib_width_m * down, width_m * across, options.rib_height_m * normal);
    return out;
}

std::vector<glm::vec3> platformBuilding(double platform_height_m) {
    std::vector<glm::vec3> out;
    const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    addBox(out, glm::dvec3(-2.5, -2.5, 0.0), 5.0 * x, 5.0 * y, platform_height_m * z);
    addBox(out, glm::dvec3(-1.0, -1.0, platform_height_m), 2.0 * x, 2.0 * y, 2.0 * z);
    return out;
}

std::vector<glm::vec3> wallBuilding() {
    std::vector<glm::vec3> out;
    addBox(out, glm::dvec3(3.0, 0.0, 0.0), glm::dvec3(0.2, 0, 0), glm::dvec3(0, 3.0, 0), glm::dvec3(0, 0, 4.0));
    return out;
}

std::optional<RayHit> castRay(const std::vector<glm::vec3>& triangles, const glm::dvec3& origin,
                              const glm::dvec3& direction) {
    std::optional<RayHit> nearest;
    for (size_t first = 0; first + 2 < triangles.size(); first += 3) {
        const glm::dvec3 a(triangles[first]), b(triangles[first + 1]), c(triangles[first + 2]);
        const glm::dvec3 edge1 = b - a, edge2 = c - a;
        const glm::dvec3 p = glm::cross(direction, edge2);
        const double determinant = glm::dot(edge1, p);
        if (std::abs(determinant) < 1e-14) continue;
        const glm::dvec3 t_vector = origin - a;
        const double u = glm::dot(t_vector, p) / determinant;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 q = glm::cross(t_vector, edge1);
        const double v = glm::dot(direction, q) / determinant;
        if (v < 0.0 || u + v > 1.0) continue;
        const double distance = glm::dot(edge2, q) / determinant;
        if (distance <= 0.0 || (nearest && distance >= nearest->distance)) continue;
        glm::dvec3 normal = glm::normalize(glm::cross(edge1, edge2));
        if (glm::dot(normal, direction) > 0.0) normal = -normal;
        nearest = RayHit{distance, normal};
    }
    return nearest;
}

double sunDiscVisibility(const std::vector<glm::vec3>& triangles, const glm::dvec3& point, const glm::dvec3& normal,
                         const glm::dvec3& sun_direction, int samples) {
    const glm::dvec3 s = glm::normalize(sun_direction);
    const glm::dvec3 helper = std::abs(s.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(helper, s)), e2 = glm::cross(s, e1);
    const double radius = std::tan(kSunAngularRadiusDeg * std::numbers::pi / 180.0);
    const glm::dvec3 origin = point + normal * kSelfHitM;
    int seen = 0;
    for (int sample = 0; sample < samples; ++sample) {
        // A Vogel spiral over the disc: uniform in area, deterministic.
        const double r = radius * std::sqrt((sample + 0.5) / samples), angle = sample * 2.39996323;
        const glm::dvec3 direction = glm::normalize(s + r * (std::cos(angle) * e1 + std::sin(angle) * e2));
        seen += castRay(triangles, origin, direction) ? 0 : 1;
    }
    return double(seen) / samples;
}

}  // namespace gusuku::testing

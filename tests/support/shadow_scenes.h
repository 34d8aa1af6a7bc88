#pragma once
// Buildings for the shadow tests (tests/test_runtime_shadows.cpp), put into the closed-form bake set of
// synthetic_bakeset.h in place of its box (same lighting terms: constant E_ind, flat lit ground), and a CPU ray
// caster that renders the runtime's light model with the exact sun visibility, as the independent truth:
//   radiance = albedo / pi x (E_ind + V x E_sun x max(0, n . s)), V the fraction of the sun's disc seen.
//   - ribbedRoof: a mono-pitch roof facing east (pitch 30 degrees, 3 m along the slope, 4 m wide) on a 2 m
//     eave line, with horizontal battens across it (`rib_height_m` tall, 3 cm wide, every `rib_spacing_m`);
//     0 ribs gives the flat roof alone;
//   - platformBuilding: a base platform `platform_height_m` tall over [-2.5, 2.5]^2 and a 2 x 2 x 2 m box on it;
//   - wallBuilding: a wall over x in [3, 3.2], y in [0, 3], 4 m tall, whose south-east vertical edge casts a long
//     straight shadow edge on the ground under a morning sun (the penumbra-width test).

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku::testing {

struct RibbedRoofOptions {
    double pitch_deg = 30.0;
    double rib_height_m = 0.04;
    double rib_width_m = 0.03;
    double rib_spacing_m = 0.25;
    bool ribs = true;
};

/// The bake set of synthetic_bakeset.h with its building replaced by `building` (one grey material of
/// options.albedo; lightmap coordinates all in the middle of the constant lightmap).
BakeSetData bakeSetWithBuilding(const std::vector<glm::vec3>& triangles, const SyntheticBakeSetOptions& options);

/// Triangle soup (three corners each, counter-clockwise seen from outside).
std::vector<glm::vec3> ribbedRoof(const RibbedRoofOptions& options);
std::vector<glm::vec3> platformBuilding(double platform_height_m);
std::vector<glm::vec3> wallBuilding();

/// What a ray meets first: distance, the triangle's unit normal (facing the ray's origin) and its index.
struct RayHit {
    double distance = 0.0;
    glm::dvec3 normal{0.0};
};
std::optional<RayHit> castRay(const std::vector<glm::vec3>& triangles, const glm::dvec3& origin,
                              const glm::dvec3& direction);

/// The fraction of the sun's disc (angular radius 0.2675 degrees, `samples` directions over it) seen from
/// `point`, which is moved 0.1 mm along `normal` first.
double sunDiscVisibility(const std::vector<glm::vec3>& triangles, const glm::dvec3& point, const glm::dvec3& normal,
                         const glm::dvec3& sun_direction, int samples);

}  // namespace gusuku::testing

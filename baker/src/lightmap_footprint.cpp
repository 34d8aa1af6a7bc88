// Texels that stand for their area: each texel's sample budget spread over sub-points of its footprint
// (lightmapTexelFootprints), and the slots' sums folded back into one sum per texel (texelSumsFromFootprint).
// A texel traced at its centre alone stores whatever lies under that centre: next to a 2 cm crease a 6 cm
// texel whose centre falls in the crease stores the crease's darkness, and bilinear filtering spreads it
// onto surfaces twice as bright.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_raster.h"

namespace gusuku::bake {
namespace {

// splitmix64 finaliser: a well-mixed 64-bit value from (seed, texel), for the per-texel pattern shift.
uint64_t mixBits(uint64_t value) {
    value += 0x9e3779b97f4a7c15ull;
    value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ull;
    value = (value ^ (value >> 27)) * 0x94d049bb133111ebull;
    return value ^ (value >> 31);
}

double unitFromBits(uint64_t bits) { return double(bits >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)

// Sub-point `slot` of an n-rooks pattern on a side x side grid, shifted by `shift` (toroidally), in [0, 1)^2.
glm::dvec2 patternPoint(int slot, int side, const glm::dvec2& shift) {
    const int column = slot % side, row = slot / side;
    const double count = double(side * side);
    const glm::dvec2 base((double(column * side + row) + 0.5) / count, (double(row * side + column) + 0.5) / count);
    glm::dvec2 shifted = base + shift;
    shifted -= glm::floor(shifted);
    return shifted;
}

detail::UvTriangle uvTriangleInTexels(const TriangleMesh& mesh, size_t triangle, int resolution) {
    detail::UvTriangle uv;
    for (int corner = 0; corner < 3; ++corner)
        uv[corner] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + corner]]) * double(resolution);
    return uv;
}

bool hasWorldArea(const TriangleMesh& mesh, size_t triangle) {
    const glm::vec3& p0 = mesh.positions[mesh.indices[triangle * 3 + 0]];
    const glm::vec3& p1 = mesh.positions[mesh.indices[triangle * 3 + 1]];
    const glm::vec3& p2 = mesh.positions[mesh.indices[triangle * 3 + 2]];
    const float world_double_area = glm::length(glm::cross(p1 - p0, p2 - p0));
    return world_double_area > 0.0f && std::isfinite(world_double_area);
}

}  // namespace

int footprintGridSide(uint32_t samples_per_texel, size_t texel_count, size_t max_points,
                      uint32_t min_samples_per_slot) {
    for (const int side : {4, 2}) {
        const uint32_t slots = uint32_t(side * side);
        if (samples_per_texel % slots == 0 && samples_per_texel / slots >= std::max(min_samples_per_slot, 1u) &&
            texel_count <= max_points / size_t(slots))
            return side;
    }
    return 1;
}

LightmapFootprint lightmapTexelFootprints(const TriangleMesh& mesh, int resolution,
                                          const std::vector<LightmapTexel>& texels, int grid_side, uint32_t seed) {
    if (grid_side < 1 || grid_side > 8)
        throw InputError("lightmap", "footprint grid", "must be in [1, 8], got " + std::to_string(grid_side));
    detail::validateLightmapMesh(mesh, resolution);

    LightmapFootprint footprint;
    footprint.grid_side = grid_side;
    const size_t slots_per_texel = footprint.pointsPerTexel();
    footprint.points.resize(texels.size() * slots_per_texel);
    if (grid_side == 1) {
        for (size_t i = 0; i < texels.size(); ++i)
            footprint.points[i] = {texels[i].position, texels[i].shading_normal, texels[i].geometric_normal, 1.0f};
        return footprint;
    }

    // Where each texel's slots sit in texel units, and which triangle covers each (-1: none yet).
    std::vector<int32_t> texel_index(size_t(resolution) * size_t(resolution), -1);
    std::vector<glm::dvec2> slot_uv(footprint.points.size());
    std::vector<int32_t> slot_triangle(footprint.points.size(), -1);
    for (size_t i = 0; i < texels.size(); ++i) {
        const LightmapTexel& texel = texels[i];
        texel_index[size_t(texel.y) * size_t(resolution) + size_t(texel.x)] = int32_t(i);
        const uint64_t bits = mixBits((uint64_t(seed) << 32) ^ (uint64_t(texel.y) * uint64_t(resolution) + texel.x));
        const glm::dvec2 shift(unitFromBits(bits), unitFromBits(mixBits(bits)));
        for (size_t slot = 0; slot < slots_per_texel; ++slot)
            slot_uv[i * slots_per_texel + slot] =
                glm::dvec2(texel.x, texel.y) + patternPoint(int(slot), grid_side, shift);
    }

    // Every triangle offers itself to the slots inside it: the texel's own triangle first (so a footprint stays
    // on the owner's surface where two claims overlap), then the others in index order.
    auto offer = [&](size_t triangle, bool owners_only) {
        if (!hasWorldArea(mesh, triangle)) return;
        const detail::UvTriangle uv = uvTriangleInTexels(mesh, triangle, resolution);
        for (const glm::dvec2& corner : uv)
            if (!std::isfinite(corner.x) || !std::isfinite(corner.y)) return;
        const int first_x = int(std::fmax(0.0, std::floor(std::fmin(uv[0].x, std::fmin(uv[1].x, uv[2].x)))));
        const int last_x = int(std::fmin(double(resolution - 1), std::floor(std::fmax(uv[0].x, std::fmax(uv[1].x, uv[2].x)))));
        const int first_y = int(std::fmax(0.0, std::floor(std::fmin(uv[0].y, std::fmin(uv[1].y, uv[2].y)))));
        const int last_y = int(std::fmin(double(resolution - 1), std::floor(std::fmax(uv[0].y, std::fmax(uv[1].y, uv[2].y)))));
        for (int y = first_y; y <= last_y; ++y)
            for (int x = first_x; x <= last_x; ++x) {
                const int32_t i = texel_index[size_t(y) * size_t(resolution) + size_t(x)];
                if (i < 0 || (texels[size_t(i)].triangle == triangle) != owners_only) continue;
                for (size_t slot = size_t(i) * slots_per_texel; slot < size_t(i + 1) * slots_per_texel; ++slot)
                    if (slot_triangle[slot] < 0 && detail::containsPoint(uv, slot_uv[slot]))
                        slot_triangle[slot] = int32_t(triangle);
            }
    };
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) offer(triangle, true);
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) offer(triangle, false);

    std::vector<size_t> covered;
    for (size_t i = 0; i < texels.size(); ++i) {
        const size_t first = i * slots_per_texel;
        covered.clear();
        for (size_t slot = first; slot < first + slots_per_texel; ++slot) {
            if (slot_triangle[slot] < 0) continue;
            const size_t triangle = size_t(slot_triangle[slot]);
            const glm::dvec3 weights = detail::nearestBarycentric(uvTriangleInTexels(mesh, triangle, resolution),
                                                                  slot_uv[slot]);
            const detail::SurfacePoint point = detail::surfacePointAt(mesh, triangle, weights);
            footprint.points[slot].position = point.position;
            footprint.points[slot].shading_normal = point.shading_normal;
            footprint.points[slot].geometric_normal = point.geometric_normal;
            covered.push_back(slot);
        }
        if (covered.empty()) {  // a fallback claim: the texel's own point, in every slot
            for (size_t slot = first; slot < first + slots_per_texel; ++slot)
                footprint.points[slot] = {texels[i].position, texels[i].shading_normal, texels[i].geometric_normal,
                                          1.0f / float(slots_per_texel)};
            continue;
        }
        // Empty slots repeat the covered sub-points in turn; each covered sub-point then splits 1 / covered
        // among the slots that trace it.
        std::vector<int> repeats(slots_per_texel, 0);
        size_t next = 0;
        std::vector<size_t> source(slots_per_texel);
        for (size_t slot = first; slot < first + slots_per_texel; ++slot) {
            if (slot_triangle[slot] >= 0) {
                source[slot - first] = slot;
            } else {
                source[slot - first] = covered[next];
                footprint.points[slot].position = footprint.points[covered[next]].position;
                footprint.points[slot].shading_normal = footprint.points[covered[next]].shading_normal;
                footprint.points[slot].geometric_normal = footprint.points[covered[next]].geometric_normal;
                next = (next + 1) % covered.size();
            }
            ++repeats[source[slot - first] - first];
        }
        for (size_t slot = first; slot < first + slots_per_texel; ++slot)
            footprint.points[slot].weight =
                1.0f / (float(covered.size()) * float(repeats[source[slot - first] - first]));
    }
    return footprint;
}

uint64_t keptFootprintSlots(const LightmapFootprint& footprint, const std::vector<glm::vec4>& slot_sums, size_t texel,
                            uint32_t samples_per_slot, float max_invalid_fraction) {
    const size_t slots_per_texel = footprint.pointsPerTexel();
    const size_t first = texel * slots_per_texel;
    const double inverse_samples = 1.0 / double(samples_per_slot);
    uint64_t valid = 0;
    double invalid_weight = 0.0;
    for (size_t k = 0; k < slots_per_texel; ++k) {
        if (slot_sums[first + k].w * inverse_samples <= max_invalid_fraction)
            valid |= uint64_t(1) << k;
        else
            invalid_weight += footprint.points[first + k].weight;
    }
    const uint64_t all = slots_per_texel >= 64 ? ~uint64_t(0) : (uint64_t(1) << slots_per_texel) - 1;
    return invalid_weight <= 0.5 ? valid : all & ~valid;
}

std::vector<glm::vec4> texelSumsFromFootprint(const LightmapFootprint& footprint,
                                              const std::vector<glm::vec4>& slot_sums, uint32_t samples_per_slot,
                                              float max_invalid_fraction) {
    const size_t slots_per_texel = footprint.pointsPerTexel();
    if (slot_sums.size() != footprint.points.size() || slots_per_texel == 0)
        throw InputError("lightmap", "footprint sums",
                         std::to_string(slot_sums.size()) + " sums for " + std::to_string(footprint.points.size()) +
                             " footprint points");
    const size_t texel_count = footprint.points.size() / slots_per_texel;
    std::vector<glm::vec4> texel_sums(texel_count, glm::vec4(0.0f));
    if (samples_per_slot == 0) return texel_sums;
    const double inverse_samples = 1.0 / double(samples_per_slot);
    const double texel_samples = double(samples_per_slot) * double(slots_per_texel);
    for (size_t i = 0; i < texel_count; ++i) {
        const uint64_t kept = keptFootprintSlots(footprint, slot_sums, i, samples_per_slot, max_invalid_fraction);
        glm::dvec4 mean(0.0);
        double weight_sum = 0.0;
        for (size_t k = 0; k < slots_per_texel; ++k) {
            if ((kept >> k & 1u) == 0) continue;
            const size_t slot = i * slots_per_texel + k;
            const double weight = footprint.points[slot].weight;
            mean += glm::dvec4(slot_sums[slot]) * (weight * inverse_samples);
            weight_sum += weight;
        }
        if (weight_sum > 0.0) texel_sums[i] = glm::vec4(mean * (texel_samples / weight_sum));
    }
    return texel_sums;
}

}  // namespace gusuku::bake

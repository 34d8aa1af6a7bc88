#include "invalid_texel_reasons.h"

#include <array>
#include <cmath>
#include <optional>
#include <numbers>

#include <glm/geometric.hpp>

#include "bake_outputs.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/closed_parts.h"

namespace gusuku::bake {

namespace {

// The tracer's ray offset (TracePass::ray_offset_m) and its score for a closed double-sided back
// (irradiance_paths.glsl's kDoubleSidedBackfaceScore).
constexpr float kRayOffsetM = 1e-3f;
constexpr double kClosedDoubleSidedScore = 0.1 / 0.9;

// An orthonormal frame about unit n.
void frameAbout(const glm::vec3& n, glm::vec3& tangent, glm::vec3& bitangent) {
    const glm::vec3 helper = std::abs(n.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    tangent = glm::normalize(glm::cross(helper, n));
    bitangent = glm::cross(n, tangent);
}

// The base colour's alpha at a hit (factor times the texture, bilinear with repeat wrapping as the tracer's
// sampleBaseColorAlpha), for the alpha test.
float alphaAt(const TriangleMesh& mesh, const Material& material, const BvhHit& hit) {
    float alpha = material.base_color_factor.a;
    if (material.base_color_texture < 0 || size_t(material.base_color_texture) >= mesh.textures.size() ||
        mesh.uv0.size() != mesh.positions.size())
        return alpha;
    const ImageRGBA& texture = mesh.textures[size_t(material.base_color_texture)];
    if (texture.width < 1 || texture.height < 1) return alpha;
    const uint32_t* corner = &mesh.indices[size_t(hit.triangle_index) * 3];
    const glm::vec2 uv = mesh.uv0[corner[0]] * (1.0f - hit.barycentric_u - hit.barycentric_v) +
                         mesh.uv0[corner[1]] * hit.barycentric_u + mesh.uv0[corner[2]] * hit.barycentric_v;
    const float fx = uv.x * float(texture.width) - 0.5f, fy = uv.y * float(texture.height) - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    auto wrapped = [](long value, int size) { return int(((value % size) + size) % size); };
    auto at = [&](float x, float y) {
        return texture.texel(wrapped(long(x), texture.width), wrapped(long(y), texture.height))[3];
    };
    const float tx = fx - x0, ty = fy - y0;
    const float top = at(x0, y0) * (1.0f - tx) + at(x0 + 1.0f, y0) * tx;
    const float bottom = at(x0, y0 + 1.0f) * (1.0f - tx) + at(x0 + 1.0f, y0 + 1.0f) * tx;
    return alpha * (top * (1.0f - ty) + bottom * ty);
}

// Closest hit that is not an alpha-masked material's hole: the tracer's rays pass through holes (its BVH runs the
// alpha test), so a ray that meets a leaf card's hole goes on to whatever is behind it, often a back face; without
// this the re-trace stops at the card and may name none where the tracer saw a back (a candidate for the shared
// house's 73-74 "unexplained" texels among its 4462 masked triangles; not yet re-counted on it).
std::optional<BvhHit> closestOpaqueHit(const Bvh& bvh, const TriangleMesh& mesh, glm::vec3 origin,
                                       const glm::vec3& direction) {
    for (int passed = 0; passed < 64; ++passed) {
        std::optional<BvhHit> hit = traceClosestCpu(bvh, origin, direction, 1e30f);
        if (!hit) return hit;
        const uint32_t material_index =
            hit->triangle_index < mesh.triangle_material.size() ? mesh.triangle_material[hit->triangle_index] : 0u;
        if (material_index >= mesh.materials.size() || !mesh.materials[material_index].alpha_masked) return hit;
        const Material& material = mesh.materials[material_index];
        if (alphaAt(mesh, material, *hit) >= material.alpha_cutoff) return hit;
        origin += direction * (hit->t + kRayOffsetM);  // through the hole
    }
    return std::nullopt;
}

}  // namespace

InvalidTexelAccounting::InvalidTexelAccounting(const BakeGeometry& geometry, const LightmapFootprint* footprint)
    : geometry_(geometry), footprint_(footprint), closed_(closedOutwardTriangles(geometry.scene.mesh)),
      reason_of_(geometry.texels.size(), int8_t(-1)) {}

void InvalidTexelAccounting::scorePoint(const glm::vec3& position, const glm::vec3& normal,
                                        const glm::vec3& geometric_normal, double score[3]) {
    const TriangleMesh& mesh = geometry_.scene.mesh;
    // The face plane on the shading normal's side, as the tracer takes it.
    const glm::vec3 face = glm::dot(geometric_normal, normal) < 0.0f ? -geometric_normal : geometric_normal;
    glm::vec3 tangent, bitangent;
    frameAbout(normal, tangent, bitangent);
    const glm::vec3 origin = position + normal * kRayOffsetM;
    constexpr int side = kInvalidReasonRaysPerSide;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            // Cosine-weighted, stratified: r = sqrt(u), phi = 2 pi v over cell centres.
            const double u = (i + 0.5) / side, v = (j + 0.5) / side;
            const double r = std::sqrt(u), phi = 2.0 * std::numbers::pi * v;
            const glm::vec3 direction = glm::normalize(tangent * float(r * std::cos(phi)) +
                                                       bitangent * float(r * std::sin(phi)) +
                                                       normal * float(std::sqrt(std::max(0.0, 1.0 - u))));
            if (glm::dot(direction, face) <= 0.0f) continue;
            const std::optional<BvhHit> hit = closestOpaqueHit(geometry_.cpuBvh(), mesh, origin, direction);
            if (!hit || hit->front_face) continue;
            const uint32_t material_index =
                hit->triangle_index < mesh.triangle_material.size() ? mesh.triangle_material[hit->triangle_index] : 0u;
            const bool double_sided =
                material_index < mesh.materials.size() && mesh.materials[material_index].double_sided;
            const bool building = hit->triangle_index < geometry_.scene.building_triangle_count;
            if (!double_sided)
                score[building ? 0 : 1] += 1.0;
            else if (closed_[hit->triangle_index])
                score[2] += kClosedDoubleSidedScore;
        }
}

InvalidTexelReason InvalidTexelAccounting::reason(size_t texel_index) {
    if (reason_of_[texel_index] >= 0) return InvalidTexelReason(reason_of_[texel_index]);
    const LightmapTexel& texel = geometry_.texels[texel_index];
    double score[3] = {};  // by InvalidTexelReason: one-sided, under ground, closed double-sided
    scorePoint(texel.position, texel.shading_normal, texel.geometric_normal, score);
    if (score[0] <= 0.0 && score[1] <= 0.0 && score[2] <= 0.0 && footprint_ != nullptr) {
        // The centre sees no back face: the footprint's sub-points, as the tracer traced them.
        const size_t per_texel = footprint_->pointsPerTexel();
        for (size_t slot = texel_index * per_texel; slot < (texel_index + 1) * per_texel; ++slot) {
            const LightmapFootprintPoint& point = footprint_->points[slot];
            scorePoint(point.position, point.shading_normal, point.geometric_normal, score);
        }
    }
    InvalidTexelReason found = InvalidTexelReason::Unexplained;
    double highest = 0.0;
    for (size_t k = 0; k < 3; ++k)
        if (score[k] > highest) {
            highest = score[k];
            found = InvalidTexelReason(k);
        }
    reason_of_[texel_index] = int8_t(found);
    return found;
}

InvalidTexelCounts InvalidTexelAccounting::count(const std::string& slot, const std::vector<glm::vec4>& texel_sums,
                                                 uint32_t samples) {
    InvalidTexelCounts counts;
    counts.slot = slot;
    const float inverse_samples = 1.0f / float(std::max(samples, 1u));
    for (size_t i = 0; i < texel_sums.size() && i < geometry_.texels.size(); ++i) {
        if (texel_sums[i].w * inverse_samples <= kMaxBackfaceFraction) continue;
        ++counts.total;
        switch (reason(i)) {
            case InvalidTexelReason::OneSidedBack: ++counts.one_sided_backs; break;
            case InvalidTexelReason::UnderGround: ++counts.under_ground; break;
            case InvalidTexelReason::ClosedDoubleSided: ++counts.closed_double_sided; break;
            case InvalidTexelReason::Unexplained: ++counts.unexplained; break;
        }
    }
    return counts;
}

}  // namespace gusuku::bake

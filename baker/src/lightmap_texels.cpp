// rasterizeLightmapTexels: which surface point (and normal) each lightmap texel stands for.

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_raster.h"

namespace gusuku::bake {
namespace {

// How a triangle claims a texel, strongest last: a claim of a stronger kind displaces a weaker one.
enum class ClaimKind : int8_t {
    Centroid = 0,  // the texel under the UV centroid of a triangle that covers no centre
    Near = 1,      // a centre within kNearClaimTexels of the triangle, inside none (lightmap_raster.h)
    Centre = 2,    // the centre inside the triangle
};

struct TexelClaim {
    int32_t triangle = -1;
    ClaimKind kind = ClaimKind::Centroid;
    double coverage = -1.0;  // Centre and Centroid: area of the triangle inside the texel, computed only when two
                             // claims meet; Near: the centre's distance to the triangle, negated (nearer wins)
};

detail::UvTriangle uvTriangleInTexels(const TriangleMesh& mesh, size_t triangle, int resolution) {
    detail::UvTriangle uv;
    for (int corner = 0; corner < 3; ++corner)
        uv[corner] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + corner]]) * double(resolution);
    return uv;
}

}  // namespace

std::vector<LightmapTexel> rasterizeLightmapTexels(const TriangleMesh& mesh, int resolution) {
    detail::validateLightmapMesh(mesh, resolution);

    const size_t texel_count = size_t(resolution) * size_t(resolution);
    std::vector<TexelClaim> claims(texel_count);
    std::vector<detail::UvTriangle> uv_triangles(mesh.triangleCount());

    auto coverageOf = [&](TexelClaim& claim, size_t texel) {
        if (claim.coverage < 0.0)
            claim.coverage = detail::areaInsideTexel(uv_triangles[claim.triangle], int(texel % resolution),
                                                     int(texel / resolution));
        return claim.coverage;
    };
    auto claimTexel = [&](size_t texel, int32_t triangle, ClaimKind kind, double near_distance = 0.0) {
        TexelClaim& held = claims[texel];
        TexelClaim incoming{triangle, kind, kind == ClaimKind::Near ? -near_distance : -1.0};
        if (held.triangle < 0 || kind > held.kind) {
            held = incoming;
            return;
        }
        if (kind != held.kind) return;  // a weaker claim never displaces a stronger one
        if (kind == ClaimKind::Near) {
            if (incoming.coverage > held.coverage) held = incoming;
            return;
        }
        if (coverageOf(incoming, texel) > coverageOf(held, texel)) held = incoming;
    };

    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        const glm::vec3& p0 = mesh.positions[mesh.indices[triangle * 3 + 0]];
        const glm::vec3& p1 = mesh.positions[mesh.indices[triangle * 3 + 1]];
        const glm::vec3& p2 = mesh.positions[mesh.indices[triangle * 3 + 2]];
        const float world_double_area = glm::length(glm::cross(p1 - p0, p2 - p0));
        if (!(world_double_area > 0.0f) || !std::isfinite(world_double_area)) continue;

        const detail::UvTriangle& uv = uv_triangles[triangle] = uvTriangleInTexels(mesh, triangle, resolution);
        bool finite = true;
        for (const glm::dvec2& corner : uv) finite = finite && std::isfinite(corner.x) && std::isfinite(corner.y);
        if (!finite) continue;

        const double min_u = std::fmin(uv[0].x, std::fmin(uv[1].x, uv[2].x));
        const double max_u = std::fmax(uv[0].x, std::fmax(uv[1].x, uv[2].x));
        const double min_v = std::fmin(uv[0].y, std::fmin(uv[1].y, uv[2].y));
        const double max_v = std::fmax(uv[0].y, std::fmax(uv[1].y, uv[2].y));
        // Texel centres x + 0.5 within [min_u, max_u], grown by the near-claim distance.
        const double near = detail::kNearClaimTexels;
        const int first_x = int(std::fmax(0.0, std::ceil(min_u - near - 0.5)));
        const int last_x = int(std::fmin(double(resolution - 1), std::floor(max_u + near - 0.5)));
        const int first_y = int(std::fmax(0.0, std::ceil(min_v - near - 0.5)));
        const int last_y = int(std::fmin(double(resolution - 1), std::floor(max_v + near - 0.5)));
        bool covered_a_centre = false;
        for (int y = first_y; y <= last_y; ++y) {
            for (int x = first_x; x <= last_x; ++x) {
                const glm::dvec2 centre(x + 0.5, y + 0.5);
                if (detail::containsPoint(uv, centre)) {
                    claimTexel(size_t(y) * resolution + x, int32_t(triangle), ClaimKind::Centre);
                    covered_a_centre = true;
                } else if (double distance = 0.0; detail::nearClaimsCentre(uv, centre, &distance)) {
                    claimTexel(size_t(y) * resolution + x, int32_t(triangle), ClaimKind::Near, distance);
                }
            }
        }
        if (!covered_a_centre) {
            // Thin or tiny in UV: still give it the texel under its centroid so it gets lit.
            const glm::dvec2 centroid = (uv[0] + uv[1] + uv[2]) / 3.0;
            const double x = std::floor(centroid.x), y = std::floor(centroid.y);
            if (x >= 0.0 && y >= 0.0 && x < resolution && y < resolution)
                claimTexel(size_t(y) * resolution + size_t(x), int32_t(triangle), ClaimKind::Centroid);
        }
    }

    std::vector<LightmapTexel> texels;
    for (size_t texel = 0; texel < texel_count; ++texel) {
        const TexelClaim& claim = claims[texel];
        if (claim.triangle < 0) continue;
        const size_t triangle = size_t(claim.triangle);
        LightmapTexel out;
        out.x = int(texel % resolution);
        out.y = int(texel / resolution);
        out.triangle = uint32_t(triangle);
        const glm::dvec3 weights =
            detail::nearestBarycentric(uv_triangles[triangle], glm::dvec2(out.x + 0.5, out.y + 0.5));
        const detail::SurfacePoint point = detail::surfacePointAt(mesh, triangle, weights);
        out.position = point.position;
        out.geometric_normal = point.geometric_normal;
        out.shading_normal = point.shading_normal;
        texels.push_back(out);
    }
    return texels;
}

}  // namespace gusuku::bake

#pragma once
// Private to the lightmap code: the one coverage rule (texel centre inside a triangle, with a tie rule that
// gives a centre on a shared edge to exactly one triangle) and the geometry the checker and the texel
// rasteriser share. All coordinates are in texel units (uv1 * resolution), in double.

#include <array>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake::detail {

using UvTriangle = std::array<glm::dvec2, 3>;

/// InputError naming the field when the resolution is outside [1, 16384], the mesh has no lightmap UVs (one per
/// vertex) or an index is out of range: what every lightmap rasteriser needs of its input.
void validateLightmapMesh(const TriangleMesh& mesh, int resolution);

/// Twice the signed area: cross(b - a, c - a), positive when the corners turn from +u towards +v.
double signedDoubleArea(const UvTriangle& triangle);

/// True when `point` lies inside the triangle. Each edge is evaluated with its end points in a canonical
/// (lexicographic) order, so two triangles sharing an edge compute exactly opposite values; a point exactly on
/// an edge belongs to the triangle that runs that edge from the lexicographically smaller end point.
/// Zero-area triangles contain nothing.
bool containsPoint(const UvTriangle& triangle, const glm::dvec2& point);

/// Area of the triangle inside the unit texel square [x, x+1] x [y, y+1] (Sutherland-Hodgman clipping).
double areaInsideTexel(const UvTriangle& triangle, int x, int y);

/// True when the triangle overlaps the open square (x0, x0 + side) x (y0, y0 + side) by some area (more than a
/// touch along an edge or a corner, within 1e-9 of a texel): separating axes, the square's two and the
/// triangle's three. A zero-area triangle meets every square its bounding box overlaps, conservatively.
bool triangleMeetsSquare(const UvTriangle& triangle, double x0, double y0, double side);

/// True when bilinear filtering at some point of the triangle reads texel (x, y), i.e. gives its centre
/// (x + 0.5, y + 0.5) a weight above zero: the centre lies less than one texel from the point on both axes, so the
/// triangle meets the open 2 x 2 square around the centre. The texels a chart's triangles read are the texels
/// that must hold that chart's value (its bilinear read set); a chart reads at most one texel beyond the texels
/// it touches. Conservative by kReadSlackTexels: uv1 is stored in float (an ulp is 2.4e-4 texel at 4096^2), so a
/// chart edge exactly one texel from a centre (a chart corner on a row of centres) may land just inside.
inline constexpr double kReadSlackTexels = 2e-3;
inline bool bilinearReadsTexel(const UvTriangle& triangle, int x, int y) {
    return triangleMeetsSquare(triangle, double(x) - 0.5 - kReadSlackTexels, double(y) - 0.5 - kReadSlackTexels,
                               2.0 + 2.0 * kReadSlackTexels);
}

/// The near-claim rule: a texel centre that no triangle contains but that lies within kNearClaimTexels of one is
/// that triangle's (the nearest's, when several are that near). The packer's spanned frames
/// (lightmap_chart_frames.cpp) end a chart a hundredth of a texel inside its end centres, so that it reads no texel
/// beyond them, and this rule still traces those centres. Ordinary charts keep their edges 0.05 texel clear of
/// rows of centres, and are not affected.
inline constexpr double kNearClaimTexels = 0.02;
/// `distance`, when given, receives the centre's distance to the triangle where the rule claims it.
bool nearClaimsCentre(const UvTriangle& triangle, const glm::dvec2& centre, double* distance = nullptr);

/// Distance from `point` to the triangle (0 inside), in texels.
double distanceToTriangle(const UvTriangle& triangle, const glm::dvec2& point);

/// Barycentric weights of the point of the triangle nearest `point` (the point itself when inside); for a
/// zero-area triangle, the nearest point on its longest edge.
glm::dvec3 nearestBarycentric(const UvTriangle& triangle, const glm::dvec2& point);

/// The point of a mesh triangle at barycentric `weights`: position, interpolated vertex normal (normalised;
/// the geometric normal where it is zero or the mesh has no normals) and the unit geometric normal from the
/// counter-clockwise winding. One function for the texel centres and the footprint sub-points.
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 shading_normal{0.0f};
    glm::vec3 geometric_normal{0.0f};
};
SurfacePoint surfacePointAt(const TriangleMesh& mesh, size_t triangle, const glm::dvec3& weights);

}  // namespace gusuku::bake::detail

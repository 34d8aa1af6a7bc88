// The coverage rule shared by the lightmap UV checker and the texel rasteriser (see lightmap_raster.h).

#include "lightmap_raster.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/formats/input_error.h"

namespace gusuku::bake::detail {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

bool lexicographicallyLess(const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

// Keeps the part of `polygon` where sign * (coordinate[axis] - bound) >= 0.
std::vector<glm::dvec2> clipAgainst(const std::vector<glm::dvec2>& polygon, int axis, double bound, double sign) {
    std::vector<glm::dvec2> clipped;
    const size_t count = polygon.size();
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec2& current = polygon[i];
        const glm::dvec2& next = polygon[(i + 1) % count];
        const double current_distance = sign * (current[axis] - bound);
        const double next_distance = sign * (next[axis] - bound);
        if (current_distance >= 0.0) clipped.push_back(current);
        if ((current_distance >= 0.0) != (next_distance >= 0.0)) {
            const double t = current_distance / (current_distance - next_distance);
            clipped.push_back(current + (next - current) * t);
        }
    }
    return clipped;
}

}  // namespace

double signedDoubleArea(const UvTriangle& triangle) {
    return cross2(triangle[1] - triangle[0], triangle[2] - triangle[0]);
}

bool containsPoint(const UvTriangle& triangle, const glm::dvec2& point) {
    const double double_area = signedDoubleArea(triangle);
    if (double_area == 0.0 || !std::isfinite(double_area)) return false;
    const double orientation = double_area > 0.0 ? 1.0 : -1.0;
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2& start = triangle[edge];
        const glm::dvec2& end = triangle[(edge + 1) % 3];
        // Evaluate in canonical order so that the neighbour across this edge gets exactly the negated value.
        const bool runs_low_to_high = lexicographicallyLess(start, end);
        const glm::dvec2& low = runs_low_to_high ? start : end;
        const glm::dvec2& high = runs_low_to_high ? end : start;
        const double canonical = cross2(high - low, point - low);
        const double side = runs_low_to_high ? canonical : -canonical;
        if (orientation * side < 0.0) return false;
        if (side == 0.0 && !runs_low_to_high) return false;
    }
    return true;
}

bool triangleMeetsSquare(const UvTriangle& triangle, double x0, double y0, double side) {
    constexpr double kTouch = 1e-9;  // overlaps thinner than this (texels) are touches
    const double low_x = std::min({triangle[0].x, triangle[1].x, triangle[2].x});
    const double high_x = std::max({triangle[0].x, triangle[1].x, triangle[2].x});
    const double low_y = std::min({triangle[0].y, triangle[1].y, triangle[2].y});
    const double high_y = std::max({triangle[0].y, triangle[1].y, triangle[2].y});
    if (!(high_x > x0 + kTouch && low_x < x0 + side - kTouch && high_y > y0 + kTouch && low_y < y0 + side - kTouch))
        return false;
    const double orientation = signedDoubleArea(triangle);
    if (!(std::abs(orientation) > 1e-12)) return true;
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2& start = triangle[edge];
        const glm::dvec2& end = triangle[(edge + 1) % 3];
        // Inward normal of the edge; the square is separated when all its corners lie on the outer side.
        const glm::dvec2 inward = orientation > 0.0 ? glm::dvec2(start.y - end.y, end.x - start.x)
                                                    : glm::dvec2(end.y - start.y, start.x - end.x);
        double most_inside = -INFINITY;
        for (int corner = 0; corner < 4; ++corner) {
            const glm::dvec2 point(x0 + side * double(corner & 1), y0 + side * double(corner >> 1));
            most_inside = std::max(most_inside, glm::dot(point - start, inward));
        }
        if (most_inside <= kTouch * glm::length(inward)) return false;
    }
    return true;
}

double areaInsideTexel(const UvTriangle& triangle, int x, int y) {
    std::vector<glm::dvec2> polygon(triangle.begin(), triangle.end());
    polygon = clipAgainst(polygon, 0, double(x), 1.0);
    if (polygon.empty()) return 0.0;
    polygon = clipAgainst(polygon, 0, double(x + 1), -1.0);
    if (polygon.empty()) return 0.0;
    polygon = clipAgainst(polygon, 1, double(y), 1.0);
    if (polygon.empty()) return 0.0;
    polygon = clipAgainst(polygon, 1, double(y + 1), -1.0);
    if (polygon.size() < 3) return 0.0;
    double double_area = 0.0;
    for (size_t i = 0; i < polygon.size(); ++i)
        double_area += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
    return std::abs(double_area) * 0.5;
}

glm::dvec3 nearestBarycentric(const UvTriangle& triangle, const glm::dvec2& point) {
    const double double_area = signedDoubleArea(triangle);
    if (double_area != 0.0 && std::isfinite(double_area)) {
        const double w0 = cross2(triangle[2] - triangle[1], point - triangle[1]) / double_area;
        const double w1 = cross2(triangle[0] - triangle[2], point - triangle[2]) / double_area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) return {w0, w1, w2};
    }
    // Outside (or zero area): the nearest point lies on one of the edges.
    glm::dvec3 best_weights{1.0 / 3.0};
    double best_distance2 = INFINITY;
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2& start = triangle[edge];
        const glm::dvec2& end = triangle[(edge + 1) % 3];
        const glm::dvec2 direction = end - start;
        const double length2 = direction.x * direction.x + direction.y * direction.y;
        double t = length2 > 0.0 ? ((point - start).x * direction.x + (point - start).y * direction.y) / length2 : 0.0;
        t = std::fmin(1.0, std::fmax(0.0, t));
        const glm::dvec2 nearest = start + direction * t;
        const double distance2 = (point - nearest).x * (point - nearest).x + (point - nearest).y * (point - nearest).y;
        if (distance2 < best_distance2) {
            best_distance2 = distance2;
            best_weights = glm::dvec3(0.0);
            best_weights[edge] = 1.0 - t;
            best_weights[(edge + 1) % 3] = t;
        }
    }
    return best_weights;
}

double distanceToTriangle(const UvTriangle& triangle, const glm::dvec2& point) {
    const glm::dvec3 weights = nearestBarycentric(triangle, point);
    const glm::dvec2 nearest = triangle[0] * weights[0] + triangle[1] * weights[1] + triangle[2] * weights[2];
    return glm::length(point - nearest);
}

bool nearClaimsCentre(const UvTriangle& triangle, const glm::dvec2& centre, double* distance) {
    const double low_x = std::min({triangle[0].x, triangle[1].x, triangle[2].x});
    const double high_x = std::max({triangle[0].x, triangle[1].x, triangle[2].x});
    const double low_y = std::min({triangle[0].y, triangle[1].y, triangle[2].y});
    const double high_y = std::max({triangle[0].y, triangle[1].y, triangle[2].y});
    if (centre.x < low_x - kNearClaimTexels || centre.x > high_x + kNearClaimTexels ||
        centre.y < low_y - kNearClaimTexels || centre.y > high_y + kNearClaimTexels)
        return false;
    if (!(std::abs(signedDoubleArea(triangle)) > 0.0)) return false;  // zero area: the centroid fallback's
    if (containsPoint(triangle, centre)) return false;
    const double to_triangle = distanceToTriangle(triangle, centre);
    if (distance) *distance = to_triangle;
    return to_triangle < kNearClaimTexels;
}

// A traced point is kept this far inside its triangle, in metres: a point on an edge where the face meets the ground
// (a near-claimed centre, a footprint sub-point on the chart's edge) is offset along its normal only, which leaves it
// on the ground's plane, and its rays below the horizon cross the ground at a distance of 0, which the tracer's
// t_min lets through: a 2 cm platform's side face read the sky under the ground (pi L of a uniform sky, the truth
// pi L (1 + a) / 2) on its bottom row of texels. Twice the tracer's 1 mm ray offset.
constexpr double kTracedPointInsetM = 2e-3;

// The barycentric weights of the point moved square to each edge it lies nearer than kTracedPointInsetM, to that
// distance (at most to the middle of the triangle's altitude there: a triangle thinner than twice the inset keeps
// its point half way across): along the surface, never along the edge, so a point stays in its texel's footprint.
static glm::dvec3 weightsInsideEdges(const glm::dvec3 corners[3], const glm::dvec3& weights) {
    const double double_area = glm::length(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
    if (!(double_area > 0.0)) return weights;
    glm::dvec3 moved = weights;
    for (int k = 0; k < 3; ++k) {
        // The distance to the edge opposite corner k is its weight times that corner's altitude; moving square to
        // the edge by delta adds delta / altitude to it and takes the same from the other two in proportion to the
        // altitude's foot on the edge (so the move has no component along the edge).
        const glm::dvec3& a = corners[(k + 1) % 3];
        const glm::dvec3& b = corners[(k + 2) % 3];
        const double edge_length = glm::length(b - a);
        const double altitude = double_area / edge_length;
        const double distance = moved[k] * altitude;
        const double target = std::min(kTracedPointInsetM, 0.5 * altitude);
        if (distance >= target) continue;
        const double foot = glm::dot(corners[k] - a, b - a) / (edge_length * edge_length);  // along a -> b
        const double step = (target - distance) / altitude;
        moved[k] += step;
        moved[(k + 1) % 3] -= step * (1.0 - foot);
        moved[(k + 2) % 3] -= step * foot;
    }
    // An obtuse corner's foot lies beyond the edge: keep the weights a point of the triangle.
    moved = glm::max(moved, glm::dvec3(0.0));
    const double sum = moved.x + moved.y + moved.z;
    return sum > 0.0 ? moved / sum : weights;
}

SurfacePoint surfacePointAt(const TriangleMesh& mesh, size_t triangle, const glm::dvec3& edge_weights) {
    glm::dvec3 position{0.0};
    glm::dvec3 shading_normal{0.0};
    glm::dvec3 corners[3];
    for (int corner = 0; corner < 3; ++corner)
        corners[corner] = glm::dvec3(mesh.positions[mesh.indices[triangle * 3 + corner]]);
    const glm::dvec3 weights = weightsInsideEdges(corners, edge_weights);
    for (int corner = 0; corner < 3; ++corner) {
        const uint32_t vertex = mesh.indices[triangle * 3 + corner];
        position += corners[corner] * weights[corner];
        if (vertex < mesh.normals.size()) shading_normal += glm::dvec3(mesh.normals[vertex]) * weights[corner];
    }
    const glm::dvec3 geometric_normal = glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
    const double shading_length = glm::length(shading_normal);
    SurfacePoint point;
    point.position = glm::vec3(position);
    point.geometric_normal = glm::vec3(geometric_normal);
    point.shading_normal = shading_length > 1e-12 && std::isfinite(shading_length)
                               ? glm::vec3(shading_normal / shading_length)
                               : point.geometric_normal;
    return point;
}

void validateLightmapMesh(const TriangleMesh& mesh, int resolution) {
    if (resolution < 1 || resolution > 16384)
        throw InputError("lightmap", "resolution", "must be in [1, 16384], got " + std::to_string(resolution));
    if (!mesh.has_uv1 || mesh.uv1.size() != mesh.positions.size())
        throw InputError("lightmap", "TEXCOORD_1", "the mesh has no lightmap UVs (one per vertex)");
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
}

}  // namespace gusuku::bake::detail

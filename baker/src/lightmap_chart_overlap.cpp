// Whether a flattened triangle overlaps the chart being grown or joined (FlatChartIndex, lightmap_charting.h):
// the exact test of two flattened triangles, and the grid that puts it to the chart's nearby triangles only.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lightmap_charting.h"

namespace gusuku::bake::detail {
namespace {

// True when two flattened triangles of one chart overlap by more than `tolerance` (metres): duplicated faces,
// triangles folded over a shared edge, or separate parts of the surface that land on each other. Corners with the
// same welded vertex are one point when they lie within `same_point` of each other (an unfolded chart is cut
// through some vertices, whose corners then lie apart).
bool flatTrianglesOverlap(const FlatTriangle& a, const FlatTriangle& b, double tolerance, double same_point) {
    if (a.max.x <= b.min.x + tolerance || b.max.x <= a.min.x + tolerance || a.max.y <= b.min.y + tolerance ||
        b.max.y <= a.min.y + tolerance)
        return false;
    int shared = 0;
    int a_shared[3] = {-1, -1, -1};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a.welded[i] == b.welded[j] && glm::length(a.corner[i] - b.corner[j]) <= same_point) {
                a_shared[i] = j;
                ++shared;
            }
    const double a_area = std::abs(cross2(a.corner[1] - a.corner[0], a.corner[2] - a.corner[0]));
    const double b_area = std::abs(cross2(b.corner[1] - b.corner[0], b.corner[2] - b.corner[0]));
    if (shared >= 3) return a_area > tolerance * tolerance && b_area > tolerance * tolerance;
    if (shared == 2) {
        // Across a shared edge they overlap exactly when their third corners lie on the same side of it.
        int edge_start = -1, a_third = -1;
        for (int i = 0; i < 3; ++i) {
            if (a_shared[i] < 0) a_third = i;
            else if (edge_start < 0) edge_start = i;
        }
        int edge_end = -1;
        for (int i = 0; i < 3; ++i)
            if (a_shared[i] >= 0 && i != edge_start) edge_end = i;
        int b_third = 3 - a_shared[edge_start] - a_shared[edge_end];
        const glm::dvec2 p = a.corner[edge_start], q = a.corner[edge_end];
        const double edge_length = glm::length(q - p);
        const double a_side = cross2(q - p, a.corner[a_third] - p) / std::max(edge_length, 1e-300);
        const double b_side = cross2(q - p, b.corner[b_third] - p) / std::max(edge_length, 1e-300);
        return (a_side > tolerance && b_side > tolerance) || (a_side < -tolerance && b_side < -tolerance);
    }
    // Separating axes: the six edge normals. Touching (depth <= tolerance) is not overlapping.
    for (const FlatTriangle* owner : {&a, &b}) {
        for (int edge = 0; edge < 3; ++edge) {
            const glm::dvec2 direction = owner->corner[(edge + 1) % 3] - owner->corner[edge];
            const double length = glm::length(direction);
            if (!(length > 0.0)) continue;
            const glm::dvec2 axis(-direction.y / length, direction.x / length);
            double a_min = INFINITY, a_max = -INFINITY, b_min = INFINITY, b_max = -INFINITY;
            for (int i = 0; i < 3; ++i) {
                const double a_projection = glm::dot(a.corner[i], axis);
                const double b_projection = glm::dot(b.corner[i], axis);
                a_min = std::min(a_min, a_projection);
                a_max = std::max(a_max, a_projection);
                b_min = std::min(b_min, b_projection);
                b_max = std::max(b_max, b_projection);
            }
            if (std::min(a_max, b_max) - std::max(a_min, b_min) <= tolerance) return false;
        }
    }
    return true;
}

}  // namespace

bool FlatChartIndex::overlapsAny(const FlatTriangle& candidate) {
    ++query_stamp_;
    auto test = [&](uint32_t member) {
        if (tested_stamp_[member] == query_stamp_) return false;
        tested_stamp_[member] = query_stamp_;
        return flatTrianglesOverlap(members_[member], candidate, tolerance_, same_point_);
    };
    for (uint32_t member : large_members_)
        if (test(member)) return true;
    if (isLarge(candidate)) {
        for (uint32_t member = 0; member < members_.size(); ++member)
            if (test(member)) return true;
        return false;
    }
    const glm::ivec4 cells = cellRange(candidate);
    for (int y = cells.y; y <= cells.w; ++y)
        for (int x = cells.x; x <= cells.z; ++x) {
            auto it = cells_.find(key(x, y));
            if (it == cells_.end()) continue;
            for (uint32_t member : it->second)
                if (test(member)) return true;
        }
    return false;
}

void FlatChartIndex::add(const FlatTriangle& triangle) {
    const uint32_t member = uint32_t(members_.size());
    members_.push_back(triangle);
    tested_stamp_.push_back(0);
    if (isLarge(triangle)) {
        large_members_.push_back(member);
        return;
    }
    const glm::ivec4 cells = cellRange(triangle);
    for (int y = cells.y; y <= cells.w; ++y)
        for (int x = cells.x; x <= cells.z; ++x) cells_[key(x, y)].push_back(member);
}

}  // namespace gusuku::bake::detail

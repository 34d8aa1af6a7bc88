// Phases 2-4 of generateLightmapCharts (lightmap_charting.h): weld, measure and connect the building's
// triangles; grow nearly planar charts from the largest triangles out, each neighbour unfolded about the edge it
// joins across; give the degenerate triangles (no area) to a neighbour's chart.

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <numeric>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "lightmap_charting.h"

namespace gusuku::bake::detail {
namespace {

constexpr double kMaxNormalDeviationDeg = 40.0;  // beyond this, projection stretches a texel by over 1/cos(40)
constexpr double kWeldToleranceOfDiagonal = 1e-6;

uint64_t cellKey(int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x) * 73856093ull) ^ (uint64_t(y) * 19349663ull) ^ (uint64_t(z) * 83492791ull);
}

// Welded vertex id for every vertex: vertices within `tolerance` (per axis) of an earlier one share its id.
std::vector<uint32_t> weldPositions(const std::vector<glm::vec3>& positions, double tolerance) {
    std::unordered_map<uint64_t, std::vector<uint32_t>> representatives_by_cell;
    representatives_by_cell.reserve(positions.size());
    std::vector<uint32_t> welded(positions.size());
    std::vector<glm::dvec3> representative_positions;
    for (size_t vertex = 0; vertex < positions.size(); ++vertex) {
        const glm::dvec3 position(positions[vertex]);
        const glm::dvec3 cell = glm::floor(position / tolerance);
        int64_t found = -1;
        for (int dz = -1; dz <= 1 && found < 0; ++dz)
            for (int dy = -1; dy <= 1 && found < 0; ++dy)
                for (int dx = -1; dx <= 1 && found < 0; ++dx) {
                    auto it = representatives_by_cell.find(
                        cellKey(int64_t(cell.x) + dx, int64_t(cell.y) + dy, int64_t(cell.z) + dz));
                    if (it == representatives_by_cell.end()) continue;
                    for (uint32_t candidate : it->second) {
                        const glm::dvec3 offset = glm::abs(representative_positions[candidate] - position);
                        if (offset.x <= tolerance && offset.y <= tolerance && offset.z <= tolerance) {
                            found = candidate;
                            break;
                        }
                    }
                }
        if (found < 0) {
            found = int64_t(representative_positions.size());
            representative_positions.push_back(position);
            representatives_by_cell[cellKey(int64_t(cell.x), int64_t(cell.y), int64_t(cell.z))].push_back(
                uint32_t(found));
        }
        welded[vertex] = uint32_t(found);
    }
    return welded;
}

EdgeNeighbours findChartableNeighbours(const std::vector<TriangleInfo>& triangles) {
    // slot * 2 + (1 when the slot runs its edge from the smaller welded index to the larger)
    std::unordered_map<uint64_t, std::vector<uint64_t>> uses;
    uses.reserve(triangles.size() * 2);
    for (size_t triangle = 0; triangle < triangles.size(); ++triangle) {
        // Degenerate triangles (slivers, collapsed poles) would tie unrelated triangles together across their
        // collapsed edges; they join a neighbour's chart afterwards instead.
        if (triangles[triangle].degenerate) continue;
        for (int edge = 0; edge < 3; ++edge) {
            const uint32_t a = triangles[triangle].welded[edge];
            const uint32_t b = triangles[triangle].welded[(edge + 1) % 3];
            const bool forward = a < b;
            const uint64_t key = forward ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
            uses[key].push_back(uint64_t(triangle * 3 + edge) * 2 + (forward ? 1 : 0));
        }
    }
    std::vector<std::vector<uint32_t>> per_slot(triangles.size() * 3);
    for (const auto& [key, slots] : uses)
        for (uint64_t first : slots)
            for (uint64_t second : slots)
                if ((first & 1) != (second & 1)) per_slot[first >> 1].push_back(uint32_t((second >> 1) / 3));
    EdgeNeighbours result;
    result.offsets.reserve(per_slot.size() + 1);
    result.offsets.push_back(0);
    for (const std::vector<uint32_t>& list : per_slot) {
        result.neighbours.insert(result.neighbours.end(), list.begin(), list.end());
        result.offsets.push_back(uint32_t(result.neighbours.size()));
    }
    return result;
}

// An orthonormal tangent basis of the plane with this unit normal.
void planeBasis(const glm::dvec3& normal, glm::dvec3* tangent, glm::dvec3* bitangent) {
    const glm::dvec3 helper = std::abs(normal.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    *tangent = glm::normalize(glm::cross(helper, normal));
    *bitangent = glm::cross(normal, *tangent);
}

// Where a chart has put each welded vertex (more than one place where the chart is cut through it).
using PlacedCorners = std::unordered_map<uint32_t, std::vector<glm::dvec2>>;

glm::dvec3 meshCorner(const TriangleMesh& mesh, uint32_t triangle, int i) {
    return glm::dvec3(mesh.positions[mesh.indices[size_t(triangle) * 3 + size_t(i)]]);
}

// Completes a flattened triangle whose corners are set: its welded vertices and bounds.
void finishFlatTriangle(FlatTriangle& flat, const TriangleInfo& info) {
    flat.min = glm::dvec2(INFINITY);
    flat.max = glm::dvec2(-INFINITY);
    for (int i = 0; i < 3; ++i) {
        flat.welded[i] = info.welded[i];
        flat.min = glm::min(flat.min, flat.corner[i]);
        flat.max = glm::max(flat.max, flat.corner[i]);
    }
}

void placeCorners(PlacedCorners& placed, const FlatTriangle& flat) {
    for (int i = 0; i < 3; ++i) {
        std::vector<glm::dvec2>& at = placed[flat.welded[i]];
        if (std::find(at.begin(), at.end(), flat.corner[i]) == at.end()) at.push_back(flat.corner[i]);
    }
}

// Triangle `next` unfolded about the edge it shares with `parent` (parent's edge parent_edge), its lengths and
// angles kept: a developable surface, a pillar's facets or a bent sheet, lies flat at the density.
FlatTriangle unfoldAboutEdge(const TriangleMesh& mesh, const std::vector<TriangleInfo>& triangles,
                             const PlacedCorners& placed, double snap_tolerance, const FlatTriangle& parent,
                             int parent_edge, uint32_t next) {
    const uint32_t a = parent.welded[parent_edge], b = parent.welded[(parent_edge + 1) % 3];
    int at_a = 0, at_b = 0;
    for (int i = 0; i < 3; ++i) {
        if (triangles[next].welded[i] == a) at_a = i;
        if (triangles[next].welded[i] == b) at_b = i;
    }
    const int at_c = 3 - at_a - at_b;
    const glm::dvec2 pa = parent.corner[parent_edge], pb = parent.corner[(parent_edge + 1) % 3];
    const glm::dvec3 edge3 = meshCorner(mesh, next, at_b) - meshCorner(mesh, next, at_a);
    const glm::dvec3 to_c = meshCorner(mesh, next, at_c) - meshCorner(mesh, next, at_a);
    const double length3 = std::max(glm::length(edge3), 1e-300);
    const glm::dvec2 edge2 = pb - pa;
    const double length2 = std::max(glm::length(edge2), 1e-300);
    const double along = glm::dot(to_c, edge3) / length3 * (length2 / length3);
    const double across = glm::length(glm::cross(to_c, edge3)) / length3;
    const glm::dvec2 direction = edge2 / length2, left(-direction.y, direction.x);
    FlatTriangle flat;
    flat.corner[at_a] = pa;
    flat.corner[at_b] = pb;
    flat.corner[at_c] = pa + along * direction + across * left;
    if (cross2(flat.corner[1] - flat.corner[0], flat.corner[2] - flat.corner[0]) < 0.0)
        flat.corner[at_c] = pa + along * direction - across * left;
    // A corner the chart already has within the snap tolerance is that point (a fan closing round a vertex).
    if (auto it = placed.find(triangles[next].welded[at_c]); it != placed.end())
        for (const glm::dvec2& point : it->second)
            if (glm::length(point - flat.corner[at_c]) <= snap_tolerance) {
                flat.corner[at_c] = point;
                break;
            }
    finishFlatTriangle(flat, triangles[next]);
    return flat;
}

}  // namespace

// Phase 2: weld, measure and connect the triangles.
MeshAnalysis analyseMesh(const TriangleMesh& mesh, double texels_per_metre) {
    glm::dvec3 low(INFINITY), high(-INFINITY);
    for (const glm::vec3& position : mesh.positions) {
        low = glm::min(low, glm::dvec3(position));
        high = glm::max(high, glm::dvec3(position));
    }
    const double diagonal = std::max(glm::length(high - low), 1e-9);
    const double magnitude = std::max(glm::length(high), glm::length(low));
    const std::vector<uint32_t> welded = weldPositions(mesh.positions, kWeldToleranceOfDiagonal * diagonal);

    MeshAnalysis analysis;
    const size_t triangle_count = mesh.triangleCount();
    analysis.triangles.resize(triangle_count);
    std::vector<double> edge_lengths;
    edge_lengths.reserve(triangle_count);
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        TriangleInfo& info = analysis.triangles[triangle];
        glm::dvec3 corner[3];
        for (int i = 0; i < 3; ++i) {
            info.welded[i] = welded[mesh.indices[triangle * 3 + i]];
            corner[i] = glm::dvec3(mesh.positions[mesh.indices[triangle * 3 + i]]);
        }
        const glm::dvec3 scaled_normal = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
        const double double_area = glm::length(scaled_normal);
        info.area = 0.5 * double_area;
        info.degenerate = !(double_area > 1e-12 * diagonal * diagonal) || info.welded[0] == info.welded[1] ||
                          info.welded[1] == info.welded[2] || info.welded[0] == info.welded[2];
        if (!info.degenerate) {
            info.normal = scaled_normal / double_area;
            edge_lengths.push_back(glm::length(corner[1] - corner[0]));
        }
    }
    analysis.adjacency = findChartableNeighbours(analysis.triangles);

    analysis.typical_edge = diagonal * 1e-3;
    if (!edge_lengths.empty()) {
        std::nth_element(edge_lengths.begin(), edge_lengths.begin() + edge_lengths.size() / 2, edge_lengths.end());
        analysis.typical_edge = std::max(edge_lengths[edge_lengths.size() / 2], diagonal * 1e-6);
    }
    // Overlaps thinner than a ten-thousandth of a texel, or than float noise at this distance from the origin,
    // are touching, not overlapping.
    analysis.overlap_tolerance = std::max(1e-4 / texels_per_metre, 4e-7 * magnitude);
    return analysis;
}

// Phase 3: grow charts from the largest triangles first, so big flat walls seed big charts. A neighbour joins
// when its normal is within kMaxNormalDeviationDeg of the seed's and its unfolded shape overlaps nothing in
// the chart. chart_of[triangle] is set for every non-degenerate triangle.
std::vector<Chart> growCharts(const TriangleMesh& mesh, const MeshAnalysis& analysis, double snap_tolerance,
                              std::vector<int64_t>& chart_of) {
    const std::vector<TriangleInfo>& triangles = analysis.triangles;
    const size_t triangle_count = triangles.size();
    std::vector<uint32_t> seed_order(triangle_count);
    std::iota(seed_order.begin(), seed_order.end(), 0u);
    std::stable_sort(seed_order.begin(), seed_order.end(), [&](uint32_t a, uint32_t b) {
        if (triangles[a].degenerate != triangles[b].degenerate) return !triangles[a].degenerate;
        return triangles[a].area > triangles[b].area;
    });
    const double min_normal_dot = std::cos(kMaxNormalDeviationDeg * std::numbers::pi / 180.0);
    chart_of.assign(triangle_count, -1);
    std::vector<int64_t> rejected_by_chart(triangle_count, -1);
    std::vector<FlatTriangle> flat_of(triangle_count);  // of the triangles that joined a chart
    PlacedCorners placed;
    std::vector<Chart> charts;
    for (uint32_t seed : seed_order) {
        if (chart_of[seed] >= 0 || triangles[seed].degenerate) continue;
        const int64_t chart_index = int64_t(charts.size());
        Chart chart;
        const glm::dvec3 seed_normal = triangles[seed].normal;
        planeBasis(seed_normal, &chart.tangent, &chart.bitangent);
        placed.clear();
        FlatChartIndex index(4.0 * analysis.typical_edge, analysis.overlap_tolerance, snap_tolerance);
        std::deque<uint32_t> frontier{seed};
        chart_of[seed] = chart_index;
        // The seed onto its own plane; every other triangle unfolded about the edge it joins across.
        for (int i = 0; i < 3; ++i) {
            const glm::dvec3 position = meshCorner(mesh, seed, i);
            flat_of[seed].corner[i] = glm::dvec2(glm::dot(position, chart.tangent), glm::dot(position, chart.bitangent));
        }
        finishFlatTriangle(flat_of[seed], triangles[seed]);
        index.add(flat_of[seed]);
        placeCorners(placed, flat_of[seed]);
        while (!frontier.empty()) {
            const uint32_t triangle = frontier.front();
            frontier.pop_front();
            chart.triangles.push_back(triangle);
            chart.corners.insert(chart.corners.end(), flat_of[triangle].corner, flat_of[triangle].corner + 3);
            const EdgeNeighbours& adjacency = analysis.adjacency;
            for (int edge = 0; edge < 3; ++edge) {
                const size_t slot = size_t(triangle) * 3 + size_t(edge);
                for (uint32_t at = adjacency.offsets[slot]; at < adjacency.offsets[slot + 1]; ++at) {
                    const uint32_t next = adjacency.neighbours[at];
                    if (chart_of[next] >= 0 || rejected_by_chart[next] == chart_index) continue;
                    const TriangleInfo& info = triangles[size_t(next)];
                    const bool similar = glm::dot(info.normal, seed_normal) >= min_normal_dot;
                    if (!similar) {
                        rejected_by_chart[next] = chart_index;
                        continue;
                    }
                    const FlatTriangle flat =
                        unfoldAboutEdge(mesh, triangles, placed, snap_tolerance, flat_of[triangle], edge, next);
                    if (index.overlapsAny(flat)) {
                        rejected_by_chart[next] = chart_index;
                        continue;
                    }
                    chart_of[next] = chart_index;
                    index.add(flat);
                    placeCorners(placed, flat);
                    flat_of[next] = flat;
                    frontier.push_back(next);
                }
            }
        }
        charts.push_back(std::move(chart));
    }
    return charts;
}

// Phase 4: degenerate triangles cover no area, so they cannot overlap anything: each joins the chart of a
// triangle it shares a welded vertex with (its uv1 then lies in that chart's rectangle), or is a chart of its own.
void attachDegenerateTriangles(const TriangleMesh& mesh, const std::vector<TriangleInfo>& triangles,
                               std::vector<int64_t>& chart_of, std::vector<Chart>& charts) {
    // A corner the charts have: its chart and where that chart put it (first place).
    std::unordered_map<uint32_t, std::pair<int64_t, glm::dvec2>> placed_corner;
    for (size_t chart = 0; chart < charts.size(); ++chart)
        for (size_t slot = 0; slot < charts[chart].triangles.size(); ++slot)
            for (int i = 0; i < 3; ++i)
                placed_corner.emplace(triangles[charts[chart].triangles[slot]].welded[i],
                                      std::make_pair(int64_t(chart), charts[chart].corners[slot * 3 + size_t(i)]));
    for (size_t triangle = 0; triangle < triangles.size(); ++triangle) {
        if (chart_of[triangle] >= 0) continue;
        glm::dvec2 anchor(0.0);
        for (uint32_t corner : triangles[triangle].welded) {
            auto it = placed_corner.find(corner);
            if (it != placed_corner.end()) {
                chart_of[triangle] = it->second.first;
                anchor = it->second.second;
                break;
            }
        }
        if (chart_of[triangle] < 0) {  // a chart of its own, on the horizontal plane
            chart_of[triangle] = int64_t(charts.size());
            charts.emplace_back();
            Chart& chart = charts.back();
            planeBasis(glm::dvec3(0, 0, 1), &chart.tangent, &chart.bitangent);
            chart.triangles.push_back(uint32_t(triangle));
            for (int i = 0; i < 3; ++i) {
                const glm::dvec3 position(mesh.positions[mesh.indices[triangle * 3 + i]]);
                chart.corners.push_back(glm::dvec2(glm::dot(position, chart.tangent), glm::dot(position, chart.bitangent)));
            }
            continue;
        }
        // Its corners where the chart has them; the others at the shared one (it has no area to show anyway).
        Chart& chart = charts[size_t(chart_of[triangle])];
        chart.triangles.push_back(uint32_t(triangle));
        for (uint32_t corner : triangles[triangle].welded) {
            auto it = placed_corner.find(corner);
            const bool in_chart = it != placed_corner.end() && it->second.first == chart_of[triangle];
            chart.corners.push_back(in_chart ? it->second.second : anchor);
        }
    }
}

}  // namespace gusuku::bake::detail

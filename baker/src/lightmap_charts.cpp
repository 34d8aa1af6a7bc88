// generateLightmapCharts: cut the building's surface into nearly planar charts, flatten each onto a plane at
// the requested texel density, and pack them into the lightmap (see lightmap_uv.h for the contract).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numbers>
#include <numeric>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_pack.h"
#include "lightmap_raster.h"

namespace gusuku::bake {
namespace {

constexpr double kMaxNormalDeviationDeg = 40.0;  // beyond this, projection stretches a texel by over 1/cos(40)
constexpr double kWeldToleranceOfDiagonal = 1e-6;
constexpr int kRotationSteps = 18;  // 5 degree steps over a quarter turn: a rectangle repeats after 90 degrees

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

struct TriangleInfo {
    uint32_t welded[3];
    glm::dvec3 normal{0.0};  // unit; zero when degenerate
    double area = 0.0;
    bool degenerate = true;
};

// Triangles a chart may grow into across each triangle's edges: those that run the same (welded) edge in the
// opposite direction, i.e. continue a consistently wound surface. On a non-manifold edge (a wall meeting a
// floor twice, a face duplicated back to back) every opposite-running pair counts; the normal test and the
// overlap test decide which of them may really join. Neighbours of edge slot (triangle * 3 + edge) are
// neighbours[offsets[slot] .. offsets[slot + 1]).
struct EdgeNeighbours {
    std::vector<uint32_t> offsets;
    std::vector<uint32_t> neighbours;
};

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

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

struct FlatTriangle {
    glm::dvec2 corner[3];
    uint32_t welded[3];
    glm::dvec2 min, max;
};

// True when two flattened triangles of one chart overlap by more than `tolerance` (metres): duplicated faces,
// triangles folded over a shared edge, or separate parts of the surface that land on each other.
bool flatTrianglesOverlap(const FlatTriangle& a, const FlatTriangle& b, double tolerance) {
    if (a.max.x <= b.min.x + tolerance || b.max.x <= a.min.x + tolerance || a.max.y <= b.min.y + tolerance ||
        b.max.y <= a.min.y + tolerance)
        return false;
    int shared = 0;
    int a_shared[3] = {-1, -1, -1};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a.welded[i] == b.welded[j]) {
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

// The flattened triangles of the chart being grown, bucketed on a grid for overlap queries. Triangles much
// larger than a cell go to a list every query scans, so one big floor triangle does not fill thousands of cells.
class FlatChartIndex {
public:
    FlatChartIndex(double cell_size, double tolerance) : cell_size_(cell_size), tolerance_(tolerance) {}

    bool overlapsAny(const FlatTriangle& candidate) {
        ++query_stamp_;
        auto test = [&](uint32_t member) {
            if (tested_stamp_[member] == query_stamp_) return false;
            tested_stamp_[member] = query_stamp_;
            return flatTrianglesOverlap(members_[member], candidate, tolerance_);
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

    void add(const FlatTriangle& triangle) {
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

private:
    static constexpr int kLargeCells = 16;
    static uint64_t key(int x, int y) { return uint64_t(uint32_t(x)) << 32 | uint32_t(y); }
    glm::ivec4 cellRange(const FlatTriangle& triangle) const {
        return glm::ivec4(int(std::floor(triangle.min.x / cell_size_)), int(std::floor(triangle.min.y / cell_size_)),
                          int(std::floor(triangle.max.x / cell_size_)), int(std::floor(triangle.max.y / cell_size_)));
    }
    bool isLarge(const FlatTriangle& triangle) const {
        const glm::ivec4 cells = cellRange(triangle);
        return cells.z - cells.x >= kLargeCells || cells.w - cells.y >= kLargeCells;
    }

    double cell_size_;
    double tolerance_;
    std::vector<FlatTriangle> members_;
    std::vector<uint32_t> large_members_;
    std::vector<uint64_t> tested_stamp_;
    uint64_t query_stamp_ = 0;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

// An orthonormal tangent basis of the plane with this unit normal.
void planeBasis(const glm::dvec3& normal, glm::dvec3* tangent, glm::dvec3* bitangent) {
    const glm::dvec3 helper = std::abs(normal.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    *tangent = glm::normalize(glm::cross(helper, normal));
    *bitangent = glm::cross(normal, *tangent);
}

// Where to start a chart of `extent` texels inside its `inner` texels (inner > extent): as far as the slack
// allows from putting either chart edge on a row of texel centres, so that float noise in the projection cannot
// flip whether a border row of centres is covered (a 1 m face at 8 texels/m then covers exactly 8 x 8 centres).
// Keeps a tenth of a texel (or half the slack) clear of the inner rectangle's sides.
double marginAwayFromCentres(double extent, int inner) {
    const double slack = double(inner) - extent;
    const double guard = std::min(0.1, 0.5 * slack);
    auto distanceFromCentre = [](double coordinate) { return std::abs(coordinate - std::floor(coordinate) - 0.5); };
    double best_margin = 0.5 * slack, best_distance = -1.0;
    constexpr int kSteps = 32;
    for (int step = 0; step <= kSteps; ++step) {
        const double margin = guard + (slack - 2.0 * guard) * step / kSteps;
        const double distance = std::min(distanceFromCentre(margin), distanceFromCentre(margin + extent));
        if (distance > best_distance + 1e-9) {
            best_distance = distance;
            best_margin = margin;
        }
    }
    return best_margin;
}

struct Chart {
    std::vector<uint32_t> triangles;
    glm::dvec3 tangent{1, 0, 0}, bitangent{0, 1, 0};  // the plane, already rotated to the smallest rectangle
    glm::dvec2 min{0.0}, max{0.0};                    // of the flattened vertices, metres
};

// Phase 1: refuse what cannot be charted, naming the field.
void validateChartInputs(const TriangleMesh& mesh, double texels_per_metre, int resolution, int padding_texels) {
    if (mesh.triangleCount() == 0) throw InputError("lightmap", "mesh", "has no triangles to chart");
    if (!(texels_per_metre > 0.0) || !std::isfinite(texels_per_metre))
        throw InputError("lightmap", "texels_per_metre",
                         "must be finite and positive, got " + std::to_string(texels_per_metre));
    if (resolution < 4 || resolution > 16384)
        throw InputError("lightmap", "resolution", "must be in [4, 16384], got " + std::to_string(resolution));
    if (padding_texels < 0 || padding_texels > 64)
        throw InputError("lightmap", "padding_texels", "must be in [0, 64], got " + std::to_string(padding_texels));
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
    for (const glm::vec3& position : mesh.positions)
        if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
            throw InputError("lightmap", "mesh positions", "a position is not finite");
}

// What chart growing needs to know of the mesh: per-triangle welded corners, normals and areas, who may join
// whom across an edge, and tolerances scaled to the scene (not to its units or its distance from the origin).
struct MeshAnalysis {
    std::vector<TriangleInfo> triangles;
    EdgeNeighbours adjacency;
    double typical_edge = 0.0;       // median first-edge length, metres: the overlap grid's cell scale
    double overlap_tolerance = 0.0;  // overlaps thinner than this (metres) are touching
};

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
// when its normal is within kMaxNormalDeviationDeg of the seed's and its flattened shape overlaps nothing in
// the chart. chart_of[triangle] is set for every non-degenerate triangle.
std::vector<Chart> growCharts(const TriangleMesh& mesh, const MeshAnalysis& analysis,
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
    std::vector<Chart> charts;
    for (uint32_t seed : seed_order) {
        if (chart_of[seed] >= 0 || triangles[seed].degenerate) continue;
        const int64_t chart_index = int64_t(charts.size());
        Chart chart;
        const glm::dvec3 seed_normal = triangles[seed].normal;
        planeBasis(seed_normal, &chart.tangent, &chart.bitangent);
        auto flatten = [&](uint32_t triangle) {
            FlatTriangle flat;
            flat.min = glm::dvec2(INFINITY);
            flat.max = glm::dvec2(-INFINITY);
            for (int i = 0; i < 3; ++i) {
                const glm::dvec3 position(mesh.positions[mesh.indices[size_t(triangle) * 3 + i]]);
                flat.corner[i] = glm::dvec2(glm::dot(position, chart.tangent), glm::dot(position, chart.bitangent));
                flat.welded[i] = triangles[triangle].welded[i];
                flat.min = glm::min(flat.min, flat.corner[i]);
                flat.max = glm::max(flat.max, flat.corner[i]);
            }
            return flat;
        };
        FlatChartIndex index(4.0 * analysis.typical_edge, analysis.overlap_tolerance);
        std::deque<uint32_t> frontier{seed};
        chart_of[seed] = chart_index;
        index.add(flatten(seed));
        while (!frontier.empty()) {
            const uint32_t triangle = frontier.front();
            frontier.pop_front();
            chart.triangles.push_back(triangle);
            const size_t first_slot = size_t(triangle) * 3;
            const EdgeNeighbours& adjacency = analysis.adjacency;
            for (uint32_t at = adjacency.offsets[first_slot]; at < adjacency.offsets[first_slot + 3]; ++at) {
                const uint32_t next = adjacency.neighbours[at];
                if (chart_of[next] >= 0 || rejected_by_chart[next] == chart_index) continue;
                const TriangleInfo& info = triangles[size_t(next)];
                const bool similar = glm::dot(info.normal, seed_normal) >= min_normal_dot;
                const FlatTriangle flat = flatten(next);
                if (!similar || index.overlapsAny(flat)) {
                    rejected_by_chart[next] = chart_index;
                    continue;
                }
                chart_of[next] = chart_index;
                index.add(flat);
                frontier.push_back(next);
            }
        }
        charts.push_back(std::move(chart));
    }
    return charts;
}

// Phase 4: degenerate triangles cover no area, so they cannot overlap anything: each joins the chart of a
// triangle it shares a welded vertex with (its uv1 then lies in that chart's rectangle), or is a chart of its own.
void attachDegenerateTriangles(const std::vector<TriangleInfo>& triangles, std::vector<int64_t>& chart_of,
                               std::vector<Chart>& charts) {
    const size_t triangle_count = triangles.size();
    std::unordered_map<uint32_t, int64_t> chart_at_welded_vertex;
    for (size_t triangle = 0; triangle < triangle_count; ++triangle)
        if (chart_of[triangle] >= 0)
            for (uint32_t corner : triangles[triangle].welded) chart_at_welded_vertex.emplace(corner, chart_of[triangle]);
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        if (chart_of[triangle] >= 0) continue;
        for (uint32_t corner : triangles[triangle].welded) {
            auto it = chart_at_welded_vertex.find(corner);
            if (it != chart_at_welded_vertex.end()) {
                chart_of[triangle] = it->second;
                break;
            }
        }
        if (chart_of[triangle] < 0) {
            chart_of[triangle] = int64_t(charts.size());
            charts.emplace_back();
            planeBasis(glm::dvec3(0, 0, 1), &charts.back().tangent, &charts.back().bitangent);
        }
        charts[size_t(chart_of[triangle])].triangles.push_back(uint32_t(triangle));
    }
}

// Phase 5: turn each chart in its plane to its smallest bounding rectangle (fewer wasted texels). Sets each
// chart's basis and min/max; returns the rectangles' extents in metres.
std::vector<glm::dvec2> fitChartRectangles(const TriangleMesh& mesh, std::vector<Chart>& charts) {
    std::vector<glm::dvec2> extents(charts.size());
    std::vector<glm::dvec3> chart_points;
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        Chart& chart = charts[chart_index];
        chart_points.clear();
        for (uint32_t triangle : chart.triangles)
            for (int i = 0; i < 3; ++i) chart_points.push_back(glm::dvec3(mesh.positions[mesh.indices[size_t(triangle) * 3 + i]]));
        double best_area = INFINITY;
        glm::dvec3 best_tangent = chart.tangent, best_bitangent = chart.bitangent;
        for (int step = 0; step < kRotationSteps; ++step) {
            const double angle = (std::numbers::pi / 2.0) * step / kRotationSteps;
            const glm::dvec3 tangent = std::cos(angle) * chart.tangent + std::sin(angle) * chart.bitangent;
            const glm::dvec3 bitangent = -std::sin(angle) * chart.tangent + std::cos(angle) * chart.bitangent;
            glm::dvec2 min(INFINITY), max(-INFINITY);
            for (const glm::dvec3& point : chart_points) {
                const glm::dvec2 flat(glm::dot(point, tangent), glm::dot(point, bitangent));
                min = glm::min(min, flat);
                max = glm::max(max, flat);
            }
            const double area = (max.x - min.x) * (max.y - min.y);
            if (area < best_area) {
                best_area = area;
                best_tangent = tangent;
                best_bitangent = bitangent;
                chart.min = min;
                chart.max = max;
            }
        }
        chart.tangent = best_tangent;
        chart.bitangent = best_bitangent;
        extents[chart_index] = chart.max - chart.min;
    }
    return extents;
}

// A chart's vertex in texels of its unturned inner rectangle at `scale` texels per metre: flattened, moved to the
// rectangle's corner and offset by the margin that keeps its edges clear of rows of texel centres.
struct ChartFrame {
    glm::ivec2 inner{1, 1};
    glm::dvec2 margin{0.0};
};

ChartFrame chartFrame(const glm::dvec2& extent, double scale) {
    ChartFrame frame;
    frame.inner = detail::innerTexelSize(extent, scale);
    const glm::dvec2 extent_texels = extent * scale;
    frame.margin = glm::dvec2(marginAwayFromCentres(extent_texels.x, frame.inner.x),
                              marginAwayFromCentres(extent_texels.y, frame.inner.y));
    return frame;
}

glm::dvec2 localTexel(const Chart& chart, const ChartFrame& frame, double scale, const glm::dvec3& position) {
    return (glm::dvec2(glm::dot(position, chart.tangent), glm::dot(position, chart.bitangent)) - chart.min) * scale +
           frame.margin;
}

// Whether a triangle (texel units) overlaps the texel square [x, x + 1] x [y, y + 1] by more than a touch along
// an edge line: separating axes (the square's own axes are the caller's bounding-box loop). A zero-area triangle
// meets every texel of its bounding box, conservatively.
bool triangleMeetsTexel(const detail::UvTriangle& triangle, int x, int y) {
    const double orientation = detail::signedDoubleArea(triangle);
    if (!(std::abs(orientation) > 1e-12)) return true;
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2& start = triangle[edge];
        const glm::dvec2& end = triangle[(edge + 1) % 3];
        // Inward normal of the edge; the square is separated when all its corners lie on the outer side.
        const glm::dvec2 inward = orientation > 0.0 ? glm::dvec2(start.y - end.y, end.x - start.x)
                                                    : glm::dvec2(end.y - start.y, start.x - end.x);
        double most_inside = -INFINITY;
        for (int corner = 0; corner < 4; ++corner) {
            const glm::dvec2 point(x + (corner & 1), y + (corner >> 1));
            most_inside = std::max(most_inside, glm::dot(point - start, inward));
        }
        if (most_inside <= 1e-9 * glm::length(inward)) return false;
    }
    return true;
}

// Phase 6: what the packer needs of each chart at a density: which texels of its inner rectangle its triangles
// touch (overlap by any area; a zero-area triangle touches every texel of its bounding box).
std::vector<detail::ChartShape> chartShapes(const TriangleMesh& mesh, const std::vector<Chart>& charts,
                                            const std::vector<glm::dvec2>& extents, double scale) {
    std::vector<detail::ChartShape> shapes(charts.size());
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        const Chart& chart = charts[chart_index];
        const ChartFrame frame = chartFrame(extents[chart_index], scale);
        detail::ChartShape& shape = shapes[chart_index];
        shape.inner = frame.inner;
        shape.touched.assign(size_t(frame.inner.x) * size_t(frame.inner.y), 0);
        for (uint32_t triangle : chart.triangles) {
            detail::UvTriangle local;
            for (int i = 0; i < 3; ++i)
                local[i] = localTexel(chart, frame, scale, glm::dvec3(mesh.positions[mesh.indices[size_t(triangle) * 3 + i]]));
            const glm::dvec2 low = glm::min(local[0], glm::min(local[1], local[2]));
            const glm::dvec2 high = glm::max(local[0], glm::max(local[1], local[2]));
            const int first_x = std::clamp(int(std::floor(low.x)), 0, frame.inner.x - 1);
            const int last_x = std::clamp(int(std::floor(high.x)), 0, frame.inner.x - 1);
            const int first_y = std::clamp(int(std::floor(low.y)), 0, frame.inner.y - 1);
            const int last_y = std::clamp(int(std::floor(high.y)), 0, frame.inner.y - 1);
            for (int y = first_y; y <= last_y; ++y)
                for (int x = first_x; x <= last_x; ++x)
                    if (triangleMeetsTexel(local, x, y)) shape.touched[size_t(y) * size_t(frame.inner.x) + size_t(x)] = 1;
        }
    }
    return shapes;
}

// Phase 7: the output mesh. Vertices are split per chart (a vertex on a chart border gets one copy per chart),
// and each copy's uv1 is its flattened position at the packed density, placed (and turned) in its chart's spot.
LightmapCharts writeChartedMesh(const TriangleMesh& mesh, const std::vector<Chart>& charts,
                                const std::vector<glm::dvec2>& extents, const detail::ChartPacking& packing,
                                int resolution) {
    const double scale = packing.texels_per_metre;
    LightmapCharts result;
    result.texels_per_metre = scale;
    result.resolution = resolution;
    result.chart_count = charts.size();
    result.triangle_chart.resize(mesh.triangleCount());
    TriangleMesh& out = result.mesh;
    out.materials = mesh.materials;
    out.textures = mesh.textures;
    out.texture_names = mesh.texture_names;
    out.triangle_material = mesh.triangle_material;
    out.indices.resize(mesh.indices.size());
    out.has_uv1 = true;
    const bool has_normals = mesh.normals.size() == mesh.positions.size();
    const bool has_uv0 = mesh.uv0.size() == mesh.positions.size();
    std::vector<int64_t> copy_chart(mesh.positions.size(), -1);  // which chart a vertex was last copied for
    std::vector<uint32_t> copy_index(mesh.positions.size(), 0);
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        const Chart& chart = charts[chart_index];
        const detail::ChartPlacement& placement = packing.placements[chart_index];
        const ChartFrame frame = chartFrame(extents[chart_index], scale);
        for (uint32_t triangle : chart.triangles) {
            result.triangle_chart[triangle] = uint32_t(chart_index);
            for (int i = 0; i < 3; ++i) {
                const uint32_t vertex = mesh.indices[size_t(triangle) * 3 + i];
                if (copy_chart[vertex] != int64_t(chart_index)) {
                    copy_chart[vertex] = int64_t(chart_index);
                    copy_index[vertex] = uint32_t(out.positions.size());
                    const glm::dvec2 local = localTexel(chart, frame, scale, glm::dvec3(mesh.positions[vertex]));
                    const glm::dvec2 texel = detail::placedTexel(placement, frame.inner, local);
                    out.positions.push_back(mesh.positions[vertex]);
                    out.normals.push_back(has_normals ? mesh.normals[vertex] : glm::vec3(0.0f));
                    out.uv0.push_back(has_uv0 ? mesh.uv0[vertex] : glm::vec2(0.0f));
                    out.uv1.push_back(glm::vec2(texel / double(resolution)));
                }
                out.indices[size_t(triangle) * 3 + i] = copy_index[vertex];
            }
        }
    }
    return result;
}

// The charts of a mesh, grown and fitted, before packing: what both entry points below share.
struct FittedCharts {
    std::vector<Chart> charts;
    std::vector<glm::dvec2> extents;
};

FittedCharts growAndFitCharts(const TriangleMesh& mesh, double texels_per_metre) {
    const MeshAnalysis analysis = analyseMesh(mesh, texels_per_metre);
    std::vector<int64_t> chart_of;
    FittedCharts fitted;
    fitted.charts = growCharts(mesh, analysis, chart_of);
    attachDegenerateTriangles(analysis.triangles, chart_of, fitted.charts);
    fitted.extents = fitChartRectangles(mesh, fitted.charts);
    return fitted;
}

// Packs the charts into a resolution^2 lightmap (the largest density up to texels_per_metre that fits) and writes
// the charted mesh.
LightmapCharts packAndWrite(const TriangleMesh& mesh, const FittedCharts& fitted, double texels_per_metre,
                            int resolution, int padding_texels) {
    const auto shapes_at = [&](double density) { return chartShapes(mesh, fitted.charts, fitted.extents, density); };
    const detail::ChartPacking packing =
        detail::packChartShapes(shapes_at, texels_per_metre, resolution, padding_texels);
    return writeChartedMesh(mesh, fitted.charts, fitted.extents, packing, resolution);
}

}  // namespace

LightmapCharts generateLightmapCharts(const TriangleMesh& mesh, double texels_per_metre, int resolution,
                                      int padding_texels) {
    validateChartInputs(mesh, texels_per_metre, resolution, padding_texels);
    return packAndWrite(mesh, growAndFitCharts(mesh, texels_per_metre), texels_per_metre, resolution, padding_texels);
}

LightmapCharts generateLightmapChartsInSmallestLightmap(const TriangleMesh& mesh, double texels_per_metre,
                                                        int max_resolution, int padding_texels) {
    validateChartInputs(mesh, texels_per_metre, max_resolution, padding_texels);
    const FittedCharts fitted = growAndFitCharts(mesh, texels_per_metre);
    const int resolution = detail::smallestFittingResolution(
        chartShapes(mesh, fitted.charts, fitted.extents, texels_per_metre), max_resolution, padding_texels);
    return packAndWrite(mesh, fitted, texels_per_metre, resolution, padding_texels);
}

}  // namespace gusuku::bake

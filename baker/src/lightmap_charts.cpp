// generateLightmapCharts: cut the building's surface into nearly planar charts, unfold each flat at the requested
// texel density (lengths kept), join charts across sharp edges where that saves gutter (a beam's faces become one
// strip), and pack them into the lightmap (see lightmap_uv.h for the contract).

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

#include "gusuku/maths/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_pack.h"
#include "lightmap_raster.h"

namespace gusuku::bake {
namespace {

constexpr double kMaxNormalDeviationDeg = 40.0;  // beyond this, projection stretches a texel by over 1/cos(40)
constexpr double kMaxUnfoldAngleDeg = 90.0;      // charts meeting at up to this are unfolded into one (phase 5)
// ... when that saves at least this share of the smaller chart's padded texels: big charts joined for a few gutter
// texels make long strips that pack worse than their parts.
constexpr double kMinUnfoldSaving = 0.25;
// ... and the joined chart takes at most this share of all the charts' padded texels: a piece that big leaves the
// packer little room.
constexpr double kMaxUnfoldedShare = 1.0 / 16.0;
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

// The flattened triangles of the chart being grown, bucketed on a grid for overlap queries. Triangles much
// larger than a cell go to a list every query scans, so one big floor triangle does not fill thousands of cells.
class FlatChartIndex {
public:
    FlatChartIndex(double cell_size, double tolerance, double same_point = INFINITY)
        : cell_size_(cell_size), tolerance_(tolerance), same_point_(same_point) {}

    bool overlapsAny(const FlatTriangle& candidate) {
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
    double same_point_;
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

// Where a chart of `extent` texels may start inside its frame, and the frame's texels, along one axis. Bilinear
// lookups on the chart read the texels whose centre lies less than a texel from it: every centre it covers plus one
// beyond each end, wherever it lies (an open unit interval holds one centre). Placement decides how many centres it
// covers, n = floor(extent) or n + 1, and so reads n + 2 or n + 3 texels. Each placement keeps both chart edges and
// both ends of the read span at least kEdgeClearanceTexels clear of rows of centres, so float noise cannot flip
// which centres it covers or reads; the frame is exactly the texels it reads.
// - Fewer: the chart starts half of 1 - frac(extent) past a centre and covers n (a 1 m face at 8 texels/m covers 8
//   centres, reads 10); possible while frac <= 1 - 2 * clearance.
// - More: it starts frac / 2 before a centre and covers n + 1 (a 1.5 m face at 2 texels/m covers 4, reads 6);
//   possible while frac >= 2 * clearance.
// Which fills better depends on the chart (chooseChartFrame): n + 1 of n + 3 beats n of n + 2 on a rectangle, but a
// thin, finely cut strip claims a texel under each triangle that covers no centre (lightmap_uv.h's fallback), so
// covering no row of centres may claim as many texels for fewer reads.
constexpr double kEdgeClearanceTexels = 0.05;

// - Spanned: the chart is stretched along the axis (shrunk by kSpannedMaxShrink at most: a 1 m wall at 8 texels/m
//   spans 9 centres, not 10) so that its ends lie kSpannedInsetTexels inside the first and last of
//   m = ceil(extent (1 - kSpannedMaxShrink) + 2 inset) + 1 centres. It reads exactly those
//   m texels (the next centre out lies a texel and the inset away, beyond the read slack), and claims the two end
//   centres too, by lightmap_raster.h's near-claim rule (a centre within kNearClaimTexels of a triangle and in
//   none): every texel it reads is traced, so a rectangle's read ring costs nothing. A 4 cm baluster's faces
//   (2.56 texels at 16 texels/m) read 4 texels across instead of 5 and claim all 4 instead of 3.
constexpr double kSpannedInsetTexels = 0.01;
constexpr double kSpannedMaxShrink = 0.005;
static_assert(kSpannedInsetTexels > detail::kReadSlackTexels && 2.0 * kSpannedInsetTexels <= detail::kNearClaimTexels,
              "the spanned frame must read no texel beyond its end centres and claim both");

struct AxisFrame {
    int texels = 1;
    double margin = 0.0;
    double stretch = 1.0;  // texels of the frame per texel of the chart at the density
};

// The placements along one axis that keep the clearance: one or both, and the spanned one.
std::vector<AxisFrame> axisFrames(double extent) {
    const double whole = std::floor(extent), fraction = extent - whole;
    std::vector<AxisFrame> frames;
    if (0.5 * (1.0 - fraction) >= kEdgeClearanceTexels) frames.push_back({int(whole) + 2, 1.0 - 0.5 * fraction});
    if (0.5 * fraction >= kEdgeClearanceTexels) frames.push_back({int(whole) + 3, 1.5 - 0.5 * fraction});
    if (extent > 1e-6) {
        const double spans = std::max(1.0, std::ceil(extent * (1.0 - kSpannedMaxShrink) + 2.0 * kSpannedInsetTexels));
        frames.push_back({int(spans) + 1, 0.5 + kSpannedInsetTexels, (spans - 2.0 * kSpannedInsetTexels) / extent});
    }
    return frames;
}

// A chart: its triangles and where their corners lie flattened (metres). A chart grown across gentle edges is
// projected onto its seed's plane; charts joined across sharp edges (phase 5) are unfolded about their seams, so a
// chart's corners are stored rather than derived from one plane.
struct Chart {
    std::vector<uint32_t> triangles;
    std::vector<glm::dvec2> corners;                  // 3 per triangle, in the order of `triangles`
    glm::dvec3 tangent{1, 0, 0}, bitangent{0, 1, 0};  // the seed's plane (growing and phase 4 project onto it)
    glm::dvec2 min{0.0}, max{0.0};                    // of the corners once turned to the smallest rectangle
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

// The smallest bounding rectangle of flattened points over quarter-turn steps: the turn (counter-clockwise
// radians, applied as (x, y) -> (c x + s y, -s x + c y)) and the turned points' bounds.
struct RectangleFit {
    double angle = 0.0;
    glm::dvec2 min{0.0}, max{0.0};
};

glm::dvec2 turned(const glm::dvec2& point, double cos_angle, double sin_angle) {
    return glm::dvec2(cos_angle * point.x + sin_angle * point.y, -sin_angle * point.x + cos_angle * point.y);
}

RectangleFit smallestRectangle(const std::vector<glm::dvec2>& points) {
    RectangleFit best;
    double best_area = INFINITY;
    for (int step = 0; step < kRotationSteps; ++step) {
        const double angle = (std::numbers::pi / 2.0) * step / kRotationSteps;
        const double c = std::cos(angle), s = std::sin(angle);
        glm::dvec2 min(INFINITY), max(-INFINITY);
        for (const glm::dvec2& point : points) {
            const glm::dvec2 flat = turned(point, c, s);
            min = glm::min(min, flat);
            max = glm::max(max, flat);
        }
        const double area = (max.x - min.x) * (max.y - min.y);
        if (area < best_area) {
            best_area = area;
            best = RectangleFit{angle, min, max};
        }
    }
    return best;
}

// Texels a chart's smallest rectangle takes at the requested density with its gutter: what joining charts saves.
double paddedTexelArea(const RectangleFit& fit, double texels_per_metre, int padding) {
    const glm::ivec2 inner = detail::innerTexelSize(fit.max - fit.min, texels_per_metre);
    return double(inner.x + 2 * padding) * double(inner.y + 2 * padding);
}

// Phase 5: join charts across sharp edges (up to kMaxUnfoldAngleDeg: a beam's corners) by unfolding one about the
// seam, as a box's net lies flat: a thin beam's four long faces become one strip that pays its gutter once,
// instead of four one-texel charts each with a texel of gutter on both sides. Unfolding is a rigid move in the
// plane, so the density stays as requested. A join is taken when the joined chart overlaps nothing of itself,
// saves at least kMinUnfoldSaving of the smaller chart's padded rectangle, and stays under kMaxUnfoldedShare of all
// the charts' padded texels. Seams are tried longest first, again after every round that joined something (a strip
// grows a face at a time); a pair refused is tried again only once one of its charts has grown.
// A triangle edge whose neighbour across it lies in another chart, at most the unfold angle away.
struct Seam {
    uint32_t triangle[2];
    uint32_t welded[2];  // the edge's welded vertices
};
// The seams two charts share; length: the seams' total flattened length, which orders the joins.
struct ChartPair {
    double length = 0.0;
    std::vector<Seam> seams;
};
// Keyed by (lower chart << 32 | higher chart).
using ChartPairs = std::unordered_map<uint64_t, ChartPair>;

ChartPairs findSeams(const MeshAnalysis& analysis, const std::vector<int64_t>& chart_of) {
    const std::vector<TriangleInfo>& triangles = analysis.triangles;
    const EdgeNeighbours& adjacency = analysis.adjacency;
    const double min_normal_dot = std::cos(kMaxUnfoldAngleDeg * std::numbers::pi / 180.0) - 1e-3;
    ChartPairs pairs;
    for (uint32_t triangle = 0; triangle < triangles.size(); ++triangle) {
        if (triangles[triangle].degenerate) continue;
        for (int edge = 0; edge < 3; ++edge) {
            const size_t slot = size_t(triangle) * 3 + size_t(edge);
            for (uint32_t at = adjacency.offsets[slot]; at < adjacency.offsets[slot + 1]; ++at) {
                const uint32_t next = adjacency.neighbours[at];
                const int64_t here = chart_of[triangle], there = chart_of[next];
                if (here == there || here > there) continue;  // each seam once, from the lower chart's side
                if (glm::dot(triangles[triangle].normal, triangles[next].normal) < min_normal_dot) continue;
                const uint32_t a = triangles[triangle].welded[edge], b = triangles[triangle].welded[(edge + 1) % 3];
                ChartPair& pair = pairs[uint64_t(here) << 32 | uint64_t(there)];
                pair.seams.push_back(Seam{{triangle, next}, {a, b}});
            }
        }
    }
    return pairs;
}

// A flattened triangle from a chart's corner list (3 per slot) and its welded vertices.
FlatTriangle flatTriangleAt(const std::vector<glm::dvec2>& corners, size_t slot, const TriangleInfo& info) {
    FlatTriangle flat;
    flat.min = glm::dvec2(INFINITY);
    flat.max = glm::dvec2(-INFINITY);
    for (int i = 0; i < 3; ++i) {
        flat.corner[i] = corners[slot * 3 + size_t(i)];
        flat.welded[i] = info.welded[i];
        flat.min = glm::min(flat.min, flat.corner[i]);
        flat.max = glm::max(flat.max, flat.corner[i]);
    }
    return flat;
}

// Phase 5 (unfoldAcrossSharpEdges below) as rounds over the chart pairs, longest seams first. Charts joined into
// another are emptied and point to it through root (a union-find); renumber() drops them at the end.
class ChartUnfolder {
public:
    ChartUnfolder(const MeshAnalysis& analysis, std::vector<int64_t>& chart_of, std::vector<Chart>& charts,
                  double texels_per_metre, int padding, double snap_tolerance)
        : analysis_(analysis), triangles_(analysis.triangles), chart_of_(chart_of), charts_(charts),
          texels_per_metre_(texels_per_metre), padding_(padding), snap_tolerance_(snap_tolerance),
          slot_of_(triangles_.size(), 0), padded_area_(charts.size()), root_(charts.size()),
          version_(charts.size(), 0) {
        for (const Chart& chart : charts_)
            for (uint32_t slot = 0; slot < chart.triangles.size(); ++slot) slot_of_[chart.triangles[slot]] = slot;
        for (size_t chart = 0; chart < charts_.size(); ++chart)
            padded_area_[chart] = paddedTexelArea(smallestRectangle(charts_[chart].corners), texels_per_metre_, padding_);
        total_padded_area_ = std::accumulate(padded_area_.begin(), padded_area_.end(), 0.0);
        std::iota(root_.begin(), root_.end(), int64_t(0));
    }

    // Rounds until one joins nothing: a strip grows a face at a time, so a pair may only pay after another join.
    void joinAll(ChartPairs& pairs) {
        const std::vector<std::pair<double, uint64_t>> order = seamOrder(pairs);
        for (bool joined_any = true; joined_any;) {
            joined_any = false;
            for (const auto& [length, key] : order) joined_any = tryJoin(key, pairs.at(key)) || joined_any;
        }
    }

    // Drop the emptied charts; renumber.
    void renumber() {
        std::vector<int64_t> renumbered(charts_.size(), -1);
        std::vector<Chart> kept_charts;
        for (size_t chart = 0; chart < charts_.size(); ++chart) {
            if (root_[chart] != int64_t(chart)) continue;
            renumbered[chart] = int64_t(kept_charts.size());
            kept_charts.push_back(std::move(charts_[chart]));
        }
        for (int64_t& chart : chart_of_) chart = renumbered[size_t(chart)];
        charts_ = std::move(kept_charts);
    }

private:
    // Where a triangle's corner of this welded vertex lies in its chart (its chart's list, at slot_of * 3).
    glm::dvec2 cornerOf(uint32_t triangle, uint32_t welded) const {
        const Chart& chart = charts_[size_t(chart_of_[triangle])];
        for (int i = 0; i < 3; ++i)
            if (triangles_[triangle].welded[i] == welded) return chart.corners[size_t(slot_of_[triangle]) * 3 + size_t(i)];
        return chart.corners[size_t(slot_of_[triangle]) * 3];
    }

    double seamLength(const Seam& seam) const {
        return glm::length(cornerOf(seam.triangle[0], seam.welded[1]) - cornerOf(seam.triangle[0], seam.welded[0]));
    }

    // The pairs by their seams' total length, longest first (ties by key, so the order is the same every run).
    std::vector<std::pair<double, uint64_t>> seamOrder(ChartPairs& pairs) const {
        std::vector<std::pair<double, uint64_t>> order;
        for (auto& [key, pair] : pairs) {
            pair.length = 0.0;
            for (const Seam& seam : pair.seams) pair.length += seamLength(seam);
            order.emplace_back(pair.length, key);
        }
        std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) {
            return x.first != y.first ? x.first > y.first : x.second < y.second;
        });
        return order;
    }

    // The chart each chart was joined into (itself while whole), halving the path on the way.
    int64_t find(int64_t chart) {
        while (root_[size_t(chart)] != chart) chart = root_[size_t(chart)] = root_[size_t(root_[size_t(chart)])];
        return chart;
    }

    // Joins the pair's charts as they are now (the smaller moved onto the larger) when that pays and overlaps
    // nothing; a pair refused is tried again only once one of its charts has grown.
    bool tryJoin(uint64_t key, const ChartPair& pair) {
        int64_t keep = find(int64_t(key >> 32)), move = find(int64_t(key & 0xffffffffu));
        if (keep == move) return false;
        if (charts_[size_t(keep)].triangles.size() < charts_[size_t(move)].triangles.size()) std::swap(keep, move);
        const uint64_t versions = uint64_t(version_[size_t(keep)]) << 32 | version_[size_t(move)];
        const uint64_t pair_key = uint64_t(keep) << 32 | uint64_t(move);
        if (auto it = tried_.find(pair_key); it != tried_.end() && it->second == versions) return false;
        tried_[pair_key] = versions;
        unfoldMover(pair, keep, move);
        const Chart& kept = charts_[size_t(keep)];
        joined_ = kept.corners;
        joined_.insert(joined_.end(), moved_.begin(), moved_.end());
        const double joined_area = paddedTexelArea(smallestRectangle(joined_), texels_per_metre_, padding_);
        const double saved = padded_area_[size_t(keep)] + padded_area_[size_t(move)] - joined_area;
        if (joined_area > kMaxUnfoldedShare * total_padded_area_ ||
            saved < kMinUnfoldSaving * std::min(padded_area_[size_t(keep)], padded_area_[size_t(move)]))
            return false;
        if (movedOverlapsKept(kept, charts_[size_t(move)])) return false;
        join(keep, move, joined_area);
        return true;
    }

    // moved_: the moved chart's corners after the rigid move (rotation, then shift) unfolding it about the seam's
    // longest edge: both charts keep their lengths, so that edge lands exactly. The seam's other corners that land
    // within the snap tolerance become one with their partners (the two sides then share their uv1 exactly); those
    // that do not (a beam's strip closing on its first face, a curved roof's seam) stay cut, which the overlap
    // test allows only where nothing overlaps.
    void unfoldMover(const ChartPair& pair, int64_t keep, int64_t move) {
        const Seam* anchor = nullptr;
        double anchor_length = -1.0;
        for (const Seam& seam : pair.seams) {
            const double seam_length = seamLength(seam);
            if (seam_length > anchor_length) {
                anchor_length = seam_length;
                anchor = &seam;
            }
        }
        const bool anchor_first_kept = find(chart_of_[anchor->triangle[0]]) == keep;
        const uint32_t anchor_kept = anchor->triangle[anchor_first_kept ? 0 : 1];
        const uint32_t anchor_moved = anchor->triangle[anchor_first_kept ? 1 : 0];
        const glm::dvec2 from0 = cornerOf(anchor_moved, anchor->welded[0]), from1 = cornerOf(anchor_moved, anchor->welded[1]);
        const glm::dvec2 to0 = cornerOf(anchor_kept, anchor->welded[0]), to1 = cornerOf(anchor_kept, anchor->welded[1]);
        const double angle = std::atan2(cross2(from1 - from0, to1 - to0), glm::dot(from1 - from0, to1 - to0));
        const double c = std::cos(angle), s = std::sin(angle);
        const glm::dvec2 moved_centre = 0.5 * (from0 + from1), kept_centre = 0.5 * (to0 + to1);
        auto place = [&](const glm::dvec2& point) {  // counter-clockwise by `angle` about the anchor's middle
            const glm::dvec2 offset = point - moved_centre;
            return kept_centre + glm::dvec2(c * offset.x - s * offset.y, s * offset.x + c * offset.y);
        };
        const Chart& mover = charts_[size_t(move)];
        moved_.clear();
        for (const glm::dvec2& corner : mover.corners) moved_.push_back(place(corner));
        seam_target_.clear();
        for (const Seam& seam : pair.seams) {
            const bool first_kept = find(chart_of_[seam.triangle[0]]) == keep;
            for (uint32_t welded : seam.welded)
                seam_target_.emplace(welded, cornerOf(seam.triangle[first_kept ? 0 : 1], welded));
        }
        for (size_t slot = 0; slot < mover.triangles.size(); ++slot)
            for (int i = 0; i < 3; ++i) {
                auto it = seam_target_.find(triangles_[mover.triangles[slot]].welded[i]);
                glm::dvec2& corner = moved_[slot * 3 + size_t(i)];
                if (it != seam_target_.end() && glm::length(corner - it->second) <= snap_tolerance_) corner = it->second;
            }
    }

    // The moved triangles against the kept ones (each chart overlaps nothing of itself already).
    bool movedOverlapsKept(const Chart& kept, const Chart& mover) const {
        FlatChartIndex index(4.0 * analysis_.typical_edge, analysis_.overlap_tolerance, snap_tolerance_);
        for (size_t slot = 0; slot < kept.triangles.size(); ++slot)
            index.add(flatTriangleAt(kept.corners, slot, triangles_[kept.triangles[slot]]));
        bool overlaps = false;
        for (size_t slot = 0; slot < mover.triangles.size() && !overlaps; ++slot)
            overlaps = index.overlapsAny(flatTriangleAt(moved_, slot, triangles_[mover.triangles[slot]]));
        return overlaps;
    }

    // Join: the moved chart's triangles follow the kept chart's, its corners unfolded; the moved chart empties.
    void join(int64_t keep, int64_t move, double joined_area) {
        Chart& kept = charts_[size_t(keep)];
        Chart& mover = charts_[size_t(move)];
        const uint32_t first_slot = uint32_t(kept.triangles.size());
        for (size_t slot = 0; slot < mover.triangles.size(); ++slot) slot_of_[mover.triangles[slot]] = first_slot + uint32_t(slot);
        kept.triangles.insert(kept.triangles.end(), mover.triangles.begin(), mover.triangles.end());
        kept.corners = std::move(joined_);
        joined_.clear();
        for (uint32_t triangle : mover.triangles) chart_of_[triangle] = keep;
        mover.triangles.clear();
        mover.corners.clear();
        root_[size_t(move)] = keep;
        padded_area_[size_t(keep)] = joined_area;
        ++version_[size_t(keep)];
    }

    const MeshAnalysis& analysis_;
    const std::vector<TriangleInfo>& triangles_;
    std::vector<int64_t>& chart_of_;
    std::vector<Chart>& charts_;
    const double texels_per_metre_;
    const int padding_;
    const double snap_tolerance_;
    std::vector<uint32_t> slot_of_;    // a triangle's slot in its chart's triangle list
    std::vector<double> padded_area_;  // each chart's padded texels (paddedTexelArea) as it is now
    double total_padded_area_ = 0.0;   // of all charts before joining
    std::vector<int64_t> root_;        // the chart each chart was joined into (itself while whole)
    std::vector<uint32_t> version_;    // bumped when a chart grows: a refused pair may now join
    std::unordered_map<uint64_t, uint64_t> tried_;  // pair key -> both charts' versions when last refused
    std::vector<glm::dvec2> moved_, joined_;        // the moved chart's corners unfolded; the kept ones then those
    std::unordered_map<uint32_t, glm::dvec2> seam_target_;  // welded vertex -> where the kept chart has it
};

void unfoldAcrossSharpEdges(const MeshAnalysis& analysis, std::vector<int64_t>& chart_of, std::vector<Chart>& charts,
                            double texels_per_metre, int padding, double snap_tolerance) {
    ChartPairs pairs = findSeams(analysis, chart_of);
    ChartUnfolder unfolder(analysis, chart_of, charts, texels_per_metre, padding, snap_tolerance);
    unfolder.joinAll(pairs);
    unfolder.renumber();
}

// Phase 6: turn each chart in its plane to its smallest bounding rectangle (fewer wasted texels), after making
// the corners a welded vertex has within snap_tolerance in a chart one point (an unfolded seam's two sides then
// share their uv1 exactly, as one chart). Sets each chart's corners and min/max; returns the rectangles' extents
// in metres.
std::vector<glm::dvec2> fitChartRectangles(const std::vector<TriangleInfo>& triangles, std::vector<Chart>& charts,
                                           double snap_tolerance) {
    std::vector<glm::dvec2> extents(charts.size());
    std::unordered_map<uint32_t, std::vector<glm::dvec2>> points_of_welded;
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        Chart& chart = charts[chart_index];
        points_of_welded.clear();
        for (size_t slot = 0; slot < chart.triangles.size(); ++slot)
            for (int i = 0; i < 3; ++i) {
                glm::dvec2& corner = chart.corners[slot * 3 + size_t(i)];
                std::vector<glm::dvec2>& points = points_of_welded[triangles[chart.triangles[slot]].welded[i]];
                bool snapped = false;
                for (const glm::dvec2& point : points)
                    if (glm::length(point - corner) <= snap_tolerance) {
                        corner = point;
                        snapped = true;
                        break;
                    }
                if (!snapped) points.push_back(corner);
            }
        const RectangleFit fit = smallestRectangle(chart.corners);
        const double c = std::cos(fit.angle), s = std::sin(fit.angle);
        for (glm::dvec2& corner : chart.corners) corner = turned(corner, c, s);
        chart.min = fit.min;
        chart.max = fit.max;
        extents[chart_index] = chart.max - chart.min;
    }
    return extents;
}

// Where a chart lies in its frame: the frame's texels and the offset of the chart's rectangle inside it, per axis
// one of axisFrames' placements.
struct ChartFrame {
    glm::ivec2 inner{1, 1};
    glm::dvec2 margin{0.0};
    glm::dvec2 stretch{1.0};  // per axis: 1, or a spanned frame's stretch (axisFrames)
};

// A chart's vertex in texels of its unturned frame at `scale` texels per metre: flattened, moved to the
// rectangle's corner, stretched and offset by the frame's margin.
glm::dvec2 localTexel(const Chart& chart, const ChartFrame& frame, double scale, const glm::dvec2& corner) {
    return (corner - chart.min) * scale * frame.stretch + frame.margin;
}

// The texels of a chart's frame its bilinear lookups read (`read`, frame.inner.x * frame.inner.y, row-major: the
// texels whose centre lies less than a texel from one of its triangles on both axes, by kReadSlackTexels
// conservatively; a zero-area triangle reads every texel around its bounding box), and how many texels it claims by
// lightmap_uv.h's coverage rule (the centres its triangles cover, and the texel under the UV centroid of a triangle
// that covers none): the texels traced for it. The frame is then cut (or grown) to the read texels' bounding box:
// a read found only through the slack (a corner of an unfolded net that lands on a row of centres) may lie a texel
// outside axisFrames' frame, and must still be kept from other charts.
size_t rasteriseChartFrame(const Chart& chart, ChartFrame& frame, double scale, std::vector<uint8_t>& read,
                           std::vector<uint8_t>& claimed) {
    // A grid with one texel more on every side than the frame.
    const glm::ivec2 grid = frame.inner + 2;
    const glm::dvec2 grid_margin = frame.margin + 1.0;
    const size_t cells = size_t(grid.x) * size_t(grid.y);
    std::vector<uint8_t> grid_read(cells, 0);
    claimed.assign(cells, 0);
    size_t claimed_count = 0;
    auto claim = [&](int x, int y) {
        uint8_t& cell = claimed[size_t(y) * size_t(grid.x) + size_t(x)];
        claimed_count += cell ? 0 : 1;
        cell = 1;
    };
    const ChartFrame grid_frame{grid, grid_margin, frame.stretch};
    glm::ivec2 low_cell(grid), high_cell(-1);
    for (size_t slot = 0; slot < chart.triangles.size(); ++slot) {
        detail::UvTriangle local;
        for (int i = 0; i < 3; ++i) local[i] = localTexel(chart, grid_frame, scale, chart.corners[slot * 3 + size_t(i)]);
        const glm::dvec2 low = glm::min(local[0], glm::min(local[1], local[2]));
        const glm::dvec2 high = glm::max(local[0], glm::max(local[1], local[2]));
        // Texels whose centre lies within (low - 1, high + 1), with the slack; the grid holds them all.
        const int first_x = std::clamp(int(std::floor(low.x - 1.5 - detail::kReadSlackTexels)), 0, grid.x - 1);
        const int last_x = std::clamp(int(std::floor(high.x + 0.5 + detail::kReadSlackTexels)), 0, grid.x - 1);
        const int first_y = std::clamp(int(std::floor(low.y - 1.5 - detail::kReadSlackTexels)), 0, grid.y - 1);
        const int last_y = std::clamp(int(std::floor(high.y + 0.5 + detail::kReadSlackTexels)), 0, grid.y - 1);
        bool covers_a_centre = false;
        for (int y = first_y; y <= last_y; ++y)
            for (int x = first_x; x <= last_x; ++x) {
                if (!detail::bilinearReadsTexel(local, x, y)) continue;
                grid_read[size_t(y) * size_t(grid.x) + size_t(x)] = 1;
                low_cell = glm::min(low_cell, glm::ivec2(x, y));
                high_cell = glm::max(high_cell, glm::ivec2(x, y));
                if (detail::containsPoint(local, glm::dvec2(x + 0.5, y + 0.5))) {
                    claim(x, y);
                    covers_a_centre = true;
                } else if (detail::nearClaimsCentre(local, glm::dvec2(x + 0.5, y + 0.5))) {
                    claim(x, y);  // the bake claims it unless another triangle contains it (lightmap_texels.cpp)
                }
            }
        if (!covers_a_centre) {
            const glm::dvec2 centroid = (local[0] + local[1] + local[2]) / 3.0;
            claim(std::clamp(int(std::floor(centroid.x)), 0, grid.x - 1),
                  std::clamp(int(std::floor(centroid.y)), 0, grid.y - 1));
        }
    }
    if (high_cell.x < 0) low_cell = high_cell = glm::ivec2(1);  // reads nothing (cannot happen): keep one texel
    frame.inner = high_cell - low_cell + 1;
    frame.margin = grid_margin - glm::dvec2(low_cell);
    read.assign(size_t(frame.inner.x) * size_t(frame.inner.y), 0);
    for (int y = 0; y < frame.inner.y; ++y)
        for (int x = 0; x < frame.inner.x; ++x)
            read[size_t(y) * size_t(frame.inner.x) + size_t(x)] =
                grid_read[size_t(y + low_cell.y) * size_t(grid.x) + size_t(x + low_cell.x)];
    return claimed_count;
}

// The claimed texels per read texel the bake's charts reach: choosing each chart's frame to maximise claimed -
// kTargetClaimedPerRead * read maximises the lightmap's claimed share over all charts' reads when the target is that
// share (the packer then keeps the reads' share of the lightmap near 90 %).
constexpr double kTargetClaimedPerRead = 0.65;

// The chart's frame among the placements axisFrames allows per axis (up to nine) that claims the most texels for
// its reads (kTargetClaimedPerRead; ties: fewer reads, then the first), with its read texels in `read`.
ChartFrame chooseChartFrame(const Chart& chart, const glm::dvec2& extent, double scale, std::vector<uint8_t>& read) {
    const std::vector<AxisFrame> along_x = axisFrames(extent.x * scale), along_y = axisFrames(extent.y * scale);
    ChartFrame best;
    double best_score = -INFINITY;
    size_t best_read = 0;
    std::vector<uint8_t> candidate_read, claimed;
    for (const AxisFrame& x : along_x)
        for (const AxisFrame& y : along_y) {
            ChartFrame frame{glm::ivec2(x.texels, y.texels), glm::dvec2(x.margin, y.margin),
                             glm::dvec2(x.stretch, y.stretch)};
            const size_t claimed_count = rasteriseChartFrame(chart, frame, scale, candidate_read, claimed);
            const size_t read_count = size_t(std::count(candidate_read.begin(), candidate_read.end(), uint8_t(1)));
            const double score = double(claimed_count) - kTargetClaimedPerRead * double(read_count);
            if (score > best_score || (score == best_score && read_count < best_read)) {
                best = frame;
                best_score = score;
                best_read = read_count;
                read.swap(candidate_read);
            }
        }
    return best;
}

// Phase 7: what the packer needs of each chart at a density: which texels of its frame (chooseChartFrame) its
// bilinear lookups read. Packing these sets apart, rather than the touched texels with a ring of gutter each, lets
// two charts share the one gutter texel that only one of them reads: the rule that keeps bilinear filtering (and
// the chart-aware dilation) from mixing charts, at half the gutter of the touched rule on thin parts.
std::vector<detail::ChartShape> chartShapes(const std::vector<Chart>& charts,
                                            const std::vector<glm::dvec2>& extents, double scale) {
    std::vector<detail::ChartShape> shapes(charts.size());
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        detail::ChartShape& shape = shapes[chart_index];
        shape.inner = chooseChartFrame(charts[chart_index], extents[chart_index], scale, shape.occupied).inner;
    }
    return shapes;
}

// Phase 8: the output mesh. Vertices are split per chart (a vertex on a chart border gets one copy per chart),
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
    // A vertex gets one copy per place it has in a chart: once per chart, or more where an unfolded chart is cut
    // through it (a beam's strip is cut along one edge, whose vertices lie at both ends of the strip).
    std::unordered_map<uint32_t, std::vector<std::pair<glm::dvec2, uint32_t>>> copies;  // of this chart's vertices
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        const Chart& chart = charts[chart_index];
        const detail::ChartPlacement& placement = packing.placements[chart_index];
        std::vector<uint8_t> read;
        const ChartFrame frame = chooseChartFrame(chart, extents[chart_index], scale, read);
        copies.clear();
        for (size_t slot = 0; slot < chart.triangles.size(); ++slot) {
            const uint32_t triangle = chart.triangles[slot];
            result.triangle_chart[triangle] = uint32_t(chart_index);
            for (int i = 0; i < 3; ++i) {
                const uint32_t vertex = mesh.indices[size_t(triangle) * 3 + i];
                const glm::dvec2& corner = chart.corners[slot * 3 + size_t(i)];
                std::vector<std::pair<glm::dvec2, uint32_t>>& vertex_copies = copies[vertex];
                int64_t copy = -1;
                for (const auto& [at, index] : vertex_copies)
                    if (at == corner) copy = index;
                if (copy < 0) {
                    copy = int64_t(out.positions.size());
                    vertex_copies.emplace_back(corner, uint32_t(copy));
                    const glm::dvec2 texel = detail::placedTexel(placement, frame.inner, localTexel(chart, frame, scale, corner));
                    out.positions.push_back(mesh.positions[vertex]);
                    out.normals.push_back(has_normals ? mesh.normals[vertex] : glm::vec3(0.0f));
                    out.uv0.push_back(has_uv0 ? mesh.uv0[vertex] : glm::vec2(0.0f));
                    out.uv1.push_back(glm::vec2(texel / double(resolution)));
                }
                out.indices[size_t(triangle) * 3 + i] = uint32_t(copy);
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

FittedCharts growAndFitCharts(const TriangleMesh& mesh, double texels_per_metre, int padding_texels) {
    const MeshAnalysis analysis = analyseMesh(mesh, texels_per_metre);
    // Seam corners closer than this are one point (ten times the overlap tolerance: a thousandth of a texel).
    const double snap_tolerance = 10.0 * analysis.overlap_tolerance;
    std::vector<int64_t> chart_of;
    FittedCharts fitted;
    fitted.charts = growCharts(mesh, analysis, snap_tolerance, chart_of);
    attachDegenerateTriangles(mesh, analysis.triangles, chart_of, fitted.charts);
    // A chart's read set reaches about one texel beyond its inner rectangle: joins are judged with that ring.
    unfoldAcrossSharpEdges(analysis, chart_of, fitted.charts, texels_per_metre, padding_texels + 1, snap_tolerance);
    fitted.extents = fitChartRectangles(analysis.triangles, fitted.charts, snap_tolerance);
    return fitted;
}

// Packs the charts into a resolution^2 lightmap (the largest density up to texels_per_metre that fits) and writes
// the charted mesh.
LightmapCharts packAndWrite(const TriangleMesh& mesh, const FittedCharts& fitted, double texels_per_metre,
                            int resolution, int padding_texels) {
    const auto shapes_at = [&](double density) { return chartShapes(fitted.charts, fitted.extents, density); };
    const detail::ChartPacking packing =
        detail::packChartShapes(shapes_at, texels_per_metre, resolution, padding_texels);
    return writeChartedMesh(mesh, fitted.charts, fitted.extents, packing, resolution);
}

}  // namespace

LightmapCharts generateLightmapCharts(const TriangleMesh& mesh, double texels_per_metre, int resolution,
                                      int padding_texels) {
    validateChartInputs(mesh, texels_per_metre, resolution, padding_texels);
    return packAndWrite(mesh, growAndFitCharts(mesh, texels_per_metre, padding_texels), texels_per_metre, resolution, padding_texels);
}

LightmapCharts generateLightmapChartsInSmallestLightmap(const TriangleMesh& mesh, double texels_per_metre,
                                                        int max_resolution, int padding_texels) {
    validateChartInputs(mesh, texels_per_metre, max_resolution, padding_texels);
    const FittedCharts fitted = growAndFitCharts(mesh, texels_per_metre, padding_texels);
    const int resolution = detail::smallestFittingResolution(
        chartShapes(fitted.charts, fitted.extents, texels_per_metre), max_resolution, padding_texels);
    return packAndWrite(mesh, fitted, texels_per_metre, resolution, padding_texels);
}

}  // namespace gusuku::bake

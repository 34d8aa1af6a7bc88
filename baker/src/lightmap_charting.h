#pragma once
// Private to the lightmap charting code (generateLightmapCharts, lightmap_uv.h): the mesh and chart types its phases
// share, and the phases of the files that own them:
//   lightmap_charts.cpp            phase 1 (the input checked), phase 8 (the charted mesh written), the entry points
//   lightmap_chart_growing.cpp     phases 2-4: weld and connect the triangles, grow nearly planar charts, give the
//                                  degenerate triangles to a neighbour's chart
//   lightmap_chart_overlap.cpp     whether a flattened triangle overlaps a chart's (growing and unfolding ask)
//   lightmap_chart_unfolding.cpp   phase 5: join charts across sharp edges by unfolding one about their seam
//   lightmap_chart_rectangles.cpp  phase 6: turn each chart to its smallest bounding rectangle
//   lightmap_chart_frames.cpp      phase 7: each chart's frame of texels at a density and the texels its lookups read
// Packing (between phases 7 and 8) is lightmap_pack.h's.

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/maths/mesh.h"
#include "lightmap_pack.h"

namespace gusuku::bake::detail {

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

inline double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

struct FlatTriangle {
    glm::dvec2 corner[3];
    uint32_t welded[3];
    glm::dvec2 min, max;
};

// The flattened triangles of the chart being grown, bucketed on a grid for overlap queries. Triangles much
// larger than a cell go to a list every query scans, so one big floor triangle does not fill thousands of cells.
class FlatChartIndex {
public:
    FlatChartIndex(double cell_size, double tolerance, double same_point = INFINITY)
        : cell_size_(cell_size), tolerance_(tolerance), same_point_(same_point) {}

    /// True when the candidate overlaps a triangle added so far by more than the tolerance
    /// (lightmap_chart_overlap.cpp).
    bool overlapsAny(const FlatTriangle& candidate);

    /// Adds a triangle of the chart: to the cells it spans, or to the list every query scans when it is large.
    void add(const FlatTriangle& triangle);

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

// A chart: its triangles and where their corners lie flattened (metres). A chart grown across gentle edges is
// projected onto its seed's plane; charts joined across sharp edges (phase 5) are unfolded about their seams, so a
// chart's corners are stored rather than derived from one plane.
struct Chart {
    std::vector<uint32_t> triangles;
    std::vector<glm::dvec2> corners;                  // 3 per triangle, in the order of `triangles`
    glm::dvec3 tangent{1, 0, 0}, bitangent{0, 1, 0};  // the seed's plane (growing and phase 4 project onto it)
    glm::dvec2 min{0.0}, max{0.0};                    // of the corners once turned to the smallest rectangle
};

// What chart growing needs to know of the mesh: per-triangle welded corners, normals and areas, who may join
// whom across an edge, and tolerances scaled to the scene (not to its units or its distance from the origin).
struct MeshAnalysis {
    std::vector<TriangleInfo> triangles;
    EdgeNeighbours adjacency;
    double typical_edge = 0.0;       // median first-edge length, metres: the overlap grid's cell scale
    double overlap_tolerance = 0.0;  // overlaps thinner than this (metres) are touching
};

// The smallest bounding rectangle of flattened points over quarter-turn steps: the turn (counter-clockwise
// radians, applied as (x, y) -> (c x + s y, -s x + c y)) and the turned points' bounds.
struct RectangleFit {
    double angle = 0.0;
    glm::dvec2 min{0.0}, max{0.0};
};

// Where a chart lies in its frame: the frame's texels and the offset of the chart's rectangle inside it, per axis
// one of axisFrames' placements.
struct ChartFrame {
    glm::ivec2 inner{1, 1};
    glm::dvec2 margin{0.0};
    glm::dvec2 stretch{1.0};  // per axis: 1, or a spanned frame's stretch (axisFrames)
};

// Phase 2 (lightmap_chart_growing.cpp): weld, measure and connect the triangles.
MeshAnalysis analyseMesh(const TriangleMesh& mesh, double texels_per_metre);

// Phase 3 (lightmap_chart_growing.cpp): charts grown from the largest triangles out; chart_of[triangle] is set for
// every non-degenerate triangle.
std::vector<Chart> growCharts(const TriangleMesh& mesh, const MeshAnalysis& analysis, double snap_tolerance,
                              std::vector<int64_t>& chart_of);

// Phase 4 (lightmap_chart_growing.cpp): every degenerate triangle into a chart it shares a vertex with, or its own.
void attachDegenerateTriangles(const TriangleMesh& mesh, const std::vector<TriangleInfo>& triangles,
                               std::vector<int64_t>& chart_of, std::vector<Chart>& charts);

// Phase 5 (lightmap_chart_unfolding.cpp): charts joined across sharp edges where that saves gutter; the emptied
// charts dropped and chart_of renumbered.
void unfoldAcrossSharpEdges(const MeshAnalysis& analysis, std::vector<int64_t>& chart_of, std::vector<Chart>& charts,
                            double texels_per_metre, int padding, double snap_tolerance);

// Phase 6 (lightmap_chart_rectangles.cpp): each chart turned to its smallest rectangle; returns their extents in
// metres.
std::vector<glm::dvec2> fitChartRectangles(const std::vector<TriangleInfo>& triangles, std::vector<Chart>& charts,
                                           double snap_tolerance);

// The smallest rectangle of the points over kRotationSteps turns (lightmap_chart_rectangles.cpp).
RectangleFit smallestRectangle(const std::vector<glm::dvec2>& points);

// Texels a chart's smallest rectangle takes at the density with its gutter (lightmap_chart_rectangles.cpp).
double paddedTexelArea(const RectangleFit& fit, double texels_per_metre, int padding);

// Phase 7 (lightmap_chart_frames.cpp): each chart's read texels at a density, for the packer.
std::vector<detail::ChartShape> chartShapes(const std::vector<Chart>& charts,
                                            const std::vector<glm::dvec2>& extents, double scale);

// The chart's frame that claims the most texels for its reads, with them in `read` (lightmap_chart_frames.cpp).
ChartFrame chooseChartFrame(const Chart& chart, const glm::dvec2& extent, double scale, std::vector<uint8_t>& read);

// A chart's corner in texels of its unturned frame (lightmap_chart_frames.cpp).
glm::dvec2 localTexel(const Chart& chart, const ChartFrame& frame, double scale, const glm::dvec2& corner);

}  // namespace gusuku::bake::detail

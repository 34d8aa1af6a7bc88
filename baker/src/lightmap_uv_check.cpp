// checkLightmapUvs: can a glTF's own TEXCOORD_1 serve as the lightmap at a given resolution?

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>
#include <vector>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_raster.h"

namespace gusuku::bake {
namespace {

// uv1 points are matched after rounding to 2^-24: the same glTF vertex written twice (split at a normal seam)
// has bit-identical uv1, and 2^-24 is far below a texel at any resolution we accept.
struct UvEdgeKey {
    int64_t a_u, a_v, b_u, b_v;
    bool operator==(const UvEdgeKey&) const = default;
};
struct UvEdgeKeyHash {
    size_t operator()(const UvEdgeKey& key) const {
        uint64_t hash = 1469598103934665603ull;
        for (int64_t part : {key.a_u, key.a_v, key.b_u, key.b_v}) hash = (hash ^ uint64_t(part)) * 1099511628211ull;
        return size_t(hash ^ (hash >> 29));
    }
};

int64_t quantise(float coordinate) { return std::llround(double(coordinate) * 16777216.0); }

size_t findRoot(std::vector<size_t>& parent, size_t node) {
    while (parent[node] != node) node = parent[node] = parent[parent[node]];
    return node;
}

// Charts: triangles joined through edges whose two end points coincide in uv1.
std::vector<size_t> findUvCharts(const TriangleMesh& mesh, const std::vector<bool>& finite_uv, size_t* chart_count) {
    const size_t triangle_count = mesh.triangleCount();
    std::vector<size_t> parent(triangle_count);
    std::iota(parent.begin(), parent.end(), size_t(0));
    std::unordered_map<UvEdgeKey, size_t, UvEdgeKeyHash> first_triangle_on_edge;
    first_triangle_on_edge.reserve(triangle_count * 3);
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        if (!finite_uv[triangle]) continue;
        for (int edge = 0; edge < 3; ++edge) {
            const glm::vec2& a = mesh.uv1[mesh.indices[triangle * 3 + edge]];
            const glm::vec2& b = mesh.uv1[mesh.indices[triangle * 3 + (edge + 1) % 3]];
            UvEdgeKey key{quantise(a.x), quantise(a.y), quantise(b.x), quantise(b.y)};
            if (key.b_u < key.a_u || (key.b_u == key.a_u && key.b_v < key.a_v))
                key = UvEdgeKey{key.b_u, key.b_v, key.a_u, key.a_v};
            auto [it, inserted] = first_triangle_on_edge.emplace(key, triangle);
            if (!inserted) parent[findRoot(parent, triangle)] = findRoot(parent, it->second);
        }
    }
    std::vector<size_t> chart(triangle_count);
    std::unordered_map<size_t, size_t> chart_of_root;
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        const size_t root = findRoot(parent, triangle);
        chart[triangle] = chart_of_root.emplace(root, chart_of_root.size()).first->second;
    }
    *chart_count = chart_of_root.size();
    return chart;
}

// The mesh's uv1 triangles in texel units, with what the checks skip: a triangle with a non-finite uv1, or one
// whose uv1 area is below 1e-6 texel^2 (degenerate).
struct TexelUvTriangles {
    std::vector<bool> finite_uv;
    std::vector<bool> degenerate;
    std::vector<detail::UvTriangle> uv;
    /// Whether the triangle's texels are checked: finite and not degenerate.
    bool claimsArea(size_t triangle) const { return finite_uv[triangle] && !degenerate[triangle]; }
};

// Scales uv1 to texels at `resolution`, counting triangles outside the unit square and degenerate ones.
TexelUvTriangles texelUvTriangles(const TriangleMesh& mesh, int resolution, UvCheckReport& report) {
    const size_t triangle_count = mesh.triangleCount();
    TexelUvTriangles triangles{std::vector<bool>(triangle_count, true), std::vector<bool>(triangle_count, false),
                               std::vector<detail::UvTriangle>(triangle_count)};
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        bool outside = false;
        for (int corner = 0; corner < 3; ++corner) {
            const glm::vec2& uv = mesh.uv1[mesh.indices[triangle * 3 + corner]];
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) triangles.finite_uv[triangle] = false;
            // The negated comparisons also catch NaN.
            if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) outside = true;
            triangles.uv[triangle][corner] = glm::dvec2(uv) * double(resolution);
        }
        if (outside) ++report.outside_unit_square;
        if (triangles.finite_uv[triangle] && std::abs(detail::signedDoubleArea(triangles.uv[triangle])) * 0.5 < 1e-6) {
            triangles.degenerate[triangle] = true;
            ++report.degenerate;
        }
    }
    return triangles;
}

// The texels, clamped to the map, whose corner plus `offset` lies inside uv's bounding box (offset 0.5: texel
// centres).
struct TexelRange {
    int x0, x1, y0, y1;
};
TexelRange texelBounds(const detail::UvTriangle& uv, double offset, int resolution) {
    const double min_u = std::fmin(uv[0].x, std::fmin(uv[1].x, uv[2].x));
    const double max_u = std::fmax(uv[0].x, std::fmax(uv[1].x, uv[2].x));
    const double min_v = std::fmin(uv[0].y, std::fmin(uv[1].y, uv[2].y));
    const double max_v = std::fmax(uv[0].y, std::fmax(uv[1].y, uv[2].y));
    return {int(std::fmax(0.0, std::ceil(min_u - offset))),
            int(std::fmin(double(resolution - 1), std::floor(max_u - offset))),
            int(std::fmax(0.0, std::ceil(min_v - offset))),
            int(std::fmin(double(resolution - 1), std::floor(max_v - offset)))};
}

// Texel centres claimed twice: overlapping_texels and overlapping_triangles.
void countOverlaps(const TexelUvTriangles& triangles, const std::vector<size_t>& chart, int resolution,
                   UvCheckReport& report) {
    const size_t triangle_count = triangles.uv.size();
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    std::vector<int32_t> owner(texel_count, -1);
    std::vector<bool> overlapped_texel(texel_count, false);
    std::vector<bool> overlapping_triangle(triangle_count, false);
    std::vector<bool> covers_a_centre(triangle_count, false);
    auto markOverlap = [&](size_t texel, size_t a, size_t b) {
        if (!overlapped_texel[texel]) ++report.overlapping_texels;
        overlapped_texel[texel] = true;
        overlapping_triangle[a] = overlapping_triangle[b] = true;
    };
    // Centre claims: any texel centre inside two triangles is an overlap (two charts, or one chart folded).
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        if (!triangles.claimsArea(triangle)) continue;
        const detail::UvTriangle& uv = triangles.uv[triangle];
        const TexelRange range = texelBounds(uv, 0.5, resolution);
        for (int y = range.y0; y <= range.y1; ++y) {
            for (int x = range.x0; x <= range.x1; ++x) {
                if (!detail::containsPoint(uv, glm::dvec2(x + 0.5, y + 0.5))) continue;
                covers_a_centre[triangle] = true;
                const size_t texel = size_t(y) * resolution + x;
                if (owner[texel] < 0) owner[texel] = int32_t(triangle);
                else markOverlap(texel, size_t(owner[texel]), triangle);
            }
        }
    }
    // Fallback claims of triangles too thin to cover a centre: an overlap only when another chart is there.
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        if (!triangles.claimsArea(triangle) || covers_a_centre[triangle]) continue;
        const detail::UvTriangle& uv = triangles.uv[triangle];
        const glm::dvec2 centroid = (uv[0] + uv[1] + uv[2]) / 3.0;
        if (!(centroid.x >= 0.0 && centroid.y >= 0.0 && centroid.x < resolution && centroid.y < resolution)) continue;
        const size_t texel = size_t(centroid.y) * resolution + size_t(centroid.x);
        if (owner[texel] < 0) owner[texel] = int32_t(triangle);
        else if (chart[size_t(owner[texel])] != chart[triangle]) markOverlap(texel, size_t(owner[texel]), triangle);
    }
    for (bool flagged : overlapping_triangle) report.overlapping_triangles += flagged ? 1 : 0;
}

// Area touches by two charts: bilinear filtering mixes them there (a warning only): shared_edge_texels.
void countSharedEdgeTexels(const TexelUvTriangles& triangles, const std::vector<size_t>& chart, int resolution,
                           UvCheckReport& report) {
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    std::vector<int64_t> toucher_chart(texel_count, -1);
    std::vector<bool> shared_texel(texel_count, false);
    for (size_t triangle = 0; triangle < triangles.uv.size(); ++triangle) {
        if (!triangles.claimsArea(triangle)) continue;
        const detail::UvTriangle& uv = triangles.uv[triangle];
        TexelRange range = texelBounds(uv, 0.0, resolution);
        range.x0 = std::max(0, range.x0 - 1);
        range.y0 = std::max(0, range.y0 - 1);
        for (int y = range.y0; y <= range.y1; ++y) {
            for (int x = range.x0; x <= range.x1; ++x) {
                const size_t texel = size_t(y) * resolution + x;
                if (toucher_chart[texel] == int64_t(chart[triangle])) continue;
                if (detail::areaInsideTexel(uv, x, y) <= 1e-3) continue;
                if (toucher_chart[texel] < 0) {
                    toucher_chart[texel] = int64_t(chart[triangle]);
                } else if (!shared_texel[texel]) {
                    shared_texel[texel] = true;
                    ++report.shared_edge_texels;
                }
            }
        }
    }
}

// The one-line verdict with the non-zero counts.
std::string uvCheckMessage(const UvCheckReport& report) {
    const std::string at = " at " + std::to_string(report.resolution) + "^2";
    std::string message = report.ok ? "lightmap UVs usable" + at : "lightmap UVs unusable" + at;
    message += ": " + std::to_string(report.triangle_count) + " triangles in " + std::to_string(report.chart_count) +
               " charts";
    if (report.outside_unit_square > 0)
        message += "; " + std::to_string(report.outside_unit_square) + " triangles with uv1 outside [0,1]";
    if (report.overlapping_texels > 0)
        message += "; " + std::to_string(report.overlapping_texels) + " texels claimed twice (overlapping uv1, " +
                   std::to_string(report.overlapping_triangles) + " triangles involved)";
    if (report.degenerate > 0)
        message += "; " + std::to_string(report.degenerate) + " triangles with zero uv1 area";
    if (report.shared_edge_texels > 0)
        message += "; " + std::to_string(report.shared_edge_texels) +
                   " texels touched by two charts (bilinear bleeding at chart edges)";
    return message;
}

}  // namespace

std::vector<uint32_t> lightmapUvCharts(const TriangleMesh& mesh) {
    if (!mesh.has_uv1 || mesh.uv1.size() != mesh.positions.size())
        throw InputError("lightmap", "TEXCOORD_1", "absent or not one per vertex");
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
    std::vector<bool> finite_uv(mesh.triangleCount(), true);
    for (size_t triangle = 0; triangle < finite_uv.size(); ++triangle)
        for (int corner = 0; corner < 3; ++corner) {
            const glm::vec2& uv = mesh.uv1[mesh.indices[triangle * 3 + corner]];
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) finite_uv[triangle] = false;
        }
    size_t chart_count = 0;
    const std::vector<size_t> chart = findUvCharts(mesh, finite_uv, &chart_count);
    return std::vector<uint32_t>(chart.begin(), chart.end());
}

UvCheckReport checkLightmapUvs(const TriangleMesh& mesh, int resolution) {
    if (resolution < 1 || resolution > 16384)
        throw InputError("lightmap", "resolution", "must be in [1, 16384], got " + std::to_string(resolution));
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
    UvCheckReport report;
    report.resolution = resolution;
    report.triangle_count = mesh.triangleCount();
    if (!mesh.has_uv1 || mesh.uv1.size() != mesh.positions.size()) {
        report.message = "no usable lightmap UVs (TEXCOORD_1 absent or not one per vertex)";
        return report;
    }
    const TexelUvTriangles triangles = texelUvTriangles(mesh, resolution, report);
    const std::vector<size_t> chart = findUvCharts(mesh, triangles.finite_uv, &report.chart_count);
    countOverlaps(triangles, chart, resolution, report);
    countSharedEdgeTexels(triangles, chart, resolution, report);
    report.ok = report.outside_unit_square == 0 && report.overlapping_texels == 0;
    report.message = uvCheckMessage(report);
    return report;
}

}  // namespace gusuku::bake

// generateLightmapCharts: cut the building's surface into nearly planar charts, unfold each flat at the requested
// texel density (lengths kept), join charts across sharp edges where that saves gutter (a beam's faces become one
// strip), and pack them into the lightmap (see lightmap_uv.h for the contract).
// This file: phase 1 (the input checked), phase 8 (the charted mesh written) and the entry points that run the
// phases; the others live in lightmap_chart_*.cpp, which lightmap_charting.h lists.

#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_charting.h"
#include "lightmap_pack.h"

namespace gusuku::bake {
namespace {

// The phases of the other files (lightmap_charting.h).
using detail::analyseMesh;
using detail::attachDegenerateTriangles;
using detail::Chart;
using detail::ChartFrame;
using detail::chartShapes;
using detail::chooseChartFrame;
using detail::fitChartRectangles;
using detail::growCharts;
using detail::localTexel;
using detail::MeshAnalysis;
using detail::unfoldAcrossSharpEdges;

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

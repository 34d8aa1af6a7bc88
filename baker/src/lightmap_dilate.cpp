// dilateLightmap: grows each chart's baked values into the empty texels around it, so that bilinear filtering
// at a chart's edge averages the chart with itself instead of with black.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_raster.h"

namespace gusuku::bake {

namespace {

void requireTexels(size_t count, int resolution, const char* what) {
    if (resolution < 1 || count != size_t(resolution) * size_t(resolution))
        throw InputError("lightmap", what,
                         std::string("dilation needs resolution^2 texels (resolution ") + std::to_string(resolution) +
                             ", got " + std::to_string(count) + ")");
}

// One dilation for both entry points: `reader_charts` empty means every texel may feed every neighbour.
void dilate(std::vector<glm::vec4>& rgba_texels, const std::vector<int32_t>& reader_charts, int resolution,
            int iterations) {
    const bool by_chart = !reader_charts.empty();
    // Read from a copy of the previous iteration so that a texel filled now does not feed its neighbours until
    // the next ring: every ring is the average of the ring inside it, independent of scan order.
    std::vector<glm::vec4> previous;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        previous = rgba_texels;
        bool changed = false;
        for (int y = 0; y < resolution; ++y) {
            for (int x = 0; x < resolution; ++x) {
                const size_t index = size_t(y) * resolution + x;
                if (previous[index].w > 0.0f) continue;
                const int32_t reader = by_chart ? reader_charts[index] : kNoReaderChart;
                glm::vec4 sum{0.0f};
                int valid_neighbours = 0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= resolution || ny >= resolution)
                            continue;
                        const size_t neighbour_index = size_t(ny) * resolution + nx;
                        // A chart's texel takes its own chart's light only.
                        if (reader >= 0 && reader_charts[neighbour_index] != reader) continue;
                        const glm::vec4& neighbour = previous[neighbour_index];
                        if (!(neighbour.w > 0.0f)) continue;
                        sum += neighbour;
                        ++valid_neighbours;
                    }
                }
                if (valid_neighbours == 0) continue;
                rgba_texels[index] = sum / float(valid_neighbours);
                changed = true;
            }
        }
        if (!changed) break;
    }
}

}  // namespace

void dilateLightmap(std::vector<glm::vec4>& rgba_texels, int resolution, int iterations) {
    requireTexels(rgba_texels.size(), resolution, "texels");
    dilate(rgba_texels, {}, resolution, iterations);
}

void dilateLightmapWithinCharts(std::vector<glm::vec4>& rgba_texels, const std::vector<int32_t>& reader_charts,
                                int resolution, int iterations) {
    requireTexels(rgba_texels.size(), resolution, "texels");
    requireTexels(reader_charts.size(), resolution, "reader charts");
    dilate(rgba_texels, reader_charts, resolution, iterations);
}

std::vector<int32_t> lightmapTexelReaderCharts(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_chart,
                                               int resolution) {
    detail::validateLightmapMesh(mesh, resolution);
    if (triangle_chart.size() != mesh.triangleCount())
        throw InputError("lightmap", "triangle charts",
                         "need one chart per triangle (" + std::to_string(mesh.triangleCount()) + "), got " +
                             std::to_string(triangle_chart.size()));
    std::vector<int32_t> readers(size_t(resolution) * size_t(resolution), kNoReaderChart);
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        detail::UvTriangle uv;
        for (int i = 0; i < 3; ++i) uv[i] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + i]]) * double(resolution);
        if (!std::isfinite(uv[0].x + uv[0].y + uv[1].x + uv[1].y + uv[2].x + uv[2].y)) continue;
        const glm::dvec2 low = glm::min(uv[0], glm::min(uv[1], uv[2]));
        const glm::dvec2 high = glm::max(uv[0], glm::max(uv[1], uv[2]));
        const int first_x = std::clamp(int(std::floor(low.x - 1.5 - detail::kReadSlackTexels)), 0, resolution - 1);
        const int last_x = std::clamp(int(std::floor(high.x + 0.5 + detail::kReadSlackTexels)), 0, resolution - 1);
        const int first_y = std::clamp(int(std::floor(low.y - 1.5 - detail::kReadSlackTexels)), 0, resolution - 1);
        const int last_y = std::clamp(int(std::floor(high.y + 0.5 + detail::kReadSlackTexels)), 0, resolution - 1);
        const int32_t chart = int32_t(triangle_chart[triangle]);
        for (int y = first_y; y <= last_y; ++y)
            for (int x = first_x; x <= last_x; ++x) {
                if (!detail::bilinearReadsTexel(uv, x, y)) continue;
                int32_t& reader = readers[size_t(y) * size_t(resolution) + size_t(x)];
                if (reader == kNoReaderChart) reader = chart;
                else if (reader != chart) reader = kSharedReaderChart;
            }
    }
    return readers;
}

}  // namespace gusuku::bake

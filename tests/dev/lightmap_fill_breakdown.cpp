// Development aid, not a test (no assertions; not built): where the lightmap texels go per chart (issue 21 item 4). Copy to tests/test_*.cpp to run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_set>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku_bake/lightmap_uv.h"

namespace gusuku::bake {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Whether the triangle overlaps the square [x, x+1] x [y, y+1] by area (separating axes).
bool overlapsSquare(const glm::dvec2 t[3], double x0, double y0, double side) {
    const glm::dvec2 square[4] = {{x0, y0}, {x0 + side, y0}, {x0, y0 + side}, {x0 + side, y0 + side}};
    if (std::max({t[0].x, t[1].x, t[2].x}) <= x0 + 1e-9 || std::min({t[0].x, t[1].x, t[2].x}) >= x0 + side - 1e-9 ||
        std::max({t[0].y, t[1].y, t[2].y}) <= y0 + 1e-9 || std::min({t[0].y, t[1].y, t[2].y}) >= y0 + side - 1e-9)
        return false;
    const double orientation = cross2(t[1] - t[0], t[2] - t[0]);
    if (std::abs(orientation) < 1e-12) return true;
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2 d = t[(edge + 1) % 3] - t[edge];
        double most = -INFINITY;
        for (const glm::dvec2& corner : square) most = std::max(most, (orientation > 0 ? 1 : -1) * cross2(d, corner - t[edge]));
        if (most <= 1e-9) return false;
    }
    return true;
}

void printBreakdown(const char* name, const LightmapCharts& charts) {
    const int r = charts.resolution;
    const TriangleMesh& mesh = charts.mesh;
    std::vector<int> touched_by(size_t(r) * r, -1);
    std::vector<uint8_t> shared(size_t(r) * r, 0);
    std::vector<std::vector<size_t>> chart_texels(charts.chart_count);
    std::vector<int> read_by(size_t(r) * r, -1);
    std::vector<size_t> read_tri(size_t(r) * r, 0);
    size_t read = 0, read_shared = 0;
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        glm::dvec2 t[3];
        for (int i = 0; i < 3; ++i) t[i] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + i]]) * double(r);
        const int chart = int(charts.triangle_chart[triangle]);
        const int x0 = std::max(0, int(std::floor(std::min({t[0].x, t[1].x, t[2].x}))));
        const int x1 = std::min(r - 1, int(std::floor(std::max({t[0].x, t[1].x, t[2].x}))));
        const int y0 = std::max(0, int(std::floor(std::min({t[0].y, t[1].y, t[2].y}))));
        const int y1 = std::min(r - 1, int(std::floor(std::max({t[0].y, t[1].y, t[2].y}))));
        for (int y = std::max(0, y0 - 1); y <= std::min(r - 1, y1 + 1); ++y)
            for (int x = std::max(0, x0 - 1); x <= std::min(r - 1, x1 + 1); ++x)
                if (overlapsSquare(t, x - 0.5, y - 0.5, 2.0)) {
                    int& reader = read_by[size_t(y) * r + x];
                    if (reader < 0) reader = chart, ++read, read_tri[size_t(y) * r + x] = triangle;
                    else if (reader != chart) {
                        if (read_shared < 3) {
                            const size_t o = read_tri[size_t(y) * r + x];
                            std::printf("  first reader tri %zu:", o);
                            for (int i = 0; i < 3; ++i) std::printf(" %.5f %.5f", mesh.uv1[mesh.indices[o * 3 + i]].x * r, mesh.uv1[mesh.indices[o * 3 + i]].y * r);
                            std::printf("\n");
                        }
                        if (read_shared < 3)
                            std::printf("shared texel %d %d charts %d %d tri %zu uv %.5f %.5f / %.5f %.5f / %.5f %.5f\n", x, y, reader, chart, triangle, t[0].x, t[0].y, t[1].x, t[1].y, t[2].x, t[2].y);
                        ++read_shared;
                    }
                }
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                if (overlapsSquare(t, x, y, 1.0)) {
                    int& owner = touched_by[size_t(y) * r + x];
                    if (owner < 0) {
                        owner = chart;
                        chart_texels[size_t(chart)].push_back(size_t(y) * r + x);
                    } else if (owner != chart) shared[size_t(y) * r + x] = 1;
                }
    }
    size_t touched = 0, dilated = 0, rectangles = 0, thin = 0, thin_dilated = 0;
    for (const std::vector<size_t>& texels : chart_texels) {
        touched += texels.size();
        std::unordered_set<size_t> grown;
        int lx = r, ly = r, hx = -1, hy = -1;
        for (size_t at : texels) {
            const int x = int(at % r), y = int(at / r);
            lx = std::min(lx, x), ly = std::min(ly, y), hx = std::max(hx, x), hy = std::max(hy, y);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) grown.insert(size_t(y + dy) * r + size_t(x + dx));
        }
        dilated += grown.size();
        rectangles += size_t(hx - lx + 3) * size_t(hy - ly + 3);
        if (std::min(hx - lx, hy - ly) + 1 <= 2) {
            ++thin;
            thin_dilated += grown.size();
        }
    }
    {
        std::vector<glm::dvec4> box(charts.chart_count, glm::dvec4(1e9, 1e9, -1e9, -1e9));
        for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle)
            for (int i = 0; i < 3; ++i) {
                const glm::dvec2 t = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + i]]) * double(r);
                glm::dvec4& b = box[charts.triangle_chart[triangle]];
                b = glm::dvec4(std::min(b.x, t.x), std::min(b.y, t.y), std::max(b.z, t.x), std::max(b.w, t.y));
            }
        for (int c : {10, 12, 13, 86}) std::printf("chart %d box %.4f %.4f .. %.4f %.4f\n", c, box[c].x, box[c].y, box[c].z, box[c].w);
    }
    const std::vector<LightmapTexel> claimed_texels = rasterizeLightmapTexels(mesh, r);
    const size_t claimed = claimed_texels.size();
    {
        std::vector<size_t> per_chart(charts.chart_count, 0), read_per_chart(charts.chart_count, 0);
        for (const LightmapTexel& texel : claimed_texels) ++per_chart[charts.triangle_chart[texel.triangle]];
        for (int owner : read_by) if (owner >= 0) ++read_per_chart[size_t(owner)];
        std::vector<glm::ivec4> rbox(charts.chart_count, glm::ivec4(1 << 30, 1 << 30, -1, -1));
        for (size_t at = 0; at < read_by.size(); ++at)
            if (read_by[at] >= 0) {
                glm::ivec4& b = rbox[size_t(read_by[at])];
                const int x = int(at % r), y = int(at / r);
                b = glm::ivec4(std::min(b.x, x), std::min(b.y, y), std::max(b.z, x), std::max(b.w, y));
            }
        int hist[8] = {0};
        for (size_t k = 0; k < charts.chart_count; ++k)
            if (per_chart[k] >= 16 && per_chart[k] < 64)
                ++hist[std::min(7, std::min(rbox[k].z - rbox[k].x, rbox[k].w - rbox[k].y) + 1)];
        std::printf("  [16,64) read short side:");
        for (int h = 0; h < 8; ++h) std::printf(" %d:%d", h, hist[h]);
        std::printf("\n");
        const size_t bounds[] = {0, 4, 16, 64, 256, 1024, 1u << 30};
        for (int b = 0; b + 1 < 7; ++b) {
            size_t n = 0, c = 0, rd = 0;
            for (size_t k = 0; k < charts.chart_count; ++k)
                if (per_chart[k] >= bounds[b] && per_chart[k] < bounds[b + 1]) ++n, c += per_chart[k], rd += read_per_chart[k];
            std::printf("  claimed in [%zu, %zu): %zu charts, claimed %zu, read %zu\n", bounds[b], bounds[b + 1], n, c, rd);
        }
    }
    const double all = double(r) * r;
    std::printf("%s: %zu charts at %.2f t/m in %d^2: claimed %.1f %%, touched %.1f %%, touched+1 ring %.1f %%, "
                "read %.1f %% (%zu read twice), padded rectangles %.1f %%, thin charts (<=2 texels across) %zu holding %.1f %% (+ring); shared %zu\n",
                name, charts.chart_count, charts.texels_per_metre, r, 100 * claimed / all, 100 * touched / all,
                100 * dilated / all, 100 * read / all, read_shared, 100 * rectangles / all, thin, 100 * thin_dilated / all,
                size_t(std::count(shared.begin(), shared.end(), 1)));
}

TEST(LightmapFillDetailed, Breakdown) {
    GUSUKU_REQUIRE_SHARED_DATA();
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    options.max_texture_size = 64;
    const TriangleMesh shrine = loadGltf(testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf", options);
    printBreakdown("shrine 16", generateLightmapChartsInSmallestLightmap(shrine, 16.0, 4096));
    TriangleMesh house = loadGltf(testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options);
    house.has_uv1 = false;
    printBreakdown("shrine 16 pad0", generateLightmapChartsInSmallestLightmap(shrine, 16.0, 4096, 0));
    printBreakdown("house 12 pad0", generateLightmapChartsInSmallestLightmap(house, 12.0 * 16.0, 4096, 0));
    printBreakdown("house 12 (x16)", generateLightmapChartsInSmallestLightmap(house, 12.0 * 16.0, 4096));
}

}  // namespace
}  // namespace gusuku::bake

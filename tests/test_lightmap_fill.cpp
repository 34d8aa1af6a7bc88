// Charts that fill the lightmap (issue 11, item 9): the bake's charts (generateLightmapChartsInSmallestLightmap)
// cover at least 60 % of the lightmap's texels (texels whose centre a chart claims, the texels the bake traces)
// at the requested density, on the sample's house, the shared shrine and the shared house, with valid uv1 (no
// texel claimed twice, no texel two charts touch). Before (shelf packing of bounding rectangles, two texels of
// gutter, the side from the area times 2, grown when the density had to drop): the sample's bake 41.9 % (16779
// texels in 200^2), shrine 29.2 % at 23.9 texels/m of 32, house 47.9 % at 979 of 1000 (both at the side
// chooseLightmapResolution gives). Packed by shape into the smallest side: sample 65.5 % (160^2), shrine 51.3 %
// (532^2; 1640 charts, mostly thin beams' faces, 577 one texel across), house 66.1 % (1228^2). Now, with charts
// unfolded across edges up to 90 degrees (a beam's faces one strip) and small charts packed into the holes under
// bigger ones: sample 65.5 % (160^2, 16765 texels), shrine 61.2 % (488^2, 902 charts), house 73.0 % (1172^2).
// Since charts pack their bilinear read sets (issue 21 item 4): sample 66.0 % (160^2, 16897 texels), shrine
// 65.4 % (472^2), house 76.2 % (1148^2). With spanned frames (a chart stretched to end on its last rows of
// centres, lightmap_uv.h): sample 74.4 % (156^2, 18102 texels), shrine 72.9 % (464^2), house 78.6 % (1140^2). The
// bench's coarser densities, where a thin part's read set is most of it, are in test_lightmap_fill_detailed.cpp
// (67-86 %).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/sample_site.h"

namespace gusuku::bake {
namespace {

constexpr double kMinimumFill = 0.60;

// Charts are flattened by unfolding (lengths kept), so each chart's uv1 area is its world area at the density:
// in texels^2, area_m2 * density^2. Flattening by projection (as before) shrank a curved chart by up to cos(40 deg);
// a chart that is not developable (a doubly curved roof) unfolds with its seams cut and keeps its area too.
void expectChartsKeepTheDensity(const char* name, const LightmapCharts& charts) {
    const TriangleMesh& mesh = charts.mesh;
    std::vector<double> uv_area(charts.chart_count, 0.0), world_area(charts.chart_count, 0.0);
    const double texels_per_uv = double(charts.resolution);
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        const uint32_t* corner = &mesh.indices[triangle * 3];
        const glm::dvec3 p0(mesh.positions[corner[0]]), p1(mesh.positions[corner[1]]), p2(mesh.positions[corner[2]]);
        const glm::dvec2 t0 = glm::dvec2(mesh.uv1[corner[0]]) * texels_per_uv;
        const glm::dvec2 e1 = glm::dvec2(mesh.uv1[corner[1]]) * texels_per_uv - t0;
        const glm::dvec2 e2 = glm::dvec2(mesh.uv1[corner[2]]) * texels_per_uv - t0;
        uv_area[charts.triangle_chart[triangle]] += 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
        world_area[charts.triangle_chart[triangle]] += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    }
    double total_uv = 0.0, total_world = 0.0, lowest = INFINITY, highest = 0.0;
    for (size_t chart = 0; chart < charts.chart_count; ++chart) {
        const double expected = world_area[chart] * charts.texels_per_metre * charts.texels_per_metre;
        total_uv += uv_area[chart];
        total_world += expected;
        if (expected < 4.0) continue;  // a chart under two texels square: float noise in uv1 dominates
        lowest = std::min(lowest, uv_area[chart] / expected);
        highest = std::max(highest, uv_area[chart] / expected);
    }
    std::printf("%s: uv1 area / (world area * density^2): all charts %.4f, each in [%.4f, %.4f]\n", name,
                total_uv / total_world, lowest, highest);
    // Spanned frames (lightmap_uv.h) stretch a chart along an axis until it ends on rows of centres: its area
    // grows by under a texel per axis (a thin chart's most), it never shrinks by more than 0.5 % an axis, and
    // over all charts the area stays within a few percent of the density's.
    EXPECT_GE(total_uv / total_world, 1.0 - 1e-3) << name;
    EXPECT_LE(total_uv / total_world, 1.06) << name;
    EXPECT_GE(lowest, 0.99) << name;
}

// Texels whose centre a chart claims (the texels the bake traces), over the lightmap's texels.
void expectChartsFillTheLightmap(const char* name, const TriangleMesh& mesh, double density) {
    const auto start = std::chrono::steady_clock::now();
    const LightmapCharts charts = generateLightmapChartsInSmallestLightmap(mesh, density, 4096);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int resolution = charts.resolution;
    EXPECT_DOUBLE_EQ(charts.texels_per_metre, density) << name << ": the density is kept";
    const UvCheckReport report = checkLightmapUvs(charts.mesh, resolution);
    EXPECT_TRUE(report.ok) << name << ": " << report.message;
    EXPECT_EQ(report.shared_edge_texels, 0u) << name << ": charts keep their gutter";
    const size_t texels = rasterizeLightmapTexels(charts.mesh, resolution).size();
    const double fill = double(texels) / (double(resolution) * resolution);
    std::printf("%s: %zu charts, %d^2 at %.2f texels/m, %zu texels, fill %.1f %%, %.2f s\n", name,
                charts.chart_count, resolution, charts.texels_per_metre, texels, 100.0 * fill, seconds);
    EXPECT_GE(fill, kMinimumFill) << name;
    expectChartsKeepTheDensity(name, charts);
}

// The sample's house as the bake loads it: placed in ENU by site.json (its heading turns it against the axes).
TEST(LightmapFill, SampleHouseChartsFillTheLightmap) {
    const std::string dir = testing::makeTemporaryDirectory("gusuku-fill-sample");
    sample_site::writeSampleSite(dir);
    const SiteConfig site = loadSiteConfig(dir + "/site.json");
    GltfLoadOptions options;
    options.enu_from_model = site.building.enuFromModel(site.site.reference);
    options.max_texture_size = 64;
    expectChartsFillTheLightmap("sample house", loadGltf(site.building.path, options), site.bake.texels_per_metre);
}

TEST(LightmapFillShared, ShrineAndHouseChartsFillTheLightmap) {
    GUSUKU_REQUIRE_SHARED_DATA();
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    options.max_texture_size = 64;
    expectChartsFillTheLightmap(
        "shrine", loadGltf(testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf", options), 32.0);
    // The house is 0.5 units across: 1000 texels per unit, as test_lightmap_uv bakes it.
    expectChartsFillTheLightmap(
        "house", loadGltf(testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options),
        1000.0);
}

}  // namespace
}  // namespace gusuku::bake

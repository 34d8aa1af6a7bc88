// Charts that fill the lightmap (issue 11, item 9): the bake's charts (generateLightmapChartsInSmallestLightmap)
// cover at least 60 % of the lightmap's texels (texels whose centre a chart claims, the texels the bake traces)
// at the requested density, on the sample's house and on the shared house. Before (shelf packing of bounding
// rectangles, two texels of gutter, the side from the area times 2, grown when the density had to drop): the
// sample's bake 41.9 % (16779 texels in 200^2), shrine 29.2 % at 23.9 texels/m of 32, house 47.9 % at 979 of
// 1000 (both at the side chooseLightmapResolution gives). Now: sample 65.5 % (160^2), shrine 51.3 % (532^2),
// house 66.1 % (1228^2), all at the requested density.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gltf_loader.h"
#include "gusuku/site.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/sample_site.h"

namespace gusuku::bake {
namespace {

constexpr double kMinimumFill = 0.60;
// The shrine's 1640 charts are mostly thin beams' faces (577 of them one texel across): each needs a texel of
// gutter on both sides, so even packed without a gap its charts' padded shapes would cover 58 % at most. It
// reaches 50 % (from 29 %); more needs charts that wrap around a beam's edges (not done).
constexpr double kShrineMinimumFill = 0.48;

// Texels whose centre a chart claims (the texels the bake traces), over the lightmap's texels.
void expectChartsFillTheLightmap(const char* name, const TriangleMesh& mesh, double density,
                                 double minimum_fill = kMinimumFill) {
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
    EXPECT_GE(fill, minimum_fill) << name;
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
        "shrine", loadGltf(testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf", options), 32.0,
        kShrineMinimumFill);
    // The house is 0.5 units across: 1000 texels per unit, as test_lightmap_uv bakes it.
    expectChartsFillTheLightmap(
        "house", loadGltf(testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options),
        1000.0);
}

}  // namespace
}  // namespace gusuku::bake

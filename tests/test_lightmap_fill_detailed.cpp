// Charts that fill on detailed models (issue 21, item 4): at the bench's texel densities (scripts/write-bench-site.py:
// the shrine 16 texels/m, the house 12 texels/m at scale 16) and on a generated lattice of thin beams and railings,
// the bake's charts (generateLightmapChartsInSmallestLightmap) claim at least 60 % of the lightmap's texels (the
// texels the bake traces), and no texel is read by the bilinear lookups of two charts (so no chart's light can
// reach another's lookups). Measured: main before this issue, shrine 47.4 %, house 50.7 %; read sets packed and each
// chart placed for its reads, lattice 51.8 % (204^2), shrine 55.2 % (260^2), house 59.4 % (256^2); with spanned
// frames (lightmap_uv.h: a chart stretched to end on rows of centres, whose read ring is then traced texels),
// lattice 86.3 % (188^2), shrine 68.5 % (252^2), house 67.3 % (252^2). The reads are found here from the uv1 alone,
// independently of the packer: a texel is read by a triangle when the triangle meets the open 2 x 2 texel square
// around the texel's centre (bilinear weight above zero somewhere on it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku_bake/lightmap_uv.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {


double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// True when the triangle (texel units) overlaps the open square (x0, x0 + side) x (y0, y0 + side) by area:
// separating axes (the square's two, the triangle's three).
bool triangleMeetsOpenSquare(const glm::dvec2 t[3], double x0, double y0, double side) {
    if (std::max({t[0].x, t[1].x, t[2].x}) <= x0 || std::min({t[0].x, t[1].x, t[2].x}) >= x0 + side ||
        std::max({t[0].y, t[1].y, t[2].y}) <= y0 || std::min({t[0].y, t[1].y, t[2].y}) >= y0 + side)
        return false;
    const double orientation = cross2(t[1] - t[0], t[2] - t[0]);
    if (std::abs(orientation) < 1e-12) return true;  // a sliver: its bounding box decides, conservatively
    const glm::dvec2 square[4] = {{x0, y0}, {x0 + side, y0}, {x0, y0 + side}, {x0 + side, y0 + side}};
    for (int edge = 0; edge < 3; ++edge) {
        const glm::dvec2 direction = t[(edge + 1) % 3] - t[edge];
        double most_inside = -INFINITY;
        for (const glm::dvec2& corner : square)
            most_inside = std::max(most_inside, (orientation > 0 ? 1.0 : -1.0) * cross2(direction, corner - t[edge]));
        if (most_inside <= 0.0) return false;
    }
    return true;
}

// Calls read(texel index, chart) for every texel some bilinear lookup on a triangle reads (found from the uv1
// alone, as above), once per triangle; the read square widened by `slack` texels.
template <typename Read>
void forEachTexelRead(const LightmapCharts& charts, double slack, Read read) {
    const int r = charts.resolution;
    const TriangleMesh& mesh = charts.mesh;
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        glm::dvec2 t[3];
        for (int i = 0; i < 3; ++i) t[i] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + i]]) * double(r);
        const uint32_t chart = charts.triangle_chart[triangle];
        const int x0 = std::max(0, int(std::floor(std::min({t[0].x, t[1].x, t[2].x}) - 1.0)));
        const int x1 = std::min(r - 1, int(std::floor(std::max({t[0].x, t[1].x, t[2].x}) + 1.0)));
        const int y0 = std::max(0, int(std::floor(std::min({t[0].y, t[1].y, t[2].y}) - 1.0)));
        const int y1 = std::min(r - 1, int(std::floor(std::max({t[0].y, t[1].y, t[2].y}) + 1.0)));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                if (triangleMeetsOpenSquare(t, x - 0.5 - slack, y - 0.5 - slack, 2.0 + 2.0 * slack))
                    read(size_t(y) * size_t(r) + size_t(x), chart);
    }
}

// Per texel, the charts whose bilinear lookups read it.
std::vector<std::vector<uint32_t>> readersOfTexels(const LightmapCharts& charts) {
    std::vector<std::vector<uint32_t>> readers(size_t(charts.resolution) * size_t(charts.resolution));
    forEachTexelRead(charts, 0.0, [&](size_t texel, uint32_t chart) {
        std::vector<uint32_t>& list = readers[texel];
        if (std::find(list.begin(), list.end(), chart) == list.end()) list.push_back(chart);
    });
    return readers;
}

struct FillMeasure {
    int resolution = 0;
    size_t charts = 0;
    double claimed = 0.0;  // share of the lightmap's texels a chart claims (the texels the bake traces)
    double read = 0.0;     // share some chart's bilinear lookups read
    size_t read_by_two = 0;  // texels two charts' lookups read
};

FillMeasure measureFill(const LightmapCharts& charts) {
    const int r = charts.resolution;
    // 1e-3 texel of slack: uv1 is float, and a chart edge meant to lie on a texel's read boundary may land inside.
    constexpr double kSlack = 1e-3;
    std::vector<int64_t> reader(size_t(r) * size_t(r), -1);
    FillMeasure measure;
    measure.resolution = r;
    measure.charts = charts.chart_count;
    size_t read = 0;
    forEachTexelRead(charts, kSlack, [&](size_t texel, uint32_t chart) {
        int64_t& first = reader[texel];
        if (first < 0) {
            first = chart;
            ++read;
        } else if (first != int64_t(chart)) {
            ++measure.read_by_two;
            first = chart;  // count each further chart once more, at most
        }
    });
    const double all = double(r) * double(r);
    measure.claimed = double(rasterizeLightmapTexels(charts.mesh, r).size()) / all;
    measure.read = double(read) / all;
    return measure;
}

void expectDetailedChartsFill(const char* name, const TriangleMesh& mesh, double density, double minimum_fill) {
    const LightmapCharts charts = generateLightmapChartsInSmallestLightmap(mesh, density, 4096);
    EXPECT_DOUBLE_EQ(charts.texels_per_metre, density) << name << ": the density is kept";
    const FillMeasure measure = measureFill(charts);
    std::printf("%s at %.1f texels/m: %zu charts in %d^2, fill %.1f %% (claimed texels), read %.1f %%, %zu texels read "
                "by two charts\n",
                name, density, measure.charts, measure.resolution, 100.0 * measure.claimed, 100.0 * measure.read,
                measure.read_by_two);
    EXPECT_GE(measure.claimed, minimum_fill) << name;
    EXPECT_EQ(measure.read_by_two, 0u) << name << ": no texel is read by two charts";
    const UvCheckReport report = checkLightmapUvs(charts.mesh, charts.resolution);
    EXPECT_TRUE(report.ok) << name << ": " << report.message;
}

// A box turned about the vertical by `heading` (radians) about the origin.
TriangleMesh turnedBox(const glm::vec3& min, const glm::vec3& max, float heading) {
    TriangleMesh box = testing::closedBox(min, max, false, glm::vec3(0.5f));
    const float c = std::cos(heading), s = std::sin(heading);
    auto turn = [&](const glm::vec3& p) { return glm::vec3(c * p.x - s * p.y, s * p.x + c * p.y, p.z); };
    for (glm::vec3& p : box.positions) p = turn(p);
    for (glm::vec3& n : box.normals) n = turn(n);
    return box;
}

// A detailed model of many thin parts: a 6 x 6 grid of posts (10 cm square, 1.6 m tall, 0.8 m apart), each row and
// column joined by a top rail and a mid rail (6 cm square), balusters between them every 16 cm (4 cm square), and a
// diagonal brace (5 cm square) across every bay in plan, all turned 20 degrees against the axes. At 16 texels/m a baluster's face is 0.64 texel wide, a post's 1.6.
TriangleMesh lattice() {
    constexpr int kPosts = 6;
    constexpr float kSpacing = 0.8f, kHeight = 1.6f, kPost = 0.05f, kRail = 0.03f, kBaluster = 0.02f, kBrace = 0.025f;
    constexpr float kHeading = 0.349f;  // 20 degrees
    TriangleMesh mesh = testing::emptyMesh(glm::vec3(0.5f));
    auto add = [&](const glm::vec3& centre, const glm::vec3& half, float heading) {
        TriangleMesh box = turnedBox(-half, half, heading);
        const float c = std::cos(kHeading), s = std::sin(kHeading);
        for (glm::vec3& p : box.positions) p += glm::vec3(c * centre.x - s * centre.y, s * centre.x + c * centre.y, centre.z);
        appendMesh(mesh, box);
    };
    for (int j = 0; j < kPosts; ++j)
        for (int i = 0; i < kPosts; ++i)
            add(glm::vec3(i * kSpacing, j * kSpacing, 0.5f * kHeight), glm::vec3(kPost, kPost, 0.5f * kHeight), kHeading);
    for (int line = 0; line < kPosts; ++line)
        for (int bay = 0; bay + 1 < kPosts; ++bay)
            for (int along_y = 0; along_y < 2; ++along_y) {
                const float a = (bay + 0.5f) * kSpacing, b = line * kSpacing;
                const glm::vec3 at = along_y ? glm::vec3(b, a, 0.0f) : glm::vec3(a, b, 0.0f);
                const float half_length = 0.5f * kSpacing - kPost;
                const glm::vec3 rail = along_y ? glm::vec3(kRail, half_length, kRail) : glm::vec3(half_length, kRail, kRail);
                for (const float z : {kHeight - kRail, 0.5f * kHeight}) add(at + glm::vec3(0, 0, z), rail, kHeading);
                for (float offset = -half_length + 0.08f; offset < half_length - 0.04f; offset += 0.16f) {
                    const glm::vec3 shift = along_y ? glm::vec3(0, offset, 0) : glm::vec3(offset, 0, 0);
                    const float low = 0.5f * kHeight + kRail, high = kHeight - 2.0f * kRail;
                    add(at + shift + glm::vec3(0, 0, 0.5f * (low + high)),
                        glm::vec3(kBaluster, kBaluster, 0.5f * (high - low)), kHeading);
                }
            }
    // A diagonal brace in plan across every bay, 0.3 m up, corner post to corner post.
    for (int j = 0; j + 1 < kPosts; ++j)
        for (int i = 0; i + 1 < kPosts; ++i)
            add(glm::vec3((i + 0.5f) * kSpacing, (j + 0.5f) * kSpacing, 0.3f),
                glm::vec3(0.70710678f * kSpacing - kPost, kBrace, kBrace), kHeading + 0.785398f);
    return mesh;
}

TEST(LightmapFillDetailed, LatticeOfThinPartsFills) {
    const TriangleMesh mesh = lattice();
    std::printf("lattice: %zu triangles\n", mesh.triangleCount());
    expectDetailedChartsFill("lattice", mesh, 16.0, 0.60);
}

// The same lattice at 32 texels/m (the density test_lightmap_fill.cpp holds the shrine to), where a baluster's face
// is 1.3 texels and a post's 3.2: 97.5 % measured (332^2; 69.0 % in 356^2 before spanned frames).
TEST(LightmapFillDetailed, LatticeOfThinPartsFillsAtAFinerDensity) {
    expectDetailedChartsFill("lattice", lattice(), 32.0, 0.60);
}

// No bleeding: every chart of the lattice lit its own colour (chart k: (k + 1, 0, 1000 - k), none alike), the bake's
// dilation (8 rings, within charts) fills the gutter, and every texel a chart's bilinear lookups read then holds that
// chart's colour exactly. The plain dilation is run too: it mixes charts in shared gutter texels, so the lattice's
// read texels do touch and the check can fail.
TEST(LightmapFillDetailed, DilationKeepsEveryChartsReadTexelsItsOwn) {
    const LightmapCharts charts = generateLightmapChartsInSmallestLightmap(lattice(), 16.0, 4096);
    const int r = charts.resolution;
    auto colour = [](uint32_t chart) { return glm::vec4(float(chart + 1), 0.0f, 1000.0f - float(chart), 1.0f); };
    std::vector<glm::vec4> image(size_t(r) * size_t(r), glm::vec4(0.0f));
    for (const LightmapTexel& texel : rasterizeLightmapTexels(charts.mesh, r))
        image[size_t(texel.y) * size_t(r) + size_t(texel.x)] = colour(charts.triangle_chart[texel.triangle]);
    const std::vector<std::vector<uint32_t>> readers = readersOfTexels(charts);
    auto wrongTexels = [&](const std::vector<glm::vec4>& dilated) {
        size_t wrong = 0;
        for (size_t at = 0; at < dilated.size(); ++at)
            for (uint32_t chart : readers[at])
                if (dilated[at] != colour(chart)) ++wrong;
        return wrong;
    };
    std::vector<glm::vec4> within_charts = image, plain = image;
    dilateLightmapWithinCharts(within_charts,
                               lightmapTexelReaderCharts(charts.mesh, charts.triangle_chart, r), r, 8);
    dilateLightmap(plain, r, 8);
    const size_t plain_wrong = wrongTexels(plain);
    std::printf("lattice %d^2: read texels holding another chart's light: %zu within charts, %zu plain dilation\n", r,
                wrongTexels(within_charts), plain_wrong);
    EXPECT_EQ(wrongTexels(within_charts), 0u);
    EXPECT_GT(plain_wrong, 0u) << "the charts' read texels never touch: the check proves nothing";
}

TEST(LightmapFillDetailedShared, ShrineAndHouseFillAtTheBenchDensities) {
    GUSUKU_REQUIRE_SHARED_DATA();
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    options.max_texture_size = 64;
    expectDetailedChartsFill(
        "shrine", loadGltf(testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf", options), 16.0, 0.60);
    // The house is 0.5 units across and baked at scale 16, 12 texels/m: 192 texels per unit. Its own TEXCOORD_1 is
    // set aside here: these are the charts the baker makes of it.
    TriangleMesh house = loadGltf(testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options);
    house.has_uv1 = false;
    expectDetailedChartsFill("house", house, 12.0 * 16.0, 0.60);
}

}  // namespace
}  // namespace gusuku::bake

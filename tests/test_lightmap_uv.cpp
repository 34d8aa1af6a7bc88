// Lightmap UVs: resolution choice, the TEXCOORD_1 checker, generated charts, texel rasterisation, dilation.
// The cube tests judge the charts by geometry the test computes itself (face membership from the cube's
// construction, coverage by supersampling), never by the chart code's own bookkeeping.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"

namespace {

using gusuku::TriangleMesh;
using namespace gusuku::bake;

// Appends a quad (corners in order around it) as two triangles wound counter-clockwise seen from `normal`,
// with its own four vertices, as glTF exporters split vertices at hard edges.
void addQuad(TriangleMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal) {
    if (glm::dot(glm::cross(b - a, c - a), normal) < 0.0f) std::swap(b, d);
    const uint32_t first = uint32_t(mesh.positions.size());
    for (const glm::vec3& corner : {a, b, c, d}) {
        mesh.positions.push_back(corner);
        mesh.normals.push_back(normal);
        mesh.uv0.push_back(glm::vec2(0.0f));
    }
    for (uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + index);
    mesh.triangle_material.push_back(0);
    mesh.triangle_material.push_back(0);
}

// The unit cube [0,1]^3; triangles 2f and 2f+1 make face f.
TriangleMesh unitCube() {
    TriangleMesh mesh;
    mesh.materials.push_back(gusuku::Material{});
    for (int axis = 0; axis < 3; ++axis) {
        for (float side : {0.0f, 1.0f}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            glm::vec3 corner[4];
            const float us[4] = {0, 1, 1, 0}, vs[4] = {0, 0, 1, 1};
            for (int i = 0; i < 4; ++i) {
                corner[i][axis] = side;
                corner[i][u] = us[i];
                corner[i][v] = vs[i];
            }
            glm::vec3 normal(0.0f);
            normal[axis] = side > 0.5f ? 1.0f : -1.0f;
            addQuad(mesh, corner[0], corner[1], corner[2], corner[3], normal);
        }
    }
    return mesh;
}

// A flat quad in the z = 0 plane with the given uv1 at its corners (two triangles, one uv chart).
void addUvQuad(TriangleMesh& mesh, glm::vec2 uv_min, glm::vec2 uv_max, float x_offset) {
    const uint32_t first = uint32_t(mesh.positions.size());
    const glm::vec2 uvs[4] = {uv_min, {uv_max.x, uv_min.y}, uv_max, {uv_min.x, uv_max.y}};
    const glm::vec3 positions[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i) {
        mesh.positions.push_back(positions[i] + glm::vec3(x_offset, 0, 0));
        mesh.normals.push_back({0, 0, 1});
        mesh.uv0.push_back(glm::vec2(0.0f));
        mesh.uv1.push_back(uvs[i]);
    }
    for (uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + index);
    mesh.triangle_material.push_back(0);
    mesh.triangle_material.push_back(0);
    mesh.has_uv1 = true;
    if (mesh.materials.empty()) mesh.materials.push_back(gusuku::Material{});
}

// Texels whose area a triangle touches, by 4x4 supersampling (inclusive edges): an estimate independent of
// the code under test.
std::vector<std::pair<int, int>> supersampledTexels(const TriangleMesh& mesh, size_t triangle, int resolution) {
    glm::dvec2 uv[3];
    for (int i = 0; i < 3; ++i) uv[i] = glm::dvec2(mesh.uv1[mesh.indices[triangle * 3 + i]]) * double(resolution);
    auto edge = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    const double area = edge(uv[0], uv[1], uv[2]);
    std::vector<std::pair<int, int>> texels;
    const int x0 = std::max(0, int(std::floor(std::min({uv[0].x, uv[1].x, uv[2].x}))));
    const int x1 = std::min(resolution - 1, int(std::floor(std::max({uv[0].x, uv[1].x, uv[2].x}))));
    const int y0 = std::max(0, int(std::floor(std::min({uv[0].y, uv[1].y, uv[2].y}))));
    const int y1 = std::min(resolution - 1, int(std::floor(std::max({uv[0].y, uv[1].y, uv[2].y}))));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            bool touched = false;
            for (int s = 0; s < 16 && !touched; ++s) {
                const glm::dvec2 p(x + (s % 4 + 0.5) / 4.0, y + (s / 4 + 0.5) / 4.0);
                const double w0 = edge(uv[1], uv[2], p) / area, w1 = edge(uv[2], uv[0], p) / area;
                touched = w0 >= 0 && w1 >= 0 && w0 + w1 <= 1;
            }
            if (touched) texels.emplace_back(x, y);
        }
    return texels;
}

constexpr double kCubeDensity = 8.0;  // texels per metre
constexpr int kCubeResolution = 64;

TEST(LightmapResolution, FollowsAreaAndDensityRoundedToFour) {
    // 6 m^2 at 8 texels/m, with the documented overhead of 2: sqrt(6 * 64 * 2) = 27.7 -> 28.
    EXPECT_EQ(chooseLightmapResolution(unitCube(), 8.0), 28);
    EXPECT_EQ(chooseLightmapResolution(unitCube(), 8.0) % 4, 0);
    EXPECT_EQ(chooseLightmapResolution(unitCube(), 1000.0, 1022), 1020);  // capped, rounded down to 4
    EXPECT_THROW(chooseLightmapResolution(unitCube(), 0.0), gusuku::InputError);
    EXPECT_THROW(chooseLightmapResolution(unitCube(), std::nan("")), gusuku::InputError);
}

TEST(LightmapCharts, CubeChartsStayInsideTheUnitSquareAndKeepTheMesh) {
    const TriangleMesh cube = unitCube();
    const LightmapCharts charts = generateLightmapCharts(cube, kCubeDensity, kCubeResolution);
    ASSERT_TRUE(charts.mesh.has_uv1);
    EXPECT_EQ(charts.chart_count, 6u);  // faces meet at 90 degrees: one chart each
    EXPECT_DOUBLE_EQ(charts.texels_per_metre, kCubeDensity);  // plenty of room: no shrinking
    ASSERT_EQ(charts.mesh.uv1.size(), charts.mesh.positions.size());
    for (const glm::vec2& uv : charts.mesh.uv1) {
        EXPECT_GE(uv.x, 0.0f);
        EXPECT_LE(uv.x, 1.0f);
        EXPECT_GE(uv.y, 0.0f);
        EXPECT_LE(uv.y, 1.0f);
    }
    ASSERT_EQ(charts.mesh.triangleCount(), cube.triangleCount());
    for (size_t triangle = 0; triangle < cube.triangleCount(); ++triangle) {
        EXPECT_EQ(charts.triangle_chart[triangle], charts.triangle_chart[triangle / 2 * 2]);  // a face, one chart
        for (int i = 0; i < 3; ++i) {
            const uint32_t before = cube.indices[triangle * 3 + i], after = charts.mesh.indices[triangle * 3 + i];
            EXPECT_EQ(charts.mesh.positions[after], cube.positions[before]);
            EXPECT_EQ(charts.mesh.normals[after], cube.normals[before]);
        }
    }
    const UvCheckReport report = checkLightmapUvs(charts.mesh, kCubeResolution);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.overlapping_texels, 0u);
    EXPECT_EQ(report.shared_edge_texels, 0u);
    EXPECT_EQ(report.chart_count, 6u);
}

TEST(LightmapCharts, CubeChartsDoNotOverlapAndKeepTwoTexelsOfPadding) {
    const TriangleMesh cube = unitCube();
    const int padding = 2;
    const LightmapCharts charts = generateLightmapCharts(cube, kCubeDensity, kCubeResolution, padding);
    // Touched texels per face, by supersampling; a texel touched by two faces is an overlap.
    std::vector<int> face_of_texel(kCubeResolution * kCubeResolution, -1);
    std::vector<std::vector<std::pair<int, int>>> face_texels(6);
    int texels_touched_twice = 0;
    for (size_t triangle = 0; triangle < cube.triangleCount(); ++triangle) {
        const int face = int(triangle / 2);
        for (auto [x, y] : supersampledTexels(charts.mesh, triangle, kCubeResolution)) {
            int& owner = face_of_texel[y * kCubeResolution + x];
            if (owner >= 0 && owner != face) ++texels_touched_twice;
            if (owner < 0) {
                owner = face;
                face_texels[face].emplace_back(x, y);
            }
        }
    }
    EXPECT_EQ(texels_touched_twice, 0);
    // Padding on each side: dilating every chart by `padding` rings must not make two charts meet, i.e. the
    // Chebyshev distance between texels of different charts is at least 2 * padding + 1.
    int closest = 1 << 30;
    for (int a = 0; a < 6; ++a)
        for (int b = a + 1; b < 6; ++b)
            for (auto [ax, ay] : face_texels[a])
                for (auto [bx, by] : face_texels[b]) closest = std::min(closest, std::max(std::abs(ax - bx), std::abs(ay - by)));
    EXPECT_GE(closest, 2 * padding + 1);
}

TEST(LightmapCharts, LowersTheDensityWhenTheChartsDoNotFitAndReportsIt) {
    const TriangleMesh cube = unitCube();
    // Six 1 m faces at 8 texels/m need 6 shapes of 9 + 2 texels (one of gutter each side): not in 24^2.
    const int resolution = 24;
    const LightmapCharts charts = generateLightmapCharts(cube, kCubeDensity, resolution);
    EXPECT_LT(charts.texels_per_metre, kCubeDensity);
    EXPECT_GT(charts.texels_per_metre, 1.0);
    // The reported density is the one the UVs carry: each 1 m face spans texels_per_metre texels.
    for (size_t face = 0; face < 6; ++face) {
        glm::vec2 low(1e9f), high(-1e9f);
        for (size_t corner = 0; corner < 6; ++corner) {
            const glm::vec2 uv = charts.mesh.uv1[charts.mesh.indices[face * 6 + corner]] * float(resolution);
            low = glm::min(low, uv);
            high = glm::max(high, uv);
        }
        // Spanned frames (lightmap_uv.h) stretch a face to end just inside a row of centres: by under one texel,
        // and never shrink it by more than 0.5 %.
        for (int axis = 0; axis < 2; ++axis) {
            EXPECT_GE(high[axis] - low[axis], 0.995 * charts.texels_per_metre - 1e-3) << "face " << face;
            EXPECT_LT(high[axis] - low[axis], charts.texels_per_metre + 1.0) << "face " << face;
        }
    }
    const UvCheckReport report = checkLightmapUvs(charts.mesh, resolution);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.shared_edge_texels, 0u);
}

TEST(LightmapCharts, RejectsWhatCannotBeCharted) {
    // Six charts reading at least 2 x 2 texels each cannot fit in 4^2.
    EXPECT_THROW(generateLightmapCharts(unitCube(), kCubeDensity, 4), gusuku::InputError);
    EXPECT_THROW(generateLightmapCharts(TriangleMesh{}, kCubeDensity, 64), gusuku::InputError);
    EXPECT_THROW(generateLightmapCharts(unitCube(), -1.0, 64), gusuku::InputError);
    TriangleMesh bad_index = unitCube();
    bad_index.indices[4] = 999;
    EXPECT_THROW(generateLightmapCharts(bad_index, kCubeDensity, 64), gusuku::InputError);
}

TEST(LightmapTexels, CubeTexelsLieOnTheirFacesAtTheRequestedDensity) {
    const TriangleMesh cube = unitCube();
    const LightmapCharts charts = generateLightmapCharts(cube, kCubeDensity, kCubeResolution);
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(charts.mesh, kCubeResolution);
    ASSERT_FALSE(texels.empty());
    std::vector<int> texels_per_face(6, 0);
    std::set<std::pair<int, int>> seen;
    for (const LightmapTexel& texel : texels) {
        ASSERT_LT(texel.triangle, cube.triangleCount());
        EXPECT_TRUE(seen.emplace(texel.x, texel.y).second) << "texel listed twice";
        ++texels_per_face[texel.triangle / 2];
        const glm::vec3 corner = cube.positions[cube.indices[texel.triangle * 3]];
        const glm::vec3 face_normal = cube.normals[cube.indices[texel.triangle * 3]];
        EXPECT_NEAR(glm::dot(texel.position - corner, face_normal), 0.0f, 1e-4f) << "off its triangle's plane";
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_GE(texel.position[axis], -1e-4f);
            EXPECT_LE(texel.position[axis], 1.0f + 1e-4f);
        }
        EXPECT_NEAR(glm::dot(texel.geometric_normal, face_normal), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(texel.shading_normal, face_normal), 1.0f, 1e-5f);
    }
    // 1 m x 1 m at 8 texels/m: 8 x 8 centres covered, or 9 x 9 when the face is spanned (lightmap_uv.h: it ends
    // on a row of centres at each side, which the near-claim rule traces).
    for (int face = 0; face < 6; ++face) {
        EXPECT_GE(texels_per_face[face], 48) << "face " << face;
        EXPECT_LE(texels_per_face[face], 81) << "face " << face;
    }
}

TEST(LightmapTexels, ThinTriangleStillGetsTheTexelUnderItsCentroid) {
    TriangleMesh mesh;
    mesh.materials.push_back(gusuku::Material{});
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0.01f, 0}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.uv0.assign(3, glm::vec2(0.0f));
    // In an 8x8 map: from (1.1, 2.1) to (3.9, 2.1) to (1.1, 2.2) texels: it covers no texel centre.
    mesh.uv1 = {{1.1f / 8, 2.1f / 8}, {3.9f / 8, 2.1f / 8}, {1.1f / 8, 2.2f / 8}};
    mesh.has_uv1 = true;
    mesh.indices = {0, 1, 2};
    mesh.triangle_material = {0};
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, 8);
    ASSERT_EQ(texels.size(), 1u);
    // The centroid is at (2.03, 2.13) texels: texel (2, 2).
    EXPECT_EQ(texels[0].x, 2);
    EXPECT_EQ(texels[0].y, 2);
    EXPECT_NEAR(texels[0].position.z, 0.0f, 1e-6f);
    EXPECT_GE(texels[0].position.y, 0.0f);  // clamped onto the triangle, not extrapolated
    EXPECT_LE(texels[0].position.y, 0.01f);
}

TEST(LightmapTexels, OneTriangleOwnsEachTexelLargerCoverageWinning) {
    // A 4x4 map fully covered by a quad (triangles 0 and 1, z = 0). Triangle 2 (z = 1) is a small sliver
    // around texel (1, 1)'s centre covering 0.08 of that texel, against at least 0.5 for the quad's triangle
    // there; triangle 3 (z = 2) is a thin triangle inside texel (3, 3) that covers no centre, so its fallback
    // claim yields to the quad's centre claim.
    TriangleMesh mesh;
    addUvQuad(mesh, {0, 0}, {1, 1}, 0.0f);
    auto addSliver = [&](glm::vec2 a, glm::vec2 b, glm::vec2 c, float z) {
        const uint32_t first = uint32_t(mesh.positions.size());
        for (const glm::vec2& texel_uv : {a, b, c}) {
            mesh.positions.push_back(glm::vec3(texel_uv, z));
            mesh.normals.push_back({0, 0, 1});
            mesh.uv0.push_back(glm::vec2(0.0f));
            mesh.uv1.push_back(texel_uv / 4.0f);
        }
        for (uint32_t i = 0; i < 3; ++i) mesh.indices.push_back(first + i);
        mesh.triangle_material.push_back(0);
    };
    addSliver({1.3f, 1.3f}, {1.7f, 1.3f}, {1.5f, 1.7f}, 1.0f);
    addSliver({3.1f, 3.1f}, {3.3f, 3.1f}, {3.1f, 3.3f}, 2.0f);
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, 4);
    ASSERT_EQ(texels.size(), 16u);
    for (const LightmapTexel& texel : texels) {
        EXPECT_LT(texel.triangle, 2u) << "texel (" << texel.x << ", " << texel.y << ")";
        EXPECT_NEAR(texel.position.z, 0.0f, 1e-6f);
    }
    const UvCheckReport report = checkLightmapUvs(mesh, 4);
    EXPECT_FALSE(report.ok);
    EXPECT_EQ(report.chart_count, 3u);
    EXPECT_EQ(report.overlapping_texels, 2u);  // (1, 1): two centre claims; (3, 3): another chart's fallback
}

TEST(LightmapUvCheck, AcceptsAQuadWhoseDiagonalRunsThroughTexelCentres) {
    // The shared diagonal passes exactly through four texel centres of the 4x4 map: each must go to one side.
    TriangleMesh mesh;
    addUvQuad(mesh, {0, 0}, {1, 1}, 0.0f);
    const UvCheckReport report = checkLightmapUvs(mesh, 4);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.overlapping_texels, 0u);
    EXPECT_EQ(report.chart_count, 1u);
    EXPECT_EQ(rasterizeLightmapTexels(mesh, 4).size(), 16u);  // every texel, exactly once
}

TEST(LightmapUvCheck, FlagsOverlappingCharts) {
    TriangleMesh mesh;
    addUvQuad(mesh, {0.1f, 0.1f}, {0.6f, 0.6f}, 0.0f);
    addUvQuad(mesh, {0.4f, 0.4f}, {0.9f, 0.9f}, 2.0f);  // another part of the surface on the same texels
    const UvCheckReport report = checkLightmapUvs(mesh, 20);
    EXPECT_FALSE(report.ok);
    // The two squares share [0.4, 0.6]^2: texel centres (x + 0.5) / 20 in it for x = 8..11, so 4 x 4.
    EXPECT_EQ(report.overlapping_texels, 16u);
    EXPECT_EQ(report.overlapping_triangles, 4u);
    EXPECT_EQ(report.chart_count, 2u);
    EXPECT_NE(report.message.find("16 texels claimed twice"), std::string::npos) << report.message;
}

TEST(LightmapUvCheck, FlagsUvsOutsideTheUnitSquareAndAcceptsSeparateCharts) {
    TriangleMesh outside;
    addUvQuad(outside, {0.5f, 0.5f}, {1.2f, 0.9f}, 0.0f);
    const UvCheckReport outside_report = checkLightmapUvs(outside, 16);
    EXPECT_FALSE(outside_report.ok);
    EXPECT_EQ(outside_report.outside_unit_square, 2u);
    EXPECT_NE(outside_report.message.find("outside [0,1]"), std::string::npos);

    TriangleMesh separate;
    addUvQuad(separate, {0.0f, 0.0f}, {0.4f, 0.4f}, 0.0f);
    addUvQuad(separate, {0.6f, 0.6f}, {1.0f, 1.0f}, 2.0f);
    const UvCheckReport separate_report = checkLightmapUvs(separate, 16);
    EXPECT_TRUE(separate_report.ok) << separate_report.message;
    EXPECT_EQ(separate_report.overlapping_texels, 0u);
    EXPECT_EQ(separate_report.shared_edge_texels, 0u);

    TriangleMesh without_uv1 = unitCube();
    EXPECT_FALSE(checkLightmapUvs(without_uv1, 16).ok);
}

TEST(LightmapUvCheck, ChartsCloserThanATexelAreAWarningNotAFailure) {
    TriangleMesh mesh;
    // At 10 texels the first ends at u = 4.2 texels and the second starts at 4.7: both touch column 4, and
    // neither covers its centres (u = 4.5), so nothing is claimed twice.
    addUvQuad(mesh, {0.0f, 0.0f}, {0.42f, 1.0f}, 0.0f);
    addUvQuad(mesh, {0.47f, 0.0f}, {1.0f, 1.0f}, 2.0f);
    const UvCheckReport report = checkLightmapUvs(mesh, 10);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.shared_edge_texels, 10u);  // column 4, all ten rows
}

TEST(LightmapDilate, FillsRingsFromTheAverageOfValidNeighbours) {
    // 3x3, valid texels at (0,0) red and (2,0) blue; worked by hand from the contract.
    const glm::vec4 red(1, 0, 0, 1), blue(0, 0, 1, 1), empty(0.0f);
    std::vector<glm::vec4> texels = {red, empty, blue, empty, empty, empty, empty, empty, empty};
    dilateLightmap(texels, 3, 1);
    EXPECT_EQ(texels[0], red);
    EXPECT_EQ(texels[2], blue);
    EXPECT_EQ(texels[1], glm::vec4(0.5f, 0, 0.5f, 1));  // (0,0) and (2,0)
    EXPECT_EQ(texels[3], red);                          // only (0,0) was valid at the start
    EXPECT_EQ(texels[4], glm::vec4(0.5f, 0, 0.5f, 1));
    EXPECT_EQ(texels[5], blue);
    for (int i = 6; i < 9; ++i) EXPECT_EQ(texels[i], empty) << "row 2 is two rings away";
    dilateLightmap(texels, 3, 1);
    EXPECT_EQ(texels[6], glm::vec4(0.75f, 0, 0.25f, 1));  // (0,1) red and (1,1) purple
    EXPECT_NEAR(texels[7].x, 0.5f, 1e-6f);                // (0,1), (1,1), (2,1)
    EXPECT_NEAR(texels[7].z, 0.5f, 1e-6f);
    EXPECT_EQ(texels[8], glm::vec4(0.25f, 0, 0.75f, 1));
    EXPECT_THROW(dilateLightmap(texels, 4, 1), gusuku::InputError);
}

TEST(LightmapDilate, StopsWhenNothingIsValid) {
    std::vector<glm::vec4> texels(16, glm::vec4(0.0f));
    dilateLightmap(texels, 4, 10);
    for (const glm::vec4& texel : texels) EXPECT_EQ(texel, glm::vec4(0.0f));
}

TEST(LightmapChartsShared, ShrineGetsChartsWithoutOverlapInSeconds) {
    GUSUKU_REQUIRE_SHARED_DATA();
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    options.max_texture_size = 256;
    const TriangleMesh shrine = gusuku::loadGltf(
        gusuku::testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf", options);
    ASSERT_GT(shrine.triangleCount(), 10000u);
    const double density = 32.0;
    const int resolution = chooseLightmapResolution(shrine, density, 2048);
    const auto start = std::chrono::steady_clock::now();
    const LightmapCharts charts = generateLightmapCharts(shrine, density, resolution);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 10.0);
    const UvCheckReport report = checkLightmapUvs(charts.mesh, resolution);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.outside_unit_square, 0u);
    EXPECT_EQ(report.overlapping_texels, 0u);
    EXPECT_EQ(report.shared_edge_texels, 0u) << "charts must keep their padding";
    EXPECT_GT(charts.texels_per_metre, 0.25 * density) << "packing lost too much density";
    EXPECT_EQ(charts.mesh.triangle_material, shrine.triangle_material);
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(charts.mesh, resolution);
    EXPECT_GT(texels.size(), size_t(resolution) * resolution / 8);
    std::printf("shrine: %zu triangles, %zu charts, %d^2 texels, %.1f texels/m, %zu texels covered, %.2f s\n",
                shrine.triangleCount(), charts.chart_count, resolution, charts.texels_per_metre, texels.size(),
                seconds);
}

// The house's TEXCOORD_1 does not pass, and that is the file, not the checker: the .glb holds two meshes whose
// TEXCOORD_1 accessors each span [0.01, 0.99] x [0.01, 0.99] (their glTF min/max), i.e. one full lightmap
// layout per mesh (PlayCanvas bakes one lightmap per mesh instance), so in the one lightmap of the flattened
// building they land on each other. (An independent count straight from the .glb's buffers, strict
// centre-inside at 512^2, also finds 1743 centres claimed twice inside the first mesh alone.) The checker must
// say so; the baker then makes its own charts, which must pass.
TEST(LightmapUvCheckShared, HouseTexcoord1OverlapsAndGeneratedChartsReplaceIt) {
    GUSUKU_REQUIRE_SHARED_DATA();
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    const TriangleMesh house = gusuku::loadGltf(
        gusuku::testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options);
    ASSERT_TRUE(house.has_uv1);
    const int resolution = 512;
    const UvCheckReport report = checkLightmapUvs(house, resolution);
    std::printf("house TEXCOORD_1: %s\n", report.message.c_str());
    EXPECT_EQ(report.outside_unit_square, 0u);  // accessor min/max: inside [0.01, 0.99]
    EXPECT_FALSE(report.ok);
    EXPECT_GT(report.overlapping_texels, 1743u);  // at least the first mesh's own, plus the two layouts' overlap
    EXPECT_NE(report.message.find("claimed twice"), std::string::npos);

    // The house is 0.5 units across: charts at 1000 texels per unit.
    const LightmapCharts charts = generateLightmapCharts(house, 1000.0, resolution);
    const UvCheckReport generated = checkLightmapUvs(charts.mesh, resolution);
    EXPECT_TRUE(generated.ok) << generated.message;
    EXPECT_EQ(generated.shared_edge_texels, 0u);
    std::printf("house generated: %zu charts at %.0f texels/unit: %s\n", charts.chart_count,
                charts.texels_per_metre, generated.message.c_str());
}

// 65k triangles of a finely tessellated sphere: curved charts that must not fold, in a few seconds.
TEST(LightmapCharts, FineSphereChartsWithoutOverlapInSeconds) {
    TriangleMesh sphere;
    sphere.materials.push_back(gusuku::Material{});
    const int rings = 128, segments = 256;
    for (int ring = 0; ring <= rings; ++ring)
        for (int segment = 0; segment <= segments; ++segment) {
            const double polar = std::numbers::pi * ring / rings, azimuth = 2.0 * std::numbers::pi * segment / segments;
            const glm::vec3 direction(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                      std::cos(polar));
            sphere.positions.push_back(direction * 2.0f);
            sphere.normals.push_back(direction);
            sphere.uv0.push_back(glm::vec2(0.0f));
        }
    auto vertex = [&](int ring, int segment) { return uint32_t(ring * (segments + 1) + segment); };
    for (int ring = 0; ring < rings; ++ring)
        for (int segment = 0; segment < segments; ++segment) {
            // Outward counter-clockwise; the polar rows make zero-area triangles, which must be harmless.
            for (uint32_t index : {vertex(ring, segment), vertex(ring + 1, segment), vertex(ring + 1, segment + 1),
                                   vertex(ring, segment), vertex(ring + 1, segment + 1), vertex(ring, segment + 1)})
                sphere.indices.push_back(index);
            sphere.triangle_material.push_back(0);
            sphere.triangle_material.push_back(0);
        }
    ASSERT_GT(sphere.triangleCount(), 50000u);
    const double density = 64.0;
    const int resolution = chooseLightmapResolution(sphere, density);
    const auto start = std::chrono::steady_clock::now();
    const LightmapCharts charts = generateLightmapCharts(sphere, density, resolution);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5.0);
    // 40 degree cones on a sphere: a handful of charts, not thousands.
    EXPECT_LT(charts.chart_count, 200u);
    const UvCheckReport report = checkLightmapUvs(charts.mesh, resolution);
    EXPECT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.shared_edge_texels, 0u);
    // Every texel on the sphere of radius 2.
    for (const LightmapTexel& texel : rasterizeLightmapTexels(charts.mesh, resolution))
        ASSERT_NEAR(glm::length(texel.position), 2.0f, 2e-3f);
    std::printf("sphere: %zu triangles, %zu charts, %d^2, %.1f texels/m, %.2f s\n", sphere.triangleCount(),
                charts.chart_count, resolution, charts.texels_per_metre, seconds);
}

}  // namespace

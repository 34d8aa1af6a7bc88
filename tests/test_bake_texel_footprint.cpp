// Texels that stand for their area (issue 11, item 3): a texel's baked irradiance is the mean over its
// footprint, not the value at its centre.
//
// The scene: a black plane (albedo 0, so only the sky counts) with two grooves 3 cm wide and 5 cm deep cut along
// y, under a uniform sky of radiance L, baked at 10 cm texels with planar uv1 = (x, y) / 1.2 m (the grooves'
// walls have no uv area; their floors lie in the texel footprints). Exact irradiance:
// - on the top surface the whole upper hemisphere is sky: E = pi L;
// - on a groove's floor, a point s from one wall of a slot of width w and depth d (infinitely long) sees the
//   sky through the opening with the 2D view factor F(s) = (s / sqrt(s^2 + d^2) + (w - s) / sqrt((w - s)^2 +
//   d^2)) / 2, E = pi L F(s); its integral over [a, b] is (sqrt(b^2 + d^2) - sqrt(a^2 + d^2) + sqrt((w - a)^2
//   + d^2) - sqrt((w - b)^2 + d^2)) / 2 (Hottel's crossed strings over the whole floor: sqrt(w^2 + d^2) - d).
// The grooves run the full 1.2 m; the texels checked lie 0.3 m or more from the open ends, where the ends add
// under 1e-3 of pi L.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;
using std::numbers::pi;

constexpr double kSize = 1.2;         // the plane is [0, 1.2]^2 m
constexpr int kResolution = 12;       // 10 cm texels
constexpr double kTexel = kSize / kResolution;
constexpr double kGrooveWidth = 0.03;
constexpr double kGrooveDepth = 0.05;
// One groove under texel 5's centre (x in [0.535, 0.565]), one across the edge between texels 2 and 3.
constexpr double kGrooveStarts[2] = {0.285, 0.535};
constexpr float kSkyRadiance = 1.0f;
constexpr float kMaxInvalidFraction = 0.1f;  // the bake's back-face threshold

void addQuadWithPlanarUv(TriangleMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    gusuku::testing::addQuad(mesh, a, b, c, d);
    for (const glm::vec3& p : {a, b, c, d}) mesh.uv1.push_back(glm::vec2(p.x, p.y) / float(kSize));
}

TriangleMesh groovedPlane() {
    TriangleMesh mesh = gusuku::testing::emptyMesh(glm::vec3(0.0f));
    mesh.has_uv1 = true;
    const float length = float(kSize), depth = float(kGrooveDepth);
    float x = 0.0f;
    for (const double start : kGrooveStarts) {
        const float g0 = float(start), g1 = float(start + kGrooveWidth);
        addQuadWithPlanarUv(mesh, {x, 0, 0}, {g0, 0, 0}, {g0, length, 0}, {x, length, 0});                    // top
        addQuadWithPlanarUv(mesh, {g0, 0, -depth}, {g1, 0, -depth}, {g1, length, -depth}, {g0, length, -depth});  // floor
        addQuadWithPlanarUv(mesh, {g0, 0, -depth}, {g0, length, -depth}, {g0, length, 0}, {g0, 0, 0});      // wall, +x
        addQuadWithPlanarUv(mesh, {g1, 0, -depth}, {g1, 0, 0}, {g1, length, 0}, {g1, length, -depth});      // wall, -x
        x = g1;
    }
    addQuadWithPlanarUv(mesh, {x, 0, 0}, {length, 0, 0}, {length, length, 0}, {x, length, 0});
    return mesh;
}

// Integral over s in [a, b] (0 <= a <= b <= w) of the floor's view factor to the slot's opening.
double floorViewFactorIntegral(double a, double b) {
    const double w = kGrooveWidth, d = kGrooveDepth;
    auto root = [d](double s) { return std::sqrt(s * s + d * d); };
    return 0.5 * (root(b) - root(a) + root(w - a) - root(w - b));
}

// Exact mean of E / (pi L) over the texel column x in [x0, x0 + texel]: the grooves' floors by their view
// factor, the top surface 1.
double exactFootprintMean(int column) {
    const double x0 = column * kTexel, x1 = x0 + kTexel;
    double integral = kTexel;
    for (const double start : kGrooveStarts) {
        const double a = std::clamp(x0, start, start + kGrooveWidth), b = std::clamp(x1, start, start + kGrooveWidth);
        integral += floorViewFactorIntegral(a - start, b - start) - (b - a);
    }
    return integral / kTexel;
}

struct BakedTexels {
    std::vector<LightmapTexel> texels;
    std::vector<double> relative;  // E / (pi L) per texel
};

// The bake's two steps for the building: footprint slots traced with samples_per_texel / K samples each, then
// folded into texels.
BakedTexels bakeGroovedPlane(VulkanContext& context, int grid_side, uint32_t samples_per_texel, uint32_t seed) {
    const TriangleMesh mesh = groovedPlane();
    BakedTexels baked;
    baked.texels = rasterizeLightmapTexels(mesh, kResolution);
    const LightmapFootprint footprint = lightmapTexelFootprints(mesh, kResolution, baked.texels, grid_side, seed);
    std::vector<QueryPointGpu> points;
    for (const LightmapFootprintPoint& point : footprint.points) {
        QueryPointGpu query{};
        query.position = glm::vec4(point.position, 1.0f);
        query.normal = glm::vec4(point.shading_normal, 0.0f);
        points.push_back(query);
    }
    const TraceScene scene = makeTraceScene(mesh, nullptr);
    IrradianceTracer tracer(context, scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(32, 16, glm::vec3(kSkyRadiance)), 0.0));
    const uint32_t samples_per_slot = samples_per_texel / uint32_t(footprint.pointsPerTexel());
    PointAccumulator accumulator = tracer.createAccumulator(points);
    TracePass pass;
    pass.seed = seed;
    tracer.addSamples(accumulator, samples_per_slot, pass);
    const std::vector<glm::vec4> sums =
        texelSumsFromFootprint(footprint, tracer.readSums(accumulator), samples_per_slot, kMaxInvalidFraction);
    for (const glm::vec4& sum : sums) {
        EXPECT_LE(sum.w / float(samples_per_texel), kMaxInvalidFraction) << "no texel here is inside geometry";
        baked.relative.push_back(double(sum.g) / double(samples_per_texel) / (pi * kSkyRadiance));
    }
    return baked;
}

// A texel's error, in units of pi L, for 16 sub-points and `samples_per_texel` rays:
// - where it falls: the 16 sub-points have 16 distinct x on a regular grid of 1/16 texel with a random shift,
//   so the count inside a groove's floor (an interval) is floor(16 l) or ceil(16 l) for a floor width of l
//   texels, mean exact: an error below 1/16 of the jump from the top (1) to the floor's edge (F(0)), plus 1/16 of
//   the floor's own variation (F(w/2) - F(0)); its sigma, sqrt(p (1 - p)) / 16 with p = frac(16 l), is at most
//   half of that;
// - the rays: each sub-point on a floor is a Bernoulli trial of variance <= 1/4 per ray; at most 6 of 16 lie on
//   floors (3 cm of 10 cm, plus one): sigma <= sqrt(6 / 4 / (samples / 16)) / 16.
struct FootprintError {
    double placement_max = 0.0;
    double placement_sigma = 0.0;
    double rays_sigma = 0.0;
    double texelBound() const { return placement_max + 4.0 * rays_sigma; }
    double sigma() const { return std::sqrt(placement_sigma * placement_sigma + rays_sigma * rays_sigma); }
};

FootprintError footprintError(uint32_t samples_per_texel) {
    const double w = kGrooveWidth, d = kGrooveDepth;
    const double edge_view_factor = 0.5 * w / std::sqrt(w * w + d * d);
    const double middle_view_factor = (w / 2) / std::sqrt(w * w / 4 + d * d);
    FootprintError error;
    error.placement_max = ((1.0 - edge_view_factor) + (middle_view_factor - edge_view_factor)) / 16.0;
    error.placement_sigma = error.placement_max / 2.0;
    error.rays_sigma = std::sqrt(6.0 / 4.0 / (double(samples_per_texel) / 16.0)) / 16.0;
    return error;
}

class BakeTexelFootprintTest : public GpuTest {};

TEST_F(BakeTexelFootprintTest, GroovedPlaneTexelsMatchTheAreaMeanOfTheExactIrradiance) {
    constexpr uint32_t kSamplesPerTexel = 1024;
    constexpr uint32_t kSeed = 7;
    ASSERT_EQ(footprintGridSide(kSamplesPerTexel), 4);  // 64 samples per slot
    const BakedTexels footprint = bakeGroovedPlane(context(), 4, kSamplesPerTexel, kSeed);
    const BakedTexels centre = bakeGroovedPlane(context(), 1, kSamplesPerTexel, kSeed);
    ASSERT_EQ(footprint.texels.size(), size_t(kResolution * kResolution));
    ASSERT_EQ(centre.texels.size(), footprint.texels.size());

    const FootprintError error = footprintError(kSamplesPerTexel);
    const double bound = error.texelBound();
    // Texel rows 3..8 (y in [0.3, 0.9] m): away from the grooves' open ends.
    double worst_footprint = 0.0, worst_centre = 0.0;
    for (int column = 0; column < kResolution; ++column) {
        const double exact = exactFootprintMean(column);
        double footprint_mean = 0.0, centre_mean = 0.0;
        int rows = 0;
        for (size_t i = 0; i < footprint.texels.size(); ++i) {
            const LightmapTexel& texel = footprint.texels[i];
            if (texel.x != column || texel.y < 3 || texel.y > 8) continue;
            EXPECT_NEAR(footprint.relative[i], exact, bound) << "texel " << texel.x << ", " << texel.y;
            worst_footprint = std::max(worst_footprint, std::abs(footprint.relative[i] - exact) / exact);
            worst_centre = std::max(worst_centre, std::abs(centre.relative[i] - exact) / exact);
            footprint_mean += footprint.relative[i];
            centre_mean += centre.relative[i];
            ++rows;
        }
        ASSERT_EQ(rows, 6);
        footprint_mean /= rows;
        centre_mean /= rows;
        // Over six rows the sub-points' shifts and rays are independent: 4 sigma of the mean of six.
        const double column_tolerance = 4.0 * error.sigma() / std::sqrt(6.0);
        EXPECT_NEAR(footprint_mean, exact, column_tolerance) << "column " << column;
        std::printf("column %2d: exact %.4f  footprint %.4f (%+.1f %%)  centre only %.4f (%+.1f %%)\n", column, exact,
                    footprint_mean, 100.0 * (footprint_mean / exact - 1.0), centre_mean,
                    100.0 * (centre_mean / exact - 1.0));
        if (exact < 0.99) {
            // The old scheme: the centre alone is as far off as the groove makes it, far outside the bound.
            EXPECT_GT(std::abs(centre_mean - exact), 2.0 * column_tolerance) << "column " << column;
        }
    }
    std::printf("worst texel error, relative: footprint %.1f %% (bound %.1f %% of pi L), centre only %.1f %%\n",
                100.0 * worst_footprint, 100.0 * bound, 100.0 * worst_centre);
    EXPECT_GT(worst_centre, 0.5) << "the texel whose centre falls in the groove stores the groove's darkness";
}

TEST_F(BakeTexelFootprintTest, SameSeedSameBytes) {
    const BakedTexels first = bakeGroovedPlane(context(), 4, 64, 3);
    const BakedTexels second = bakeGroovedPlane(context(), 4, 64, 3);
    EXPECT_EQ(first.relative, second.relative);
}

// CPU-only contracts of the footprint and the fold.
TEST(LightmapFootprint, GridSideFollowsTheSampleBudget) {
    // At least 20 samples per slot (2 / the back-face threshold), all slots the same share.
    EXPECT_EQ(footprintGridSide(1), 1);
    EXPECT_EQ(footprintGridSide(16), 1);
    EXPECT_EQ(footprintGridSide(64), 1);
    EXPECT_EQ(footprintGridSide(80), 2);
    EXPECT_EQ(footprintGridSide(128), 2);
    EXPECT_EQ(footprintGridSide(320), 4);
    EXPECT_EQ(footprintGridSide(512), 4);
    EXPECT_EQ(footprintGridSide(64, 0, SIZE_MAX, 1), 4);
    EXPECT_EQ(footprintGridSide(512, 1000, 16000), 4);
    EXPECT_EQ(footprintGridSide(512, 1000, 15999), 2) << "16 slots per texel would pass the point limit";
    EXPECT_EQ(footprintGridSide(512, 1000, 3999), 1);
}

TEST(LightmapFootprint, SubPointsLieInTheirTexelOnCoveredTrianglesWithWeightsSummingToOne) {
    const TriangleMesh mesh = groovedPlane();
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, kResolution);
    const LightmapFootprint centre = lightmapTexelFootprints(mesh, kResolution, texels, 1, 1);
    ASSERT_EQ(centre.points.size(), texels.size());
    for (size_t i = 0; i < texels.size(); ++i) {
        EXPECT_EQ(centre.points[i].position, texels[i].position);
        EXPECT_EQ(centre.points[i].weight, 1.0f);
    }
    const LightmapFootprint footprint = lightmapTexelFootprints(mesh, kResolution, texels, 4, 1);
    ASSERT_EQ(footprint.points.size(), texels.size() * 16);
    std::vector<double> distinct_x;
    for (size_t i = 0; i < texels.size(); ++i) {
        double weight_sum = 0.0;
        for (size_t slot = i * 16; slot < i * 16 + 16; ++slot) {
            const LightmapFootprintPoint& point = footprint.points[slot];
            weight_sum += point.weight;
            // Every texel is fully covered here (top or floor), so every slot is its own sub-point.
            EXPECT_FLOAT_EQ(point.weight, 1.0f / 16.0f);
            // Within the texel, give or take the 2 mm a traced point keeps from its triangle's edges
            // (lightmap_raster.cpp's kTracedPointInsetM: a sub-point beside a groove's edge moves off it).
            constexpr double kInsetM = 2e-3 + 1e-6;
            EXPECT_GE(point.position.x, texels[i].x * kTexel - kInsetM);
            EXPECT_LE(point.position.x, (texels[i].x + 1) * kTexel + kInsetM);
            EXPECT_GE(point.position.y, texels[i].y * kTexel - kInsetM);
            EXPECT_LE(point.position.y, (texels[i].y + 1) * kTexel + kInsetM);
            const bool on_floor = point.position.z < -0.5 * kGrooveDepth;
            EXPECT_NEAR(point.position.z, on_floor ? -kGrooveDepth : 0.0, 1e-6);
            EXPECT_EQ(point.shading_normal, glm::vec3(0.0f, 0.0f, 1.0f));
            if (i == 0) distinct_x.push_back(point.position.x);
        }
        EXPECT_NEAR(weight_sum, 1.0, 1e-6);
    }
    std::sort(distinct_x.begin(), distinct_x.end());
    for (size_t k = 1; k < distinct_x.size(); ++k)
        EXPECT_NEAR(distinct_x[k] - distinct_x[k - 1], kTexel / 16.0, 1e-6) << "n-rooks: 16 distinct x";
}

TEST(LightmapFootprint, PartlyCoveredTexelRepeatsItsCoveredSubPointsWithEqualShares) {
    // One triangle covering the lower-left half of a 1 x 1 lightmap's only texel (its centre on the diagonal
    // goes to it by the tie rule or not; the footprint only needs its sub-points).
    TriangleMesh mesh = gusuku::testing::emptyMesh(glm::vec3(0.5f));
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals.assign(3, glm::vec3(0, 0, 1));
    mesh.uv0.assign(3, glm::vec2(0.0f));
    mesh.uv1 = {{0, 0}, {1, 0}, {0, 1}};
    mesh.has_uv1 = true;
    mesh.indices = {0, 1, 2};
    mesh.triangle_material = {0};
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, 1);
    ASSERT_EQ(texels.size(), 1u);
    const LightmapFootprint footprint = lightmapTexelFootprints(mesh, 1, texels, 4, 5);
    double weight_sum = 0.0;
    for (const LightmapFootprintPoint& point : footprint.points) {
        weight_sum += point.weight;
        EXPECT_LE(point.position.x + point.position.y, 1.0f + 1e-6f) << "on the triangle";
    }
    EXPECT_NEAR(weight_sum, 1.0, 1e-6);
    // Weighted mean of a linear function over the covered sub-points = its mean over those sub-points.
    std::vector<glm::vec3> distinct;
    for (const LightmapFootprintPoint& point : footprint.points)
        if (std::find(distinct.begin(), distinct.end(), point.position) == distinct.end()) distinct.push_back(point.position);
    double weighted_x = 0.0, plain_x = 0.0;
    for (const LightmapFootprintPoint& point : footprint.points) weighted_x += point.weight * point.position.x;
    for (const glm::vec3& position : distinct) plain_x += position.x / double(distinct.size());
    EXPECT_NEAR(weighted_x, plain_x, 1e-5);
    EXPECT_GE(distinct.size(), 5u);
    EXPECT_LE(distinct.size(), 11u);
}

TEST(LightmapFootprint, FoldKeepsValidSlotsAndCallsATexelInvalidOnlyWhenMostOfItIs) {
    LightmapFootprint footprint;
    footprint.grid_side = 2;
    LightmapFootprintPoint quarter;
    quarter.weight = 0.25f;
    footprint.points.assign(8, quarter);
    // 20 samples per slot (enough to judge each: 20 * 0.1 >= 2). Texel 0: one slot of four inside a wall (all
    // back faces, dark); texel 1: three.
    const std::vector<glm::vec4> sums = {
        {40, 40, 40, 0}, {60, 60, 60, 0}, {80, 80, 80, 2}, {0, 0, 0, 20},
        {100, 100, 100, 0}, {0, 0, 0, 20}, {0, 0, 0, 18}, {4, 4, 4, 16},
    };
    const std::vector<glm::vec4> texels = texelSumsFromFootprint(footprint, sums, 20, 0.1f);
    ASSERT_EQ(texels.size(), 2u);
    // Texel 0: the mean of its three valid slots (2, 3, 4) over 80 samples; back-face share (0 + 0 + 0.1) / 3.
    EXPECT_NEAR(texels[0].r / 80.0f, 3.0f, 1e-5f);
    EXPECT_NEAR(texels[0].w / 80.0f, 0.1f / 3.0f, 1e-6f);
    // Texel 1: invalid (three quarters inside), and stays above the threshold.
    EXPECT_GT(texels[1].w / 80.0f, 0.1f);
    EXPECT_NEAR(texels[1].r / 80.0f, 0.2f / 3.0f, 1e-5f);
    EXPECT_THROW(texelSumsFromFootprint(footprint, std::vector<glm::vec4>(7), 20, 0.1f), InputError);
}

}  // namespace
}  // namespace gusuku::bake

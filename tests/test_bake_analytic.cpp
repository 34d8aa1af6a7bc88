// The tracer against answers known in closed form (issue 3, "Correctness"):
// - a horizontal plane under a uniform sky of radiance L: E = pi L;
// - a point at the foot of a tall black wall: half the hemisphere is wall, E = pi L / 2;
// - a closed furnace of albedo rho and emission Le: E = pi Le (1 + rho + ... + rho^N) for N bounces;
// - the sun term alone on a plane tilted by theta from the sun: E = I_sun cos(theta), 0 in shadow.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;
using std::numbers::pi;

// Both ways of gathering the sky must meet the same closed-form answers.
constexpr SkySampling kBothSkySamplings[] = {SkySampling::CosineOnly, SkySampling::CosineAndMap};

double meanLuminance(const std::vector<glm::vec3>& irradiance) {
    double sum = 0.0;
    for (const glm::vec3& e : irradiance) sum += luminanceRec709(glm::dvec3(e));
    return sum / double(irradiance.size());
}

std::vector<QueryPointGpu> pointsOnLine(int count, glm::vec3 start, glm::vec3 step, glm::vec3 normal) {
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < count; ++i)
        points.push_back({glm::vec4(start + step * float(i), 1.0f), glm::vec4(normal, 0.0f)});
    return points;
}

// Three bounces, the sky gathered the given way.
TracePass skyPass(SkySampling sky_sampling) {
    TracePass pass;
    pass.max_bounces = 3;
    pass.sky_sampling = sky_sampling;
    return pass;
}

// A sun of 5 and the sky sampled both ways (MIS): the path that draws the most random numbers, for the
// determinism tests.
TracePass sunlitPassWithEveryRandomDraw(const glm::dvec3& towards_sun) {
    TracePass pass;
    pass.sun.present = true;
    pass.sun.direction_enu = glm::normalize(towards_sun);
    pass.sun.irradiance_rgb = glm::dvec3(5.0);
    pass.sky_sampling = SkySampling::CosineAndMap;
    return pass;
}

class BakeAnalyticTest : public GpuTest {};

TEST_F(BakeAnalyticTest, PlaneUnderUniformSkyReceivesPiL) {
    const float radiance = 0.8f;
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.5f)), nullptr);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, glm::vec3(radiance)), 0.0));
    const auto points = pointsOnLine(64, {-5.0f, -3.0f, 0.0f}, {0.17f, 0.11f, 0.0f}, {0.0f, 0.0f, 1.0f});
    for (const SkySampling sky_sampling : kBothSkySamplings) {
        SCOPED_TRACE(skySamplingName(sky_sampling));
        const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(points, 128, skyPass(sky_sampling));
        EXPECT_NEAR(meanLuminance(irradiance), pi * radiance, 0.01 * pi * radiance);
        for (const glm::vec3& e : irradiance)
            EXPECT_NEAR(e.g, pi * radiance, 0.15 * pi * radiance) << "one point, 128 samples: within 4 sigma";
    }
}

TEST_F(BakeAnalyticTest, FootOfTallBlackWallReceivesHalfPiL) {
    const float radiance = 1.0f;
    TriangleMesh wall = gusuku::testing::emptyMesh(glm::vec3(0.0f));
    // A wall in the plane y = 0, facing south (-y), 2 km wide and 1 km tall: from a point 5 cm in front of its
    // foot it fills the northern half of the sky to within 0.01 %.
    gusuku::testing::addQuad(wall, {-1000.0f, 0.0f, -1.0f}, {1000.0f, 0.0f, -1.0f}, {1000.0f, 0.0f, 1000.0f},
                             {-1000.0f, 0.0f, 1000.0f});
    const TriangleMesh ground = gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.0f));
    const TraceScene scene = makeTraceScene(wall, &ground);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, glm::vec3(radiance)), 0.0));
    const auto points = pointsOnLine(64, {-3.0f, -0.05f, 0.0f}, {0.1f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    for (const SkySampling sky_sampling : kBothSkySamplings) {
        SCOPED_TRACE(skySamplingName(sky_sampling));
        const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(points, 128, skyPass(sky_sampling));
        EXPECT_NEAR(meanLuminance(irradiance), pi * radiance / 2.0, 0.01 * pi * radiance / 2.0);
    }
}

struct FurnaceCase {
    float albedo;
    uint32_t bounces;
};

class FurnaceTest : public GpuTest, public ::testing::WithParamInterface<FurnaceCase> {};

TEST_P(FurnaceTest, ClosedFurnaceMatchesGeometricSeries) {
    const FurnaceCase furnace = GetParam();
    const float emitted_radiance = 1.0f;
    const TraceScene scene = makeTraceScene(
        gusuku::testing::closedBox({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}, true, glm::vec3(furnace.albedo),
                                   glm::vec3(emitted_radiance)),
        nullptr);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(0.0f)), 0.0));
    TracePass pass;
    pass.max_bounces = furnace.bounces;
    std::vector<QueryPointGpu> points;
    const glm::vec3 normals[3] = {{0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, -0.6f, 0.8f}};
    for (int i = 0; i < 48; ++i)
        points.push_back({glm::vec4(-0.5f + 0.02f * float(i), 0.1f, -0.2f, 1.0f), glm::vec4(normals[i % 3], 0.0f)});
    const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(points, 256, pass);
    double series = 0.0;
    for (uint32_t k = 0; k <= furnace.bounces; ++k) series += std::pow(double(furnace.albedo), double(k));
    const double expected = pi * emitted_radiance * series;
    EXPECT_NEAR(meanLuminance(irradiance), expected, 0.01 * expected)
        << "albedo " << furnace.albedo << ", " << furnace.bounces << " bounces";
}

INSTANTIATE_TEST_SUITE_P(AlbedoAndBounces, FurnaceTest,
                         ::testing::Values(FurnaceCase{0.5f, 0}, FurnaceCase{0.5f, 2}, FurnaceCase{0.5f, 40},
                                           FurnaceCase{0.8f, 60}));

TEST_F(BakeAnalyticTest, SunTermAloneIsIrradianceTimesCosine) {
    // A small blocker high up shades one probe; the others see the sun unobstructed.
    TriangleMesh blocker = gusuku::testing::emptyMesh(glm::vec3(0.5f));
    const glm::vec3 sun_direction = glm::normalize(glm::vec3(0.3f, -0.4f, 0.866f));
    const glm::vec3 shaded_point(50.0f, 50.0f, 0.0f);
    const glm::vec3 blocker_centre = shaded_point + sun_direction * 5.0f;
    gusuku::testing::addQuad(blocker, blocker_centre + glm::vec3(-1.0f, -1.0f, 0.0f),
                             blocker_centre + glm::vec3(1.0f, -1.0f, 0.0f), blocker_centre + glm::vec3(1.0f, 1.0f, 0.0f),
                             blocker_centre + glm::vec3(-1.0f, 1.0f, 0.0f));
    const TraceScene scene = makeTraceScene(blocker, nullptr);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
    TracePass pass;
    pass.mode = TraceMode::SunDirect;
    pass.sun.present = true;
    pass.sun.direction_enu = glm::dvec3(sun_direction);
    pass.sun.irradiance_rgb = glm::dvec3(1000.0, 900.0, 800.0);

    // Normals tilted away from the sun by known angles, about an axis perpendicular to it.
    const glm::vec3 axis = glm::normalize(glm::cross(sun_direction, glm::vec3(0.0f, 0.0f, 1.0f)));
    const float angles_deg[] = {0.0f, 30.0f, 60.0f, 85.0f, 100.0f};
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 5; ++i) {
        const float angle = angles_deg[i] * std::numbers::pi_v<float> / 180.0f;
        const glm::vec3 normal = std::cos(angle) * sun_direction + std::sin(angle) * glm::cross(axis, sun_direction);
        points.push_back({glm::vec4(-20.0f + 2.0f * float(i), 0.0f, 0.0f, 1.0f), glm::vec4(normal, 0.0f)});
    }
    points.push_back({glm::vec4(shaded_point, 1.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});
    const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(points, 64, pass);
    for (int i = 0; i < 5; ++i) {
        const double expected = 1000.0 * std::max(0.0, std::cos(double(angles_deg[i]) * pi / 180.0));
        EXPECT_NEAR(irradiance[size_t(i)].r, expected, 0.002 * 1000.0) << angles_deg[i] << " degrees";
    }
    EXPECT_NEAR(irradiance[1].b / irradiance[1].r, 0.8, 1e-4);
    EXPECT_EQ(irradiance[5].r, 0.0f) << "a point in the blocker's shadow gets no sun";
}

TEST_F(BakeAnalyticTest, SameSeedGivesSameResultAndChunkingDoesNotMatter) {
    const TriangleMesh box = gusuku::testing::closedBox({-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 2.0f}, false, glm::vec3(0.6f));
    const TriangleMesh ground = gusuku::testing::horizontalPlane(50.0f, 0.0f, glm::vec3(0.3f));
    const TraceScene scene = makeTraceScene(box, &ground);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(32, 16, glm::vec3(1.0f)), 0.0));
    const TracePass pass = sunlitPassWithEveryRandomDraw(glm::dvec3(0.5, 0.2, 0.8));
    const auto points = pointsOnLine(40, {-3.0f, -1.5f, 0.0f}, {0.15f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});

    PointAccumulator in_one = tracer.createAccumulator(points);
    tracer.addSamples(in_one, 12, pass);
    PointAccumulator in_chunks = tracer.createAccumulator(points);
    tracer.addSamples(in_chunks, 5, pass);
    tracer.addSamples(in_chunks, 1, pass);
    tracer.addSamples(in_chunks, 6, pass);
    const auto one = tracer.readSums(in_one);
    const auto chunks = tracer.readSums(in_chunks);
    for (size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 4; ++c) EXPECT_EQ(one[i][c], chunks[i][c]) << "point " << i << " channel " << c;

    TracePass other_seed = pass;
    other_seed.seed = 7;
    PointAccumulator reseeded = tracer.createAccumulator(points);
    tracer.addSamples(reseeded, 12, other_seed);
    const auto different = tracer.readSums(reseeded);
    int differing = 0;
    for (size_t i = 0; i < points.size(); ++i) differing += different[i].x != one[i].x ? 1 : 0;
    EXPECT_GT(differing, 30) << "another seed draws other random numbers";
}

TEST_F(BakeAnalyticTest, LongDispatchLosesNoSamples) {
    // Regression: with one invocation looping over all of a dispatch's samples, llvmpipe's shader loop limiter
    // silently cut long invocations short (fewer rays, biased sums). 1024 samples in one call must equal 16
    // calls of 64, ray for ray and bit for bit.
    TriangleMesh terrain = gusuku::testing::emptyMesh(glm::vec3(0.4f));
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 60; ++x) {
            const float x0 = float(x) - 30.0f, y0 = float(y) - 30.0f;
            const float h = 0.2f * std::sin(x0 * 0.7f) * std::cos(y0 * 0.5f);
            gusuku::testing::addQuad(terrain, {x0, y0, h}, {x0 + 1.0f, y0, h}, {x0 + 1.0f, y0 + 1.0f, h}, {x0, y0 + 1.0f, h});
        }
    const TriangleMesh box = gusuku::testing::closedBox({-2.0f, -2.0f, 0.0f}, {2.0f, 2.0f, 3.0f}, false, glm::vec3(0.7f));
    const TraceScene scene = makeTraceScene(box, &terrain);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(32, 16, glm::vec3(1.0f)), 0.0));
    const TracePass pass = sunlitPassWithEveryRandomDraw(glm::dvec3(0.3, 0.2, 0.9));
    const auto points = pointsOnLine(256, {-6.0f, -2.5f, 0.3f}, {0.05f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    PointAccumulator one_call = tracer.createAccumulator(points);
    const uint64_t rays_one_call = tracer.addSamples(one_call, 1024, pass);
    PointAccumulator many_calls = tracer.createAccumulator(points);
    uint64_t rays_many_calls = 0;
    for (int i = 0; i < 16; ++i) rays_many_calls += tracer.addSamples(many_calls, 64, pass);
    EXPECT_EQ(rays_one_call, rays_many_calls);
    const auto a = tracer.readSums(one_call), b = tracer.readSums(many_calls);
    for (size_t i = 0; i < points.size(); ++i) EXPECT_EQ(a[i].x, b[i].x) << "point " << i;
}

}  // namespace
}  // namespace gusuku::bake

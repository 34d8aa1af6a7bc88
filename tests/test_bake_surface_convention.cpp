// The convention at a surface (issue 11, item 5): light is gathered with the cosine lobe about the shading
// normal, and directions below the geometric face plane contribute nothing, at the lightmap texel and at every
// path vertex alike (as Cycles and Mitsuba end such rays). Checked against the closed form for a plane whose
// shading normal leans theta from its face under a uniform sky of radiance L:
//     E = L * integral over the upper half-space of max(0, n_s . w) dw = pi L (1 + cos theta) / 2
// (the cosine lobe about n_s loses the wedge below the face plane, (1 - cos theta) / 2 of its weight).
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;
using std::numbers::pi;

constexpr SkySampling kBothSkySamplings[] = {SkySampling::CosineOnly, SkySampling::CosineAndMap};
constexpr double kLeanDeg = 30.0;
constexpr float kRadiance = 0.8f;

// The share of the shading normal's cosine lobe above the face plane: (1 + cos theta) / 2.
double liftedLobeShare() { return (1.0 + std::cos(kLeanDeg * pi / 180.0)) / 2.0; }

glm::vec3 leaningNormal() {
    const float lean = float(kLeanDeg * pi / 180.0);
    return {std::sin(lean), 0.0f, std::cos(lean)};
}

// A 2 km horizontal plane facing up whose vertex normals all lean 30 degrees east: what a smoothing exporter
// gives a wall next to a sharp corner, in its simplest form.
TraceScene leaningNormalPlane(float albedo) {
    TriangleMesh plane = gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(albedo));
    for (glm::vec3& normal : plane.normals) normal = leaningNormal();
    return makeTraceScene(plane, nullptr);
}

// Mean over points of their per-point means, and its standard error. The points' random streams are
// independent (seeded per point), so the per-point means are independent draws and the standard error of
// their mean is their sample standard deviation / sqrt(points); a tolerance of 4.5 of them is passed by
// chance about once in 150 000 runs.
struct MeanAndError {
    double mean = 0.0;
    double standard_error = 0.0;
};
MeanAndError meanOverPoints(const std::vector<glm::vec3>& irradiance) {
    double sum = 0.0, sum_squares = 0.0;
    for (const glm::vec3& e : irradiance) {
        sum += e.g;
        sum_squares += double(e.g) * double(e.g);
    }
    const double n = double(irradiance.size());
    const double mean = sum / n;
    const double variance = std::max(0.0, (sum_squares - n * mean * mean) / (n - 1.0));
    return {mean, std::sqrt(variance / n)};
}

class SurfaceConventionTest : public GpuTest {};

TEST_F(SurfaceConventionTest, TexelWithLeaningNormalGathersOnlyAboveItsFace) {
    // Albedo 0.8: under the old convention (lobe not clipped) the rays below the face hit the plane itself and
    // bring back 0.8 x its light, 5-6 % too much here; clipped, every ray above the face escapes to the sky.
    const TraceScene scene = leaningNormalPlane(0.8f);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, glm::vec3(kRadiance)), 0.0));
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 1024; ++i)
        points.push_back({glm::vec4(-40.0f + 0.078f * float(i), 3.0f - 0.0059f * float(i), 0.0f, 1.0f),
                          glm::vec4(leaningNormal(), 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});
    const double expected = pi * kRadiance * liftedLobeShare();
    for (const SkySampling sky_sampling : kBothSkySamplings) {
        SCOPED_TRACE(skySamplingName(sky_sampling));
        TracePass pass;
        pass.max_bounces = 3;
        pass.sky_sampling = sky_sampling;
        // 1024 points x 256 samples. For the cosine lobe alone each sample is pi L (escaped above the face) or
        // 0, a Bernoulli draw with p = 0.933, so independent samples would give a relative standard error of
        // sqrt((1 - p) / p / 262144) = 0.052 %; the scrambled Sobol draws do better, and the measured standard
        // error below is what the tolerance uses (it must stay small enough to see a 1 % bias).
        const MeanAndError measured = meanOverPoints(tracer.traceIrradiance(points, 256, pass));
        std::printf("  [%s] lean %.0f deg: baked %.5f, analytic pi L (1 + cos) / 2 = %.5f (%+.3f %%, "
                    "standard error %.3f %%)\n",
                    skySamplingName(sky_sampling), kLeanDeg, measured.mean, expected,
                    100.0 * (measured.mean / expected - 1.0), 100.0 * measured.standard_error / expected);
        EXPECT_LT(measured.standard_error, 0.001 * expected) << "the test must resolve a 1 % bias";
        EXPECT_NEAR(measured.mean, expected, 4.5 * measured.standard_error);
    }
}

TEST_F(SurfaceConventionTest, PathVertexWithLeaningNormalGathersOnlyAboveItsFace) {
    // A probe 1 m above the plane looks straight down: every first ray lands on the plane (albedo rho), whose
    // light is rho / pi times the irradiance there, so E = rho pi L (1 + cos theta) / 2 with the convention
    // holding at the path's vertex. Many bounces allowed: under the old convention the vertex's rays below the
    // face would hit the plane again and again (E = rho pi L p / (1 - rho (1 - p)), 3.5 % more at rho = 0.5).
    const float albedo = 0.5f;
    const TraceScene scene = leaningNormalPlane(albedo);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, glm::vec3(kRadiance)), 0.0));
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 1024; ++i)
        points.push_back({glm::vec4(-40.0f + 0.078f * float(i), 3.0f - 0.0059f * float(i), 1.0f, 1.0f),
                          glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)});
    const double expected = double(albedo) * pi * kRadiance * liftedLobeShare();
    for (const SkySampling sky_sampling : kBothSkySamplings) {
        SCOPED_TRACE(skySamplingName(sky_sampling));
        TracePass pass;
        pass.max_bounces = 12;
        pass.sky_sampling = sky_sampling;
        const MeanAndError measured = meanOverPoints(tracer.traceIrradiance(points, 256, pass));
        std::printf("  [%s] path vertex: baked %.5f, analytic rho pi L (1 + cos) / 2 = %.5f (%+.3f %%, "
                    "standard error %.3f %%)\n",
                    skySamplingName(sky_sampling), measured.mean, expected,
                    100.0 * (measured.mean / expected - 1.0), 100.0 * measured.standard_error / expected);
        EXPECT_LT(measured.standard_error, 0.001 * expected);
        EXPECT_NEAR(measured.mean, expected, 4.5 * measured.standard_error);
    }
}

TEST_F(SurfaceConventionTest, SunBelowTheFacePlaneGivesNothing) {
    // The sun term follows the same convention: a sun 10 degrees below the face plane but 20 degrees above the
    // leaning shading normal's horizon gives nothing; 40 degrees above the face plane it gives I cos(angle to n_s).
    const TraceScene scene = leaningNormalPlane(0.5f);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
    const auto sunAt = [&](double elevation_deg) {
        // Towards the east (the side the normal leans to) a sun below the face plane is still above the lobe's
        // horizon; towards the west it is below it. The west side is what the lean cuts off.
        const double e = elevation_deg * pi / 180.0;
        TracePass pass;
        pass.mode = TraceMode::SunDirect;
        pass.sun.present = true;
        pass.sun.direction_enu = glm::dvec3(std::cos(e), 0.0, std::sin(e));
        pass.sun.irradiance_rgb = glm::dvec3(1000.0);
        const std::vector<QueryPointGpu> probe = {
            {glm::vec4(3.0f, 2.0f, 0.0f, 1.0f), glm::vec4(leaningNormal(), 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)}};
        return double(tracer.traceIrradiance(probe, 32, pass)[0].r);
    };
    EXPECT_EQ(sunAt(-10.0), 0.0);
    const double angle_to_normal = (90.0 - 40.0 - kLeanDeg) * pi / 180.0;
    EXPECT_NEAR(sunAt(40.0), 1000.0 * std::cos(angle_to_normal), 2.0);
}

}  // namespace
}  // namespace gusuku::bake

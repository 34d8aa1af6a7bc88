// How paths gather the sky: the cosine lobe alone for smooth skies, plus the importance-sampled map (MIS) for
// uneven ones. The measure that decides (skyCosineRelativeVariance) is pinned on skies with closed-form values,
// and both methods must give the exact irradiance of an uneven sky on an open plane.
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


void setRadiance(ImageRGBA& sky, int x, int y, float radiance) {
    float* texel = sky.texel(x, y);
    texel[0] = texel[1] = texel[2] = radiance;
}

// Radiance 1 above the horizon, 0 below.
ImageRGBA upperHemisphereSky(int width, int height) {
    ImageRGBA sky = gusuku::testing::uniformSky(width, height, glm::vec3(0.0f));
    for (int y = 0; y < height / 2; ++y)
        for (int x = 0; x < width; ++x) setRadiance(sky, x, y, 1.0f);
    return sky;
}

TEST(SkyCosineRelativeVariance, UniformSkyHasNone) {
    const ImageRGBA sky = gusuku::testing::uniformSky(64, 32, glm::vec3(2.0f));
    EXPECT_NEAR(skyCosineRelativeVariance(sky, 0.0), 0.0, 1e-3);
    EXPECT_EQ(resolveSkySampling(SkySampling::Automatic, buildSkySamplingTables(sky, 0.0)), SkySampling::CosineOnly);
}

TEST(SkyCosineRelativeVariance, UpperHemisphereSkyGivesOneOnAWall) {
    // Facing up: uniform over the hemisphere, 0. Facing a horizon: the lit quarter-sphere carries half of the
    // cosine weight, so E[(pi L)^2] / E^2 = pi (pi / 2) / (pi / 2)^2 = 2, a relative variance of 1.
    EXPECT_NEAR(skyCosineRelativeVariance(upperHemisphereSky(128, 64), 0.0), 1.0, 0.01);
}

TEST(SkyCosineRelativeVariance, SmallBrightPatchNeedsTheMap) {
    ImageRGBA sky = gusuku::testing::uniformSky(64, 32, glm::vec3(1.0f));
    for (int y = 8; y < 10; ++y)
        for (int x = 20; x < 22; ++x) setRadiance(sky, x, y, 1000.0f);
    const SkySamplingTables tables = buildSkySamplingTables(sky, 0.0);
    EXPECT_GT(tables.cosine_relative_variance, 100.0);
    EXPECT_EQ(resolveSkySampling(SkySampling::Automatic, tables), SkySampling::CosineAndMap);
    EXPECT_EQ(resolveSkySampling(SkySampling::CosineOnly, tables), SkySampling::CosineOnly) << "forced stays forced";
}

TEST(SkyCosineRelativeVariance, BlackOrEmptySkyIsZeroNotNaN) {
    EXPECT_EQ(skyCosineRelativeVariance(gusuku::testing::uniformSky(16, 8, glm::vec3(0.0f)), 0.0), 0.0);
    EXPECT_EQ(skyCosineRelativeVariance(ImageRGBA{}, 0.0), 0.0);
}

class SkySamplingGpuTest : public gusuku::testing::GpuTest {};

TEST_F(SkySamplingGpuTest, OpenPlaneUnderUnevenSkyGetsTheExactIrradianceEitherWay) {
    // A sky brighter towards the zenith with a bright region: the shader reads the nearest texel, so the
    // irradiance on an upward plane is exactly sum over texels of L * (delta phi) * (sin^2 theta1 - sin^2
    // theta0) / 2, the texel's integral of cos(theta) d(omega).
    const int width = 64, height = 32;
    ImageRGBA sky = gusuku::testing::uniformSky(width, height, glm::vec3(0.0f));
    double expected = 0.0;
    for (int y = 0; y < height / 2; ++y) {
        const double theta0 = std::numbers::pi * y / height, theta1 = std::numbers::pi * (y + 1) / height;
        const double cosine_weight =
            (2.0 * std::numbers::pi / width) * (std::pow(std::sin(theta1), 2) - std::pow(std::sin(theta0), 2)) / 2.0;
        for (int x = 0; x < width; ++x) {
            float radiance = 0.5f + 1.5f * float(std::cos(0.5 * (theta0 + theta1)));
            if (x >= 10 && x < 18 && y >= 6 && y < 10) radiance *= 6.0f;
            setRadiance(sky, x, y, radiance);
            expected += radiance * cosine_weight;
        }
    }
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.5f)), nullptr);
    const SkySamplingTables tables = buildSkySamplingTables(sky, 0.0);
    IrradianceTracer tracer(context(), scene, tables);
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 64; ++i)
        points.push_back({glm::vec4(-4.0f + 0.13f * float(i), 2.0f - 0.07f * float(i), 0.0f, 1.0f),
                          glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});
    for (const SkySampling sky_sampling : {SkySampling::CosineOnly, SkySampling::CosineAndMap}) {
        SCOPED_TRACE(skySamplingName(sky_sampling));
        TracePass pass;
        pass.max_bounces = 2;
        pass.sky_sampling = sky_sampling;
        double mean = 0.0;
        for (const glm::vec3& irradiance : tracer.traceIrradiance(points, 1024, pass)) mean += irradiance.g;
        mean /= double(points.size());
        EXPECT_NEAR(mean, expected, 0.003 * expected) << "measured within 0.03 %";
    }
}

}  // namespace
}  // namespace gusuku::bake

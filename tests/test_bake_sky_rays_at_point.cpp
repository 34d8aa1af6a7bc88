// Several sky next-event rays at the query point (TracePass::sky_rays_at_point, irradiance_paths.glsl): the
// estimate must stay unbiased for any count (the MIS weights count the map's rays), so it is held to closed-form
// irradiances of uneven skies, open and half blocked, at 1, 2, 8 and 64 rays; and it must pay: the variance of
// one sample falls with the count. The automatic count (8 without a sun when the map is sampled, else 1) is
// pinned too.
#include <cmath>
#include <numbers>
#include <stdexcept>
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

using std::numbers::pi;

// A grey sky brighter towards the zenith with a bright band (rows 6-9, every azimuth): uneven enough that the
// map is sampled, and alike at every azimuth, so a wall through the zenith blocks exactly half of each row. The
// shader reads the nearest texel, so an upward plane's irradiance is exactly the sum over texels above the
// horizon of L * (delta phi) * (sin^2 theta1 - sin^2 theta0) / 2, each texel's integral of cos(theta) d(omega).
struct BandedSky {
    ImageRGBA image;
    double upward_irradiance = 0.0;
};

BandedSky bandedSky() {
    const int width = 64, height = 32;
    BandedSky sky{gusuku::testing::uniformSky(width, height, glm::vec3(0.0f))};
    for (int y = 0; y < height / 2; ++y) {
        const double theta0 = pi * y / height, theta1 = pi * (y + 1) / height;
        const double row_cosine_weight = pi * (std::pow(std::sin(theta1), 2) - std::pow(std::sin(theta0), 2));
        float radiance = 0.5f + 1.5f * float(std::cos(0.5 * (theta0 + theta1)));
        if (y >= 6 && y < 10) radiance *= 6.0f;
        for (int x = 0; x < width; ++x) {
            float* texel = sky.image.texel(x, y);
            texel[0] = texel[1] = texel[2] = radiance;
        }
        sky.upward_irradiance += radiance * row_cosine_weight;
    }
    return sky;
}

std::vector<QueryPointGpu> pointsAlongX(float y) {
    std::vector<QueryPointGpu> points;
    for (int i = 0; i < 64; ++i)
        points.push_back({glm::vec4(-3.0f + 0.1f * float(i), y, 0.0f, 1.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});
    return points;
}

struct Traced {
    double mean = 0.0;                  ///< of the points' mean irradiances (luminance; the sky is grey)
    double sample_variance = 0.0;       ///< of one sample, averaged over the points
    uint64_t rays = 0;
};

Traced trace(IrradianceTracer& tracer, const std::vector<QueryPointGpu>& points, uint32_t samples, TracePass pass) {
    PointAccumulator accumulator = tracer.createAccumulator(points);
    Traced traced;
    traced.rays = tracer.addSamples(accumulator, samples, pass);
    const std::vector<glm::vec4> sums = tracer.readSums(accumulator);
    const std::vector<float> squares = tracer.readLuminanceSquareSums(accumulator);
    for (size_t p = 0; p < points.size(); ++p) {
        traced.mean += luminanceRec709(glm::vec3(sums[p])) / samples / double(points.size());
        traced.sample_variance +=
            luminanceVarianceOfMean(sums[p], squares[p], samples) * samples / double(points.size());
    }
    return traced;
}

class SkyRaysAtPointTest : public gusuku::testing::GpuTest {};

TEST_F(SkyRaysAtPointTest, OpenPlaneGetsTheExactIrradianceAtEveryCountAndLessNoiseWithMore) {
    const BandedSky sky = bandedSky();
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.5f)), nullptr);
    IrradianceTracer tracer(context(), scene, buildSkySamplingTables(sky.image, 0.0));
    ASSERT_EQ(tracer.resolvedSkySampling(SkySampling::Automatic), SkySampling::CosineAndMap) << "an uneven sky";
    const std::vector<QueryPointGpu> points = pointsAlongX(0.0f);
    double one_ray_variance = 0.0;
    for (const uint32_t rays : {1u, 2u, 8u, 64u}) {
        SCOPED_TRACE(rays);
        TracePass pass;
        pass.max_bounces = 2;
        pass.sky_rays_at_point = rays;
        const Traced traced = trace(tracer, points, 512, pass);
        EXPECT_NEAR(traced.mean, sky.upward_irradiance, 0.003 * sky.upward_irradiance);
        if (rays == 1) one_ray_variance = traced.sample_variance;
        // An open plane: every ray at the point sees the sky, so more of them average more of it.
        if (rays == 8) EXPECT_LT(traced.sample_variance, 0.3 * one_ray_variance);
        if (rays == 64) EXPECT_LT(traced.sample_variance, 0.1 * one_ray_variance);
    }
}

TEST_F(SkyRaysAtPointTest, FootOfABlackWallGetsHalfTheSkyAtEveryCount) {
    const BandedSky sky = bandedSky();
    // A black wall in the plane y = 0, 2 km wide and 1 km tall, over a black ground: from 5 cm in front of its
    // foot it blocks the northern half of every row of the sky (to within 0.01 %), and nothing bounces.
    TriangleMesh wall = gusuku::testing::emptyMesh(glm::vec3(0.0f));
    gusuku::testing::addQuad(wall, {-1000.0f, 0.0f, -1.0f}, {1000.0f, 0.0f, -1.0f}, {1000.0f, 0.0f, 1000.0f},
                             {-1000.0f, 0.0f, 1000.0f});
    const TriangleMesh ground = gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.0f));
    IrradianceTracer tracer(context(), makeTraceScene(wall, &ground), buildSkySamplingTables(sky.image, 0.0));
    const std::vector<QueryPointGpu> points = pointsAlongX(-0.05f);
    for (const uint32_t rays : {1u, 8u}) {
        SCOPED_TRACE(rays);
        TracePass pass;
        pass.max_bounces = 2;
        pass.sky_rays_at_point = rays;
        const Traced traced = trace(tracer, points, 512, pass);
        EXPECT_NEAR(traced.mean, sky.upward_irradiance / 2.0, 0.005 * sky.upward_irradiance / 2.0);
    }
}

TEST_F(SkyRaysAtPointTest, EightWithoutASunWhenTheMapIsSampledElseOne) {
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(10.0f, 0.0f, glm::vec3(0.5f)), nullptr);
    IrradianceTracer uneven(context(), scene, buildSkySamplingTables(bandedSky().image, 0.0));
    TracePass pass;
    EXPECT_EQ(uneven.resolvedSkyRaysAtPoint(pass), kSkyRaysAtPointWithoutSun);
    pass.sun.present = true;
    EXPECT_EQ(uneven.resolvedSkyRaysAtPoint(pass), 1u) << "with a sun, bounced sunlight is the noise";
    pass.sun.present = false;
    pass.sky_sampling = SkySampling::CosineOnly;
    EXPECT_EQ(uneven.resolvedSkyRaysAtPoint(pass), 1u) << "no map rays to add";
    pass.sky_sampling = SkySampling::Automatic;
    pass.sky_rays_at_point = 4;
    EXPECT_EQ(uneven.resolvedSkyRaysAtPoint(pass), 4u);
    pass.sky_rays_at_point = 3;
    EXPECT_THROW(uneven.resolvedSkyRaysAtPoint(pass), std::invalid_argument) << "not a power of two";
    IrradianceTracer smooth(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, glm::vec3(1.0f)), 0.0));
    EXPECT_EQ(smooth.resolvedSkyRaysAtPoint(TracePass{}), 1u) << "a smooth sky is gathered by the cosine lobe";
}

}  // namespace
}  // namespace gusuku::bake

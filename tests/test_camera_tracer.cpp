// The camera path tracer (issue 9 item 4; the benchmark's ground truth) against answers known independently:
// - a camera looking straight down at a large plane of albedo rho under a uniform sky of radiance L sees rho L
//   in every pixel (every path's one bounce escapes to the same sky: exact up to rounding);
// - a view of the sky alone shows the map's radiance per pixel direction (gusuku/maths/equirect.h on the CPU,
//   averaged over each pixel's area);
// - the projection: small emissive markers at known ENU points light the pixels runtime.h's pinhole formula
//   predicts (within 1 px), for a camera turned off every axis with fx != fy and an off-centre principal point;
// - the building flag hides exactly the building;
// - determinism: one seed, one set of bits;
// - the denoiser: lower error than the raw frame against a converged render, sky pixels untouched;
// - the sRGB packing of the runtime's camera input, and the middle-grey exposure, by hand values.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "mini_site.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku_bake/camera_denoise.h"
#include "gusuku_bake/camera_frame.h"
#include "gusuku_bake/camera_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;

constexpr glm::dvec3 kUp{0.0, 0.0, 1.0};

// A pose at `position` looking along `forward`, image x to the right of it and image y down (runtime.h).
CameraPose lookAlong(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up = kUp) {
    const glm::dvec3 z = glm::normalize(forward);
    const glm::dvec3 x = glm::normalize(glm::cross(z, up));
    const glm::dvec3 y = glm::cross(z, x);
    CameraPose pose;
    pose.position_enu = position;
    pose.camera_to_enu = glm::dmat3(x, y, z);
    return pose;
}

CameraIntrinsics intrinsics64x48(double fx, double fy, double cx, double cy) {
    CameraIntrinsics intrinsics;
    intrinsics.fx = fx;
    intrinsics.fy = fy;
    intrinsics.cx = cx;
    intrinsics.cy = cy;
    intrinsics.width = 64;
    intrinsics.height = 48;
    return intrinsics;
}

// runtime.h's formula, written out here independently of the tracer: X = R^T (p - c), u = fx X / Z + cx.
glm::dvec2 projectPoint(const CameraIntrinsics& intrinsics, const CameraPose& pose, const glm::dvec3& point_enu) {
    const glm::dvec3 camera = glm::transpose(pose.camera_to_enu) * (point_enu - pose.position_enu);
    return {intrinsics.fx * camera.x / camera.z + intrinsics.cx, intrinsics.fy * camera.y / camera.z + intrinsics.cy};
}

glm::vec3 pixelOf(const ImageRGBA& image, int x, int y) {
    const float* texel = image.texel(x, y);
    return {texel[0], texel[1], texel[2]};
}

CameraRenderOptions samples(uint32_t samples_per_pixel) {
    CameraRenderOptions options;
    options.samples_per_pixel = samples_per_pixel;
    return options;
}

// An equirect map that changes texel by texel in all three channels, so a wrong row, column or north offset
// shows.
ImageRGBA patternedSky(int width, int height) {
    ImageRGBA sky = gusuku::testing::uniformSky(width, height, glm::vec3(0.0f));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* texel = sky.texel(x, y);
            texel[0] = 0.1f + float(x) / float(width);
            texel[1] = 0.1f + float(y) / float(height);
            texel[2] = 0.3f + 0.2f * float((x * 7 + y * 3) % 5);
        }
    return sky;
}

// The texel of `sky` that contains a direction, by gusuku/maths/equirect.h.
glm::vec3 equirectLookup(const ImageRGBA& sky, const glm::dvec3& direction, double north_deg) {
    const glm::dvec2 uv = equirectCoordinates(glm::normalize(direction), north_deg);
    const int x = std::min(int(uv.x * sky.width), sky.width - 1);
    const int y = std::min(int(uv.y * sky.height), sky.height - 1);
    return pixelOf(sky, x, y);
}

class CameraTracerTest : public GpuTest {};

TEST_F(CameraTracerTest, LookingDownAtPlaneUnderUniformSkySeesAlbedoTimesSkyRadiance) {
    const glm::vec3 albedo(0.5f, 0.3f, 0.7f);
    const glm::vec3 sky_radiance(0.8f, 0.6f, 0.4f);
    // 2 km across, seen from 10 m up with a 65 x 51 degree view: every bounce ray leaves over the plane's
    // interior and escapes, so each sample is exactly rho / pi * (pi L) = rho L, up to float rounding.
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1000.0f, 0.0f, albedo), nullptr);
    const SkySamplingTables sky = buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, sky_radiance), 0.0);
    CameraTracer tracer(context(), scene);
    const CameraPose pose = lookAlong({3.0, -2.0, 10.0}, -kUp, {0.0, 1.0, 0.0});
    CameraRenderOptions options = samples(4);
    options.include_building = true;  // makeTraceScene's first mesh is the building
    const CameraRender render = tracer.render({&sky, {}}, intrinsics64x48(50.0, 50.0, 32.0, 24.0), pose, options);
    const glm::vec3 expected = albedo * sky_radiance;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            for (int channel = 0; channel < 3; ++channel)
                ASSERT_NEAR(pixelOf(render.radiance, x, y)[channel], expected[channel], 1e-5f * expected[channel])
                    << "pixel " << x << ", " << y << " channel " << channel;
    // Per sample: the camera ray, the bounce ray; plus one guide ray per pixel.
    EXPECT_EQ(render.rays_traced, uint64_t(64 * 48) * (2 * 4 + 1));
    EXPECT_EQ(render.guides.normalDistance(10, 10).z, 1.0f);
    // Pixel (32, 24)'s centre is half a pixel off the axis in x and y.
    EXPECT_NEAR(render.guides.normalDistance(32, 24).w, 10.0 * std::sqrt(1.0 + 2.0 * 0.01 * 0.01), 1e-4)
        << "the centre ray's distance to the plane";
}

TEST_F(CameraTracerTest, SkyOnlyViewShowsTheMapRadiancePerPixelDirection) {
    const double north_deg = 30.0;
    const ImageRGBA map = patternedSky(64, 32);
    const SkySamplingTables sky = buildSkySamplingTables(map, north_deg);
    // Nothing but a small plane far below and behind the camera, which looks up to the north-east.
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1.0f, -100.0f, glm::vec3(0.5f)), nullptr);
    CameraTracer tracer(context(), scene);
    const CameraIntrinsics intrinsics = intrinsics64x48(40.0, 36.0, 30.0, 25.0);
    const CameraPose pose = lookAlong({0.0, 0.0, 1.0}, {0.6, 0.7, 0.5});
    CameraRenderOptions options = samples(64);
    options.include_building = true;  // the plane below is the building here: either way it is out of view
    const CameraRender render = tracer.render({&sky, {}}, intrinsics, pose, options);
    // Each pixel against the mean of the map over the pixel's area (16 x 16 positions). Where a texel edge
    // crosses the pixel the two estimates of the mix differ a little (64 stratified samples against a grid, and
    // float against double at the edge itself): within 15 % of the contrast the pixel's area (and a margin of
    // 5 % of a pixel around it) holds. A pixel inside one texel must match it to rounding.
    constexpr int kGrid = 16;
    const auto lookup = [&](int x, int y, double sub_x, double sub_y) {
        const glm::dvec3 camera((x + sub_x - intrinsics.cx) / intrinsics.fx, (y + sub_y - intrinsics.cy) / intrinsics.fy,
                                1.0);
        return equirectLookup(map, pose.camera_to_enu * camera, north_deg);
    };
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            glm::dvec3 sum(0.0);
            glm::vec3 low(1e30f), high(-1e30f);
            for (int j = 0; j < kGrid; ++j)
                for (int i = 0; i < kGrid; ++i) sum += glm::dvec3(lookup(x, y, (i + 0.5) / kGrid, (j + 0.5) / kGrid));
            for (int j = 0; j <= kGrid; ++j)
                for (int i = 0; i <= kGrid; ++i) {
                    const glm::vec3 radiance = lookup(x, y, -0.05 + 1.1 * i / kGrid, -0.05 + 1.1 * j / kGrid);
                    low = glm::min(low, radiance);
                    high = glm::max(high, radiance);
                }
            const glm::vec3 expected(sum / double(kGrid * kGrid));
            for (int channel = 0; channel < 3; ++channel)
                ASSERT_NEAR(pixelOf(render.radiance, x, y)[channel], expected[channel],
                            1e-5f + 0.15f * (high[channel] - low[channel]))
                    << "pixel " << x << ", " << y << " channel " << channel;
            EXPECT_EQ(render.guides.normalDistance(x, y).w, -1.0f) << "sky in the guides";
        }
}

TEST_F(CameraTracerTest, EmissiveMarkersLandWherePinholeFormulaPredicts) {
    // A camera turned about every axis (yaw, pitch and the roll that comes with them), fx != fy, principal
    // point off centre. Three markers, red, green and blue, each a square of 0.6 pixel footprints facing the
    // camera, at camera coordinates chosen to spread over the frame; black sky, no sun.
    const CameraIntrinsics intrinsics = intrinsics64x48(60.0, 55.0, 30.3, 26.7);
    const CameraPose pose = lookAlong({3.0, -2.0, 1.5}, {0.5, 0.8, -0.2}, glm::normalize(glm::dvec3(0.1, 0.0, 1.0)));
    const glm::dvec3 camera_points[3] = {{1.3, -0.9, 8.0}, {-2.0, 1.1, 6.0}, {0.2, 0.3, 12.0}};
    TriangleMesh markers;
    for (int marker = 0; marker < 3; ++marker) {
        glm::vec3 emission(0.0f);
        emission[marker] = 50.0f;
        TriangleMesh quad = gusuku::testing::emptyMesh(glm::vec3(0.0f), emission);
        const glm::dvec3 centre = pose.position_enu + pose.camera_to_enu * camera_points[marker];
        const double half = 0.3 * camera_points[marker].z / intrinsics.fx;
        const glm::dvec3 hx = pose.camera_to_enu[0] * half, hy = pose.camera_to_enu[1] * half;
        // Counter-clockwise seen from the camera: the front faces it.
        gusuku::testing::addQuad(quad, glm::vec3(centre - hx - hy), glm::vec3(centre - hx + hy),
                                 glm::vec3(centre + hx + hy), glm::vec3(centre + hx - hy));
        if (marker == 0)
            markers = quad;
        else
            appendMesh(markers, quad);
    }
    const TraceScene scene = makeTraceScene(markers, nullptr);
    const SkySamplingTables sky = buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(0.0f)), 0.0);
    CameraTracer tracer(context(), scene);
    CameraRenderOptions options = samples(16);
    options.include_building = true;
    const CameraRender render = tracer.render({&sky, {}}, intrinsics, pose, options);
    for (int marker = 0; marker < 3; ++marker) {
        const glm::dvec2 predicted =
            projectPoint(intrinsics, pose, pose.position_enu + pose.camera_to_enu * camera_points[marker]);
        int best_x = -1, best_y = -1;
        float best = 0.0f;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x)
                if (pixelOf(render.radiance, x, y)[marker] > best) {
                    best = pixelOf(render.radiance, x, y)[marker];
                    best_x = x;
                    best_y = y;
                }
        ASSERT_GT(best, 0.0f) << "marker " << marker << " is not in the frame";
        EXPECT_LE(std::fabs(best_x + 0.5 - predicted.x), 1.0) << "marker " << marker << " predicted at u " << predicted.x;
        EXPECT_LE(std::fabs(best_y + 0.5 - predicted.y), 1.0) << "marker " << marker << " predicted at v " << predicted.y;
    }
    // The first marker is up and right of the view's centre: the top-right quarter (row 0 at the top).
    const glm::dvec2 first = projectPoint(intrinsics, pose, pose.position_enu + pose.camera_to_enu * camera_points[0]);
    EXPECT_GT(first.x, intrinsics.cx);
    EXPECT_LT(first.y, intrinsics.cy);
}

TEST_F(CameraTracerTest, BuildingFlagHidesTheBuildingAlone) {
    // The building: an emissive square straight ahead; the site: a grey ground under a uniform sky.
    TriangleMesh building = gusuku::testing::emptyMesh(glm::vec3(0.0f), glm::vec3(20.0f));
    gusuku::testing::addQuad(building, {-1.0f, 5.0f, 0.0f}, {1.0f, 5.0f, 0.0f}, {1.0f, 5.0f, 2.0f},
                             {-1.0f, 5.0f, 2.0f});
    const TriangleMesh ground = gusuku::testing::horizontalPlane(1000.0f, 0.0f, glm::vec3(0.4f));
    const TraceScene scene = makeTraceScene(building, &ground);
    const SkySamplingTables sky = buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0);
    CameraTracer tracer(context(), scene);
    const CameraPose pose = lookAlong({0.0, 0.0, 1.0}, {0.0, 1.0, 0.0});
    const CameraIntrinsics intrinsics = intrinsics64x48(40.0, 40.0, 32.0, 24.0);
    CameraRenderOptions options = samples(4);
    options.include_building = true;
    const CameraRender with = tracer.render({&sky, {}}, intrinsics, pose, options);
    options.include_building = false;
    const CameraRender without = tracer.render({&sky, {}}, intrinsics, pose, options);
    // Pixel (32, 23) looks just above the horizon: at the square's middle, or without it at the sky.
    EXPECT_NEAR(pixelOf(with.radiance, 32, 23).g, 20.0f, 1e-3f);
    EXPECT_NEAR(pixelOf(without.radiance, 32, 23).g, 1.0f, 1e-5f);
    // Pixel (32, 24) looks just below it: at the square, or at the ground 40 m and more away, which under a
    // uniform sky with nothing else in view shows rho L exactly.
    EXPECT_NEAR(pixelOf(with.radiance, 32, 24).g, 20.0f, 1e-3f);
    EXPECT_NEAR(pixelOf(without.radiance, 32, 24).g, 0.4f, 1e-5f);
    // The ground at the camera's feet (the bottom 8 rows, 2048 paths): brighter with the glowing square, whose
    // light bounces off it; without the square, rho L exactly.
    double with_sum = 0.0, without_sum = 0.0;
    for (int y = 40; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            with_sum += pixelOf(with.radiance, x, y).g;
            without_sum += pixelOf(without.radiance, x, y).g;
        }
    EXPECT_NEAR(without_sum / (8 * 64), 0.4, 1e-5);
    EXPECT_GT(with_sum / (8 * 64), 0.41);
}

// A sunlit scene with an uneven sky (both sky estimators), a shadow and bounces: every random draw in use.
struct SunlitScene {
    TraceScene scene;
    SkySamplingTables sky;
    SunLight sun;
};

SunlitScene sunlitScene() {
    SunlitScene result;
    const TriangleMesh box = gusuku::testing::closedBox({-1.0f, 3.0f, 0.0f}, {1.0f, 5.0f, 2.0f}, false,
                                                        glm::vec3(0.6f, 0.5f, 0.4f));
    const TriangleMesh ground = gusuku::testing::horizontalPlane(200.0f, 0.0f, glm::vec3(0.3f));
    result.scene = makeTraceScene(box, &ground);
    result.sky = buildSkySamplingTables(patternedSky(64, 32), 0.0);
    result.sun.present = true;
    result.sun.direction_enu = glm::normalize(glm::dvec3(-0.4, 0.5, 0.7));
    result.sun.irradiance_rgb = glm::dvec3(6.0, 5.5, 5.0);
    return result;
}

TEST_F(CameraTracerTest, SameSeedGivesIdenticalBits) {
    const SunlitScene scene = sunlitScene();
    CameraTracer tracer(context(), scene.scene);
    const CameraPose pose = lookAlong({0.5, -3.0, 1.6}, {0.0, 1.0, -0.25});
    const CameraIntrinsics intrinsics = intrinsics64x48(45.0, 45.0, 32.0, 24.0);
    CameraRenderOptions options = samples(8);
    options.include_building = true;
    options.sky_sampling = SkySampling::CosineAndMap;
    const CameraRender first = tracer.render({&scene.sky, scene.sun}, intrinsics, pose, options);
    const CameraRender second = tracer.render({&scene.sky, scene.sun}, intrinsics, pose, options);
    ASSERT_EQ(first.radiance.texels.size(), second.radiance.texels.size());
    EXPECT_EQ(std::memcmp(first.radiance.texels.data(), second.radiance.texels.data(),
                          first.radiance.texels.size() * sizeof(float)),
              0);
    EXPECT_EQ(first.rays_traced, second.rays_traced);
    options.seed = 2;
    const CameraRender other_seed = tracer.render({&scene.sky, scene.sun}, intrinsics, pose, options);
    EXPECT_NE(std::memcmp(first.radiance.texels.data(), other_seed.radiance.texels.data(),
                          first.radiance.texels.size() * sizeof(float)),
              0)
        << "another seed must give other noise";
}

double rmsDifference(const ImageRGBA& a, const ImageRGBA& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.texels.size(); ++i)
        if (i % 4 != 3) sum += double(a.texels[i] - b.texels[i]) * double(a.texels[i] - b.texels[i]);
    return std::sqrt(sum / double(a.texels.size() / 4 * 3));
}

TEST_F(CameraTracerTest, DenoiserLowersErrorAndLeavesSkyAlone) {
    const SunlitScene scene = sunlitScene();
    CameraTracer tracer(context(), scene.scene);
    const CameraPose pose = lookAlong({0.5, -3.0, 1.6}, {0.0, 1.0, -0.1});
    const CameraIntrinsics intrinsics = intrinsics64x48(45.0, 45.0, 32.0, 24.0);
    CameraRenderOptions options = samples(4);
    options.include_building = true;
    const CameraRender noisy = tracer.render({&scene.sky, scene.sun}, intrinsics, pose, options);
    options.samples_per_pixel = 128;
    options.seed = 7;
    const CameraRender reference = tracer.render({&scene.sky, scene.sun}, intrinsics, pose, options);
    const ImageRGBA denoised = denoiseCameraFrame(noisy, intrinsics, pose, cameraDenoiseOptionsForSamples(4));
    const double raw_error = rmsDifference(noisy.radiance, reference.radiance);
    const double denoised_error = rmsDifference(denoised, reference.radiance);
    std::printf("camera frame RMS error against 128 spp, 4 spp: raw %.4f, denoised %.4f\n", raw_error, denoised_error);
    EXPECT_LT(denoised_error, 0.7 * raw_error);
    int sky_pixels = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            if (noisy.guides.normalDistance(x, y).w < 0.0f) {
                ++sky_pixels;
                EXPECT_EQ(pixelOf(denoised, x, y), pixelOf(noisy.radiance, x, y));
            }
    EXPECT_GT(sky_pixels, 100) << "the view must hold sky for this test to mean anything";
}

TEST_F(CameraTracerTest, BadViewIsRefusedWithTheField) {
    const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(10.0f, 0.0f, glm::vec3(0.5f)), nullptr);
    const SkySamplingTables sky = buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0);
    CameraTracer tracer(context(), scene);
    const CameraPose pose = lookAlong({0.0, 0.0, 5.0}, -kUp, {0.0, 1.0, 0.0});
    CameraIntrinsics intrinsics = intrinsics64x48(0.0, 40.0, 32.0, 24.0);
    EXPECT_THROW(tracer.render({&sky, {}}, intrinsics, pose, samples(1)), std::invalid_argument);
    intrinsics.fx = 40.0;
    CameraPose skewed = pose;
    skewed.camera_to_enu[0] *= 2.0;
    try {
        tracer.render({&sky, {}}, intrinsics, skewed, samples(1));
        ADD_FAILURE() << "a scaled rotation was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("pose.camera_to_enu"), std::string::npos) << error.what();
    }
    EXPECT_THROW(tracer.render({&sky, {}}, intrinsics, pose, samples(0)), std::invalid_argument);
    EXPECT_THROW(tracer.render({nullptr, {}}, intrinsics, pose, samples(1)), std::invalid_argument);
}

TEST_F(CameraTracerTest, SiteFrameInOneCallForSlotInstantAndOvercast) {
    // The mini site: a 2 m box house at the origin on the flat stand-in ground, slots "noon" and "cloudy".
    const SiteConfig site =
        loadSiteConfig(gusuku::testing::writeMiniSite(gusuku::testing::makeTemporaryDirectory("camera_site")));
    CameraIntrinsics intrinsics;
    intrinsics.width = 48;
    intrinsics.height = 27;
    intrinsics.fx = intrinsics.fy = 40.0;
    intrinsics.cx = 24.0;
    intrinsics.cy = 13.5;
    const CameraPose pose = lookAlong({0.3, -8.0, 1.2}, {0.0, 1.0, -0.05});
    SiteCameraOptions options;
    const BakeSlot noon = findSiteSlot(site, "noon");
    const SiteCameraFrame camera = renderSiteCameraFrame(context(), site, noon, intrinsics, pose, 4, options);
    options.include_building = true;
    const SiteCameraFrame truth = renderSiteCameraFrame(context(), site, noon, intrinsics, pose, 4, options);
    ASSERT_TRUE(camera.sun.present);
    EXPECT_EQ(camera.denoised.width, 48);
    EXPECT_EQ(camera.denoised.height, 27);
    // The centre pixel: the house's south wall with the building, the ground far behind without it.
    EXPECT_GT(truth.render.guides.albedoLit(24, 13).w, 0.0f);
    EXPECT_LT(truth.render.guides.normalDistance(24, 13).w, 8.5f);
    EXPECT_GT(camera.render.guides.normalDistance(24, 13).w, 8.5f);
    // A sunny condition at the slot's instant is the slot: the same bits.
    const SiteCameraFrame at_instant =
        renderSiteCameraFrame(context(), site, sunnyConditionAt(noon.utc_seconds), intrinsics, pose, 4, options);
    EXPECT_EQ(at_instant.render.radiance.texels, truth.render.radiance.texels);
    const SiteCameraFrame cloudy = renderSiteCameraFrame(context(), site, overcastCondition(), intrinsics, pose, 4, options);
    EXPECT_FALSE(cloudy.sun.present);
    try {
        findSiteSlot(site, "dusk");
        ADD_FAILURE() << "an unknown slot was found";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("noon, cloudy"), std::string::npos) << error.what();
    }
}

TEST(CameraFrameOutput, PacksLinearIntoSrgbBytes) {
    ImageRGBA image = gusuku::testing::uniformSky(5, 1, glm::vec3(0.0f));
    const float values[5] = {0.0f, 1.0f, 2.0f, -1.0f, 0.18f};
    for (int x = 0; x < 5; ++x)
        for (int channel = 0; channel < 3; ++channel) image.texel(x, 0)[channel] = values[x];
    image.texel(4, 0)[0] = 0.09f;  // 0.18 at exposure 2
    const std::vector<uint8_t> bytes = packRgba8Srgb(image);
    ASSERT_EQ(bytes.size(), 20u);
    // 0 -> 0, 1 -> 255, clamped above and below; linear 0.18 -> 1.055 0.18^(1/2.4) - 0.055 = 0.4614 -> 117.7 -> 118.
    const uint8_t expected[5] = {0, 255, 255, 0, 118};
    for (int x = 0; x < 5; ++x) {
        EXPECT_EQ(bytes[4 * x + 1], expected[x]) << "pixel " << x;
        EXPECT_EQ(bytes[4 * x + 3], 255) << "alpha";
    }
    EXPECT_EQ(packRgba8Srgb(image, 2.0f)[16], 118) << "exposure multiplies before encoding";
}

TEST(CameraFrameOutput, MiddleGreyExposureOfConstantFrame) {
    const ImageRGBA image = gusuku::testing::uniformSky(8, 4, glm::vec3(0.5f));
    EXPECT_NEAR(middleGreyExposure(image), 0.18 / (0.5 + 1e-6), 1e-5);
    EXPECT_EQ(middleGreyExposure(gusuku::testing::uniformSky(8, 4, glm::vec3(0.0f))), 1.0f);
}

}  // namespace
}  // namespace gusuku::bake

// One-sided faces of open parts (a cut-out card, a leaf, a sign: glTF materials without doubleSided that bound no
// solid) are sheets lit on both sides, as Cycles shades them and as the runtime draws them; only a closed part's
// one-sided back is the inside of a solid, dark. Checked against answers known without the tracer:
// - the bake: the light a floor gathers beside a one-sided open sheet is the same, bit for bit, as beside the
//   same sheet marked double-sided (the same random streams, the back shaded as the other side); the floor's
//   validity score still counts the one-sided back (the evidence of an inside, docs/baker.md);
// - the bake: a point inside a closed one-sided box gathers nothing;
// - the camera tracer: a camera under a one-sided open plane, under a uniform sky of radiance L, sees rho L in
//   every pixel (its back's bounce rays all escape to the same sky), and from inside a closed one-sided box sees
//   black.
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku_bake/camera_tracer.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;

// A floor (4 m square at z = 0.05, facing up) with a sheet standing on it across x (3 m wide, 2 m tall, in the
// plane y = 0, its front facing north); the sheet's material one- or double-sided, the floor's one-sided.
TriangleMesh floorWithSheet(bool sheet_double_sided) {
    TriangleMesh mesh = gusuku::testing::emptyMesh(glm::vec3(0.6f));
    gusuku::testing::addQuad(mesh, {-2.0f, -2.0f, 0.05f}, {2.0f, -2.0f, 0.05f}, {2.0f, 2.0f, 0.05f},
                             {-2.0f, 2.0f, 0.05f});
    Material sheet = mesh.materials[0];
    sheet.base_color_factor = glm::vec4(0.8f, 0.5f, 0.3f, 1.0f);
    sheet.double_sided = sheet_double_sided;
    mesh.materials.push_back(sheet);
    const size_t first_sheet_triangle = mesh.triangle_material.size();
    gusuku::testing::addQuad(mesh, {1.5f, 0.0f, 0.05f}, {-1.5f, 0.0f, 0.05f}, {-1.5f, 0.0f, 2.05f},
                             {1.5f, 0.0f, 2.05f});
    for (size_t t = first_sheet_triangle; t < mesh.triangle_material.size(); ++t) mesh.triangle_material[t] = 1u;
    return mesh;
}

struct ProbeSums {
    std::vector<glm::vec4> sums;  ///< xyz the irradiance sum, w the back-face score's
    uint32_t samples = 0;
};

// Probes on the floor south of the sheet (its back side) and north of it, facing up.
std::vector<QueryPointGpu> floorProbes() {
    std::vector<QueryPointGpu> points;
    const glm::vec4 up(0.0f, 0.0f, 1.0f, 0.0f);
    for (int ix = -4; ix <= 4; ++ix)
        for (const float y : {-0.02f, -0.1f, -0.4f, -1.2f, 0.4f})
            points.push_back({glm::vec4(0.3f * float(ix) + 0.01f, y, 0.05f, 1.0f), up, up});
    return points;
}

ProbeSums traceProbes(VulkanContext& context, const TriangleMesh& building, const std::vector<QueryPointGpu>& points) {
    const TriangleMesh ground = gusuku::testing::horizontalPlane(50.0f, 0.0f, glm::vec3(0.3f));
    const TraceScene scene = makeTraceScene(building, &ground);
    IrradianceTracer tracer(context, scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(32, 16, glm::vec3(1.0f)), 0.0));
    ProbeSums result;
    result.samples = 64;
    PointAccumulator accumulator = tracer.createAccumulator(points);
    TracePass pass;
    pass.max_bounces = 2;
    tracer.addSamples(accumulator, result.samples, pass);
    result.sums = tracer.readSums(accumulator);
    return result;
}

class OpenOneSidedTest : public GpuTest {};

TEST_F(OpenOneSidedTest, AnOpenOneSidedSheetLightsTheFloorAsItsDoubleSidedTwin) {
    const std::vector<QueryPointGpu> points = floorProbes();
    const ProbeSums one_sided = traceProbes(context(), floorWithSheet(false), points);
    const ProbeSums double_sided = traceProbes(context(), floorWithSheet(true), points);
    ASSERT_EQ(one_sided.sums.size(), points.size());
    float highest_one_sided_score = 0.0f;
    double back_side_irradiance = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        for (int channel = 0; channel < 3; ++channel)
            EXPECT_EQ(one_sided.sums[i][channel], double_sided.sums[i][channel])
                << "probe at (" << points[i].position.x << ", " << points[i].position.y << ") channel " << channel;
        // An open double-sided sheet's back is no evidence of an inside; a one-sided back still is.
        EXPECT_EQ(double_sided.sums[i].w, 0.0f);
        highest_one_sided_score = std::max(highest_one_sided_score, one_sided.sums[i].w / float(one_sided.samples));
        if (points[i].position.y < 0.0f) back_side_irradiance += one_sided.sums[i].y / float(one_sided.samples);
    }
    // At the sheet's foot about half of the first rays see its back.
    EXPECT_GT(highest_one_sided_score, 0.3f);
    EXPECT_GT(back_side_irradiance, 0.0);
    std::printf("  open one-sided sheet: floor light equal to the double-sided sheet's on %zu probes; highest "
                "one-sided back score %.3f\n",
                points.size(), highest_one_sided_score);
}

TEST_F(OpenOneSidedTest, APointInsideAClosedOneSidedBoxGathersNothing) {
    // A 2 m box standing 1 m above the ground, faces outward, one-sided; probes inside it facing every axis.
    const TriangleMesh box = gusuku::testing::closedBox({-1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 3.0f}, false,
                                                        glm::vec3(0.7f));
    std::vector<QueryPointGpu> points;
    for (const glm::vec3 normal : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
        points.push_back({glm::vec4(0.2f, -0.1f, 2.0f, 1.0f), glm::vec4(normal, 0.0f), glm::vec4(normal, 0.0f)});
    const ProbeSums inside = traceProbes(context(), box, points);
    for (size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(inside.sums[i].x, 0.0f) << "probe " << i;
        EXPECT_EQ(inside.sums[i].y, 0.0f) << "probe " << i;
        EXPECT_EQ(inside.sums[i].z, 0.0f) << "probe " << i;
        EXPECT_EQ(inside.sums[i].w, float(inside.samples)) << "every first ray sees a one-sided back";
    }
}

// A pose at `position` looking along `forward` (image x to the right, y down: runtime.h).
CameraPose lookAlong(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up) {
    const glm::dvec3 z = glm::normalize(forward);
    const glm::dvec3 x = glm::normalize(glm::cross(z, up));
    CameraPose pose;
    pose.position_enu = position;
    pose.camera_to_enu = glm::dmat3(x, glm::cross(z, x), z);
    return pose;
}

CameraIntrinsics intrinsics32x24() {
    CameraIntrinsics intrinsics;
    intrinsics.fx = intrinsics.fy = 25.0;
    intrinsics.cx = 16.0;
    intrinsics.cy = 12.0;
    intrinsics.width = 32;
    intrinsics.height = 24;
    return intrinsics;
}

glm::vec3 pixelOf(const ImageRGBA& image, int x, int y) {
    const float* texel = image.texel(x, y);
    return {texel[0], texel[1], texel[2]};
}

TEST_F(OpenOneSidedTest, TheCameraSeesAnOpenOneSidedBackLitAndAClosedOnesInsideDark) {
    const glm::vec3 albedo(0.5f, 0.3f, 0.7f);
    const glm::vec3 sky_radiance(0.8f, 0.6f, 0.4f);
    const SkySamplingTables sky = buildSkySamplingTables(gusuku::testing::uniformSky(64, 32, sky_radiance), 0.0);
    CameraRenderOptions options;
    options.samples_per_pixel = 4;
    options.include_building = true;
    {
        // A 2 km one-sided plane facing up, seen from 10 m below: every bounce off its back leaves downward to
        // the uniform sky, so each sample is rho / pi * (pi L) = rho L (before, such a back was black).
        const TraceScene scene = makeTraceScene(gusuku::testing::horizontalPlane(1000.0f, 0.0f, albedo), nullptr);
        CameraTracer tracer(context(), scene);
        const CameraPose pose = lookAlong({3.0, -2.0, -10.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0});
        const CameraRender render = tracer.render({&sky, {}}, intrinsics32x24(), pose, options);
        const glm::vec3 expected = albedo * sky_radiance;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 32; ++x)
                for (int channel = 0; channel < 3; ++channel)
                    ASSERT_NEAR(pixelOf(render.radiance, x, y)[channel], expected[channel], 1e-5f * expected[channel])
                        << "pixel " << x << ", " << y << " channel " << channel;
    }
    {
        // Inside a closed one-sided box (faces outward): the inside of a solid, black in every pixel.
        const TraceScene scene = makeTraceScene(
            gusuku::testing::closedBox({-1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 3.0f}, false, albedo), nullptr);
        CameraTracer tracer(context(), scene);
        const CameraPose pose = lookAlong({0.2, -0.1, 2.0}, {0.3, 1.0, 0.2}, {0.0, 0.0, 1.0});
        const CameraRender render = tracer.render({&sky, {}}, intrinsics32x24(), pose, options);
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 32; ++x) ASSERT_EQ(pixelOf(render.radiance, x, y), glm::vec3(0.0f)) << x << ", " << y;
    }
}

}  // namespace
}  // namespace gusuku::bake

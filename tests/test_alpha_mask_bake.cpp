// Alpha-masked materials in the baker's tracer (issue 21 item 3): rays pass through a masked surface where its
// base colour's alpha is below the cutoff. Checked against answers computed from the mask itself:
// - the sun's shadow of a masked checker quad on the ground has the checker's shape, texel for texel;
// - sunlight through a fence of masked slats reaches the ground in proportion to the open fraction;
// - under an infinite black masked roof with open fraction f, the ground sees f of the sky: E = f pi L
//   (sky shadow rays and cosine-sampled bounce rays alike pass the holes);
// - the same geometry unmasked casts a solid shadow (the flag, not the texture, decides).
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

// A white texture whose alpha is open(x, y) ? 0 : 1 (x, y texel indices, row 0 the top: v = 0).
template <typename Open>
ImageRGBA alphaMask(int width, int height, Open open) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, 1.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.texel(x, y)[3] = open(x, y) ? 0.0f : 1.0f;
    return image;
}

// A one-quad mesh (corners a, b, c, d as addQuad takes them: uv0 (0,0) at a, (1,0) at b, (0,1) at d) textured
// with `mask`, uv0 scaled by `repeats` (the sampler repeats), black unless given an albedo, masked or not.
TriangleMesh maskedQuad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                        const ImageRGBA& mask, float repeats, bool masked, glm::vec3 albedo = glm::vec3(0.0f)) {
    TriangleMesh mesh = gusuku::testing::emptyMesh(albedo);
    gusuku::testing::addQuad(mesh, a, b, c, d);
    for (glm::vec2& uv : mesh.uv0) uv *= repeats;
    mesh.textures.push_back(mask);
    mesh.texture_names.push_back("mask");
    mesh.materials[0].base_color_texture = 0;
    mesh.materials[0].double_sided = true;
    mesh.materials[0].alpha_masked = masked;
    mesh.materials[0].alpha_cutoff = 0.5f;
    return mesh;
}

TracePass sunOnly(const glm::vec3& towards_sun) {
    TracePass pass;
    pass.mode = TraceMode::SunDirect;
    pass.sun.present = true;
    pass.sun.direction_enu = glm::normalize(glm::dvec3(towards_sun));
    pass.sun.irradiance_rgb = glm::dvec3(1000.0);
    return pass;
}

std::vector<QueryPointGpu> upFacing(const std::vector<glm::vec3>& positions) {
    std::vector<QueryPointGpu> points;
    for (const glm::vec3& p : positions) points.push_back({glm::vec4(p, 1.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)});
    return points;
}

class AlphaMaskBakeTest : public GpuTest {};

// An 8 m quad 2 m above the ground, an 8 x 8 texel mask (one texel a metre) with holes in a checker and one
// extra hole, the sun overhead: each ground point under a texel centre is lit exactly where its texel is open.
TEST_F(AlphaMaskBakeTest, SunShadowOfMaskedQuadHasTheMasksShape) {
    const auto open = [](int x, int y) { return (x + y) % 2 == 0 || (x == 1 && y == 6); };
    const ImageRGBA mask = alphaMask(8, 8, open);
    for (const bool masked : {true, false}) {
        TriangleMesh quad = maskedQuad({0, 0, 2}, {8, 0, 2}, {8, 8, 2}, {0, 8, 2}, mask, 1.0f, masked);
        TriangleMesh ground = gusuku::testing::horizontalPlane(100.0f, 0.0f, glm::vec3(0.5f));
        const TraceScene scene = makeTraceScene(quad, &ground);
        IrradianceTracer tracer(context(), scene,
                                buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
        std::vector<glm::vec3> positions;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) positions.push_back({float(x) + 0.5f, float(y) + 0.5f, 0.0f});
        const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(upFacing(positions), 16, sunOnly({0, 0, 1}));
        int lit = 0;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                // uv = (x, y) / 8 on this quad: texel (x, y) lies over ground point (x + 0.5, y + 0.5).
                const float expected = masked && open(x, y) ? 1000.0f : 0.0f;
                EXPECT_NEAR(irradiance[size_t(y * 8 + x)].r, expected, 1.0f)
                    << (masked ? "masked" : "opaque") << " texel " << x << ", " << y;
                lit += irradiance[size_t(y * 8 + x)].r > 500.0f;
            }
        EXPECT_EQ(lit, masked ? 33 : 0);
    }
}

// A vertical fence of slats (a 64-texel-wide mask, a quarter of each period open, 16 periods over 4 m) with the
// sun low behind it: the ground strip in its shadow gets a quarter of the sun, averaged over whole periods.
TEST_F(AlphaMaskBakeTest, SunlightThroughMaskedFenceIsInProportionToItsOpening) {
    const ImageRGBA slats = alphaMask(64, 4, [](int x, int) { return x % 16 < 4; });
    TriangleMesh fence = maskedQuad({0, 0, 0}, {4, 0, 0}, {4, 0, 3}, {0, 0, 3}, slats, 4.0f, true);
    TriangleMesh ground = gusuku::testing::horizontalPlane(100.0f, 0.0f, glm::vec3(0.5f));
    const TraceScene scene = makeTraceScene(fence, &ground);
    IrradianceTracer tracer(context(), scene,
                            buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
    // Sun from -y at 45 degrees: the fence's shadow falls on y in (0, 3); points at y = 1 along a line across
    // one metre (four periods), 256 of them so each period is sampled evenly.
    const glm::vec3 towards_sun = glm::normalize(glm::vec3(0.0f, -1.0f, 1.0f));
    std::vector<glm::vec3> positions;
    for (int i = 0; i < 256; ++i) positions.push_back({1.0f + (float(i) + 0.5f) / 256.0f, 1.0f, 0.0f});
    const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(upFacing(positions), 4, sunOnly(towards_sun));
    double mean = 0.0;
    for (const glm::vec3& e : irradiance) mean += e.r;
    mean /= double(irradiance.size());
    const double unshadowed = 1000.0 * double(towards_sun.z);
    EXPECT_NEAR(mean / unshadowed, 0.25, 0.02);
}

// A black masked roof, 1 m up and 2 km wide, open in fine stripes (open fraction 3/8, period 5 cm): a ground
// point sees the uniform sky through the stripes only, E = (3/8) pi L, by the cosine lobe and the sky map both.
// Unmasked it is a solid roof: E = 0.
TEST_F(AlphaMaskBakeTest, UniformSkyThroughMaskedRoofIsTheOpenFraction) {
    const ImageRGBA stripes = alphaMask(8, 1, [](int x, int) { return x < 3; });
    const float half = 1000.0f, period_m = 0.05f;
    for (const bool masked : {true, false}) {
        TriangleMesh roof = maskedQuad({-half, -half, 1}, {half, -half, 1}, {half, half, 1}, {-half, half, 1}, stripes,
                                       2.0f * half / period_m, masked);
        TriangleMesh ground = gusuku::testing::horizontalPlane(2.0f * half, 0.0f, glm::vec3(0.0f));
        const TraceScene scene = makeTraceScene(roof, &ground);
        IrradianceTracer tracer(context(), scene,
                                buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
        std::vector<glm::vec3> positions;
        for (int i = 0; i < 32; ++i) positions.push_back({0.013f * float(i), 0.0f, 0.0f});
        for (const SkySampling sky_sampling : {SkySampling::CosineOnly, SkySampling::CosineAndMap}) {
            TracePass pass;
            pass.max_bounces = 2;
            pass.sky_sampling = sky_sampling;
            const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(upFacing(positions), 256, pass);
            double mean = 0.0;
            for (const glm::vec3& e : irradiance) mean += e.g;
            mean /= double(irradiance.size());
            const double expected = masked ? 3.0 / 8.0 * std::numbers::pi : 0.0;
            EXPECT_NEAR(mean, expected, 0.03 * std::numbers::pi)
                << (masked ? "masked" : "opaque") << ", sky sampling " << int(sky_sampling);
        }
    }
}

}  // namespace
}  // namespace gusuku::bake

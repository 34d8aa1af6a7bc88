// Alpha-masked materials in the baker's tracer (issue 21 item 3): rays pass through a masked surface where its
// base colour's alpha is below the cutoff. Checked against answers computed from the mask itself:
// - the sun's shadow of a masked checker quad on the ground has the checker's shape, texel for texel;
// - sunlight through a fence of masked slats reaches the ground in proportion to the open fraction;
// - under an infinite black masked roof with open fraction f, the ground sees f of the sky: E = f pi L
//   (sky shadow rays and cosine-sampled bounce rays alike pass the holes);
// - the same geometry unmasked casts a solid shadow (the flag, not the texture, decides);
// - the shared house's tree (material "WhiteAlpha", alphaMode MASK) casts a dappled shadow: under an overhead sun
//   some points beneath its canopy are lit, where read as opaque almost none are (skipped without ../shared).
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::alphaMask;
using gusuku::testing::GpuTest;

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

// Points 5 cm below the tree's crown, over its bounding box's footprint (its corners outside the crown), sun
// straight overhead: the share lit, with the tree's mask and with it read as opaque.
TEST_F(AlphaMaskBakeTest, SharedHousesTreeCastsADappledShadow) {
    GUSUKU_REQUIRE_SHARED_DATA();
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp() * glm::dmat4(glm::dmat3(16.0));  // as the bench's site: scale 16
    options.max_texture_size = 512;
    TriangleMesh house =
        loadGltf(gusuku::testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb", options);
    // The masked material textures the whole diorama from one atlas of cut-outs (vines, flowers, the tree's
    // crown). The crown's cards: the largest triangle with a transparent corner, and every masked triangle whose
    // uv centre falls in that triangle's uv box (the crown is crossed cards of the same picture).
    const auto alphaAt = [&](const Material& material, glm::vec2 uv) {
        const ImageRGBA& texture = house.textures[size_t(material.base_color_texture)];
        const int x = std::clamp(int((uv.x - std::floor(uv.x)) * float(texture.width)), 0, texture.width - 1);
        const int y = std::clamp(int((uv.y - std::floor(uv.y)) * float(texture.height)), 0, texture.height - 1);
        return texture.texel(x, y)[3];
    };
    const auto corner = [&](size_t t, int c) { return house.indices[3 * t + size_t(c)]; };
    size_t largest = house.triangleCount();
    float largest_area = 0.0f;
    for (size_t t = 0; t < house.triangleCount(); ++t) {
        const Material& material = house.materials[house.triangle_material[t]];
        if (!material.alpha_masked || material.base_color_texture < 0) continue;
        bool transparent_corner = false;
        for (int c = 0; c < 3; ++c) transparent_corner |= alphaAt(material, house.uv0[corner(t, c)]) < material.alpha_cutoff;
        const float area = glm::length(glm::cross(house.positions[corner(t, 1)] - house.positions[corner(t, 0)],
                                                  house.positions[corner(t, 2)] - house.positions[corner(t, 0)]));
        if (transparent_corner && area > largest_area) largest = t, largest_area = area;
    }
    ASSERT_LT(largest, house.triangleCount()) << "the shared house has no cut-out card";
    glm::vec2 uv_min(1e30f), uv_max(-1e30f);
    for (int c = 0; c < 3; ++c) {
        uv_min = glm::min(uv_min, house.uv0[corner(largest, c)]);
        uv_max = glm::max(uv_max, house.uv0[corner(largest, c)]);
    }
    Bounds3 tree;
    for (size_t t = 0; t < house.triangleCount(); ++t) {
        if (!house.materials[house.triangle_material[t]].alpha_masked) continue;
        glm::vec2 uv(0.0f);
        for (int c = 0; c < 3; ++c) uv += house.uv0[corner(t, c)] / 3.0f;
        if (glm::any(glm::lessThan(uv, uv_min)) || glm::any(glm::greaterThan(uv, uv_max))) continue;
        for (int c = 0; c < 3; ++c) tree.extend(house.positions[corner(t, c)]);
    }
    const glm::vec3 middle = 0.5f * (tree.min + tree.max), half = 0.5f * (tree.max - tree.min);
    std::vector<glm::vec3> positions;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            positions.push_back({middle.x + half.x * (float(x) / 15.5f - 1.0f),
                                 middle.y + half.y * (float(y) / 15.5f - 1.0f), tree.min.z - 0.05f});
    double lit_share[2] = {0.0, 0.0};
    for (const bool masked : {true, false}) {
        for (Material& material : house.materials) material.alpha_masked &= masked;
        const TraceScene scene = makeTraceScene(house, nullptr);
        IrradianceTracer tracer(context(), scene,
                                buildSkySamplingTables(gusuku::testing::uniformSky(16, 8, glm::vec3(1.0f)), 0.0));
        const std::vector<glm::vec3> irradiance = tracer.traceIrradiance(upFacing(positions), 4, sunOnly({0, 0, 1}));
        int lit = 0;
        for (const glm::vec3& e : irradiance) lit += e.r > 500.0f;
        lit_share[masked ? 0 : 1] = double(lit) / double(positions.size());
    }
    std::printf("foliage bounds (%.2f, %.2f, %.2f) to (%.2f, %.2f, %.2f) m\n", tree.min.x, tree.min.y, tree.min.z,
                tree.max.x, tree.max.y, tree.max.z);
    std::printf("under the shared house's tree: %.3f of the points lit with its mask, %.3f read as opaque\n",
                lit_share[0], lit_share[1]);
    EXPECT_GT(lit_share[0], lit_share[1] + 0.1) << "the mask's holes let the sun through";
    EXPECT_LT(lit_share[0], 0.95) << "the canopy still shades: dappled, not gone";
}

}  // namespace
}  // namespace gusuku::bake

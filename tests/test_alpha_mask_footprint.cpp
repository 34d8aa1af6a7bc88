// Which alpha-masked triangles the tracer alpha-tests (narrowAlphaMaskFlags, gusuku_bake/alpha_mask_footprint.h).
// Judged against the shader's own lookup, evaluated here on a dense grid of points over each triangle
// (sampleBaseColorAlpha's bilinear mix with wrap, in float): a triangle whose test is dropped must have no point
// below the cutoff (the narrowing is exact, never a change to a bake), and the cases below must keep or drop the
// test as the geometry of the footprint says.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "gusuku_bake/alpha_mask_footprint.h"
#include "gusuku_bake/trace_scene.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::alphaMask;

// A masked (cutoff 0.5) mesh of one material with `texture`, and one triangle per uv0 triple.
TriangleMesh maskedTriangles(const ImageRGBA& texture, const std::vector<std::array<glm::vec2, 3>>& uvs) {
    TriangleMesh mesh = gusuku::testing::emptyMesh(glm::vec3(0.5f));
    mesh.textures.push_back(texture);
    mesh.texture_names.push_back("mask");
    mesh.materials[0].base_color_texture = 0;
    mesh.materials[0].alpha_masked = true;
    mesh.materials[0].alpha_cutoff = 0.5f;
    for (size_t t = 0; t < uvs.size(); ++t) {
        const uint32_t first = uint32_t(mesh.positions.size());
        const float x = float(t);
        mesh.positions.insert(mesh.positions.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}});
        mesh.normals.insert(mesh.normals.end(), 3, glm::vec3(0, 0, 1));
        mesh.uv0.insert(mesh.uv0.end(), uvs[t].begin(), uvs[t].end());
        mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
        mesh.triangle_material.push_back(0u);
    }
    return mesh;
}

std::vector<bool> testedAfterNarrowing(const TriangleMesh& mesh) {
    const TraceScene scene = makeTraceScene(mesh, nullptr);
    const PackedSceneShading shading = packSceneShading(scene.mesh);
    const std::vector<uint32_t> flags = narrowAlphaMaskFlags(shading, scene.triangle_flags);
    std::vector<bool> tested;
    for (uint32_t f : flags) tested.push_back((f & kTriangleFlagAlphaMasked) != 0);
    return tested;
}

// The shader's alpha at uv (scene_shading.glsl's sampleBaseColorAlpha, times the factor), in float.
float shaderAlpha(const ImageRGBA& texture, float factor, glm::vec2 uv) {
    const int w = texture.width, h = texture.height;
    const float cx = uv.x * float(w) - 0.5f, cy = uv.y * float(h) - 0.5f;
    const float bx = std::floor(cx), by = std::floor(cy);
    const float wx = cx - bx, wy = cy - by;
    const auto wrap = [](float base, int size) { return int(base - float(size) * std::floor(base / float(size))); };
    const int x0 = wrap(bx, w), y0 = wrap(by, h), x1 = (x0 + 1) % w, y1 = (y0 + 1) % h;
    const auto a = [&](int x, int y) { return std::round(texture.texel(x, y)[3] * 255.0f) / 255.0f; };
    const float top = a(x0, y0) + (a(x1, y0) - a(x0, y0)) * wx;
    const float bottom = a(x0, y1) + (a(x1, y1) - a(x0, y1)) * wx;
    return factor * (top + (bottom - top) * wy);
}

// True when some point of the triangle (a 64 x 64 barycentric grid, edges and corners included) is a hole.
bool someHoleUnder(const ImageRGBA& texture, const std::array<glm::vec2, 3>& uv) {
    constexpr int kSteps = 64;
    for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
            const float u = float(i) / kSteps, v = float(j) / kSteps;
            const glm::vec2 at = (1.0f - u - v) * uv[0] + u * uv[1] + v * uv[2];
            if (shaderAlpha(texture, 1.0f, at) < 0.5f) return true;
        }
    return false;
}

// A 16 x 16 texture with one hole texel at (8, 8): texel centre (8.5, 8.5), read by bilinear lookups at texel
// coordinates within one texel of it, i.e. uv in (7.5, 9.5) / 16 on both axes.
TEST(AlphaMaskFootprint, KeepsTheTestOnlyWhereALookupCanReadAHole) {
    const ImageRGBA texture = alphaMask(16, 16, [](int x, int y) { return x == 8 && y == 8; });
    const auto at = [](float x, float y) { return glm::vec2(x / 16.0f, y / 16.0f); };  // texel units
    const std::vector<std::array<glm::vec2, 3>> uvs = {
        {at(1, 1), at(5, 1), at(1, 5)},              // far from the hole: dropped
        {at(8.2f, 8.2f), at(8.8f, 8.2f), at(8.2f, 8.8f)},  // on the hole: kept
        {at(9.3f, 8.5f), at(12, 8.5f), at(9.3f, 12)},  // 0.8 texel from its centre: bilinear reads it, kept
        {at(9.6f, 8.5f), at(12, 8.5f), at(9.6f, 12)},  // 1.1 texels away: never read, dropped
        {at(-0.4f, 8.5f), at(0.3f, 8.5f), at(-0.4f, 9)},  // across the wrap at u = 0, rows of the hole, far in u: dropped
        {at(-7.6f, 8.4f), at(-7.2f, 8.4f), at(-7.6f, 8.7f)},  // one repeat to the left of the hole: kept
        {at(0, 0), at(48, 0), at(0, 48)},            // three repeats: kept
    };
    const std::vector<bool> expected = {false, true, true, false, false, true, true};
    const std::vector<bool> tested = testedAfterNarrowing(maskedTriangles(texture, uvs));
    ASSERT_EQ(tested.size(), expected.size());
    // Reading the hole is not being one: the third triangle mixes it in at most 0.2 (alpha 0.8), so it stays
    // tested for a hole it never shows, the price of a bound on the footprint rather than its exact alpha.
    EXPECT_TRUE(someHoleUnder(texture, uvs[1]));
    EXPECT_FALSE(someHoleUnder(texture, uvs[2]));
    for (size_t t = 0; t < expected.size(); ++t) {
        EXPECT_EQ(tested[t], expected[t]) << "triangle " << t;
        if (!tested[t]) EXPECT_FALSE(someHoleUnder(texture, uvs[t])) << "triangle " << t;
    }
}

// The factor alone decides without a texture; opaque materials are never tested, and the building flag is kept.
TEST(AlphaMaskFootprint, UntexturedMaterialsAreDecidedByTheirFactor) {
    for (const float factor_alpha : {1.0f, 0.3f}) {
        TriangleMesh mesh = gusuku::testing::emptyMesh(glm::vec3(0.5f));
        gusuku::testing::addQuad(mesh, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
        mesh.materials[0].base_color_factor.a = factor_alpha;
        mesh.materials[0].alpha_masked = true;
        mesh.materials[0].alpha_cutoff = 0.5f;
        const TraceScene scene = makeTraceScene(mesh, nullptr);
        const std::vector<uint32_t> flags = narrowAlphaMaskFlags(packSceneShading(scene.mesh), scene.triangle_flags);
        for (uint32_t f : flags) {
            EXPECT_EQ((f & kTriangleFlagAlphaMasked) != 0, factor_alpha < 0.5f) << "factor alpha " << factor_alpha;
            EXPECT_NE(f & kTriangleFlagBuilding, 0u);
        }
    }
}

// Random small triangles over a texture with random holes: every triangle whose test is dropped has no point the
// shader would call a hole, and most triangles that miss the holes are dropped (the footprint is a bound, not
// the exact set, so a few near holes stay tested).
TEST(AlphaMaskFootprint, DroppedTestsNeverHideAHoleOnRandomTriangles) {
    std::mt19937 random(20261202u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const ImageRGBA texture = alphaMask(32, 32, [&](int, int) { return unit(random) < 0.03f; });
    std::vector<std::array<glm::vec2, 3>> uvs;
    for (int t = 0; t < 2000; ++t) {
        const glm::vec2 corner(unit(random) * 3.0f - 1.0f, unit(random) * 3.0f - 1.0f);  // across repeats
        const float size = 0.01f + 0.1f * unit(random);
        uvs.push_back({corner, corner + glm::vec2(size * unit(random), size * unit(random)),
                       corner + glm::vec2(-size * unit(random), size * unit(random))});
    }
    const std::vector<bool> tested = testedAfterNarrowing(maskedTriangles(texture, uvs));
    size_t dropped = 0, without_holes = 0;
    for (size_t t = 0; t < uvs.size(); ++t) {
        const bool hole = someHoleUnder(texture, uvs[t]);
        if (!tested[t]) {
            EXPECT_FALSE(hole) << "triangle " << t << " lost its alpha test over a hole";
            ++dropped;
        }
        without_holes += hole ? 0 : 1;
    }
    EXPECT_GT(without_holes, 500u);
    EXPECT_GT(double(dropped), 0.6 * double(without_holes)) << dropped << " dropped of " << without_holes;
    std::printf("alpha footprint: %zu of %zu triangles without a hole dropped their test\n", dropped, without_holes);
}

}  // namespace
}  // namespace gusuku::bake

// The real assets in ../shared/data load through the same paths the baker uses: both buildings (one .glb
// with a lightmap UV channel, one .gltf with external JPEG textures) and the three skies. Expected sizes and
// triangle counts come from the assets' SOURCE.md files.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"

namespace {

using gusuku::TriangleMesh;

void expectFiniteBoundsWithExtent(const TriangleMesh& mesh) {
    const gusuku::Bounds3 bounds = gusuku::meshBounds(mesh);
    ASSERT_FALSE(bounds.empty());
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_TRUE(std::isfinite(bounds.min[axis]) && std::isfinite(bounds.max[axis]));
        EXPECT_GT(bounds.max[axis] - bounds.min[axis], 0.0f) << "flat along axis " << axis;
    }
}

void expectWellFormed(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.vertexCount());
    ASSERT_EQ(mesh.uv0.size(), mesh.vertexCount());
    ASSERT_EQ(mesh.triangle_material.size(), mesh.triangleCount());
    for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertexCount());
    for (uint32_t material : mesh.triangle_material) ASSERT_LT(material, mesh.materials.size());
    for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
}

TEST(SharedAssetsTest, PlaycanvasHouseHasLightmapUvs) {
    GUSUKU_REQUIRE_SHARED_DATA();
    const std::string path = gusuku::testing::sharedDataDir() + "/building/playcanvas_house_lightmapUV/house.glb";
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    std::vector<std::string> warnings;
    const TriangleMesh mesh = gusuku::loadGltf(path, options, &warnings);
    EXPECT_GT(mesh.triangleCount(), 0u);
    EXPECT_EQ(mesh.triangleCount(), 10497u);  // SOURCE.md
    EXPECT_TRUE(mesh.has_uv1);
    EXPECT_EQ(mesh.uv1.size(), mesh.vertexCount());
    expectWellFormed(mesh);
    expectFiniteBoundsWithExtent(mesh);
    // SOURCE.md: about 0.5 x 0.19 x 0.5 units; glTF's y (up) becomes ENU z: the 0.19 is the height.
    const gusuku::Bounds3 bounds = gusuku::meshBounds(mesh);
    EXPECT_NEAR(bounds.max.x - bounds.min.x, 0.5f, 0.02f);
    EXPECT_NEAR(bounds.max.y - bounds.min.y, 0.5f, 0.02f);
    EXPECT_NEAR(bounds.max.z - bounds.min.z, 0.19f, 0.01f);
}

TEST(SharedAssetsTest, JapanTempleLoadsWithTextures) {
    GUSUKU_REQUIRE_SHARED_DATA();
    const std::string path = gusuku::testing::sharedDataDir() + "/building/japan_temple_yankobe/scene.gltf";
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    options.max_texture_size = 256;  // the test needs the textures decoded, not their detail
    std::vector<std::string> warnings;
    const TriangleMesh mesh = gusuku::loadGltf(path, options, &warnings);
    EXPECT_GT(mesh.triangleCount(), 0u);
    EXPECT_EQ(mesh.triangleCount(), 12418u);  // SOURCE.md
    EXPECT_FALSE(mesh.has_uv1);
    expectWellFormed(mesh);
    expectFiniteBoundsWithExtent(mesh);
    // SOURCE.md: about 3.0 x 4.0 x 4.7 units; glTF's y (up) becomes ENU z: the 4.0 is the height.
    const gusuku::Bounds3 bounds = gusuku::meshBounds(mesh);
    EXPECT_NEAR(bounds.max.x - bounds.min.x, 3.0f, 0.1f);
    EXPECT_NEAR(bounds.max.y - bounds.min.y, 4.7f, 0.1f);
    EXPECT_NEAR(bounds.max.z - bounds.min.z, 4.0f, 0.1f);
    EXPECT_GE(mesh.textures.size(), 7u);  // seven base-colour JPEGs in textures/
    EXPECT_EQ(mesh.texture_names.size(), mesh.textures.size());
    for (const gusuku::ImageRGBA& texture : mesh.textures) {
        EXPECT_GT(texture.width, 0);
        EXPECT_LE(texture.width, 256);
        EXPECT_LE(texture.height, 256);
        double mean = 0.0;
        for (float value : texture.texels) mean += value;
        EXPECT_GT(mean / double(texture.texels.size()), 0.0);
    }
    size_t textured_materials = 0;
    for (const gusuku::Material& material : mesh.materials) textured_materials += material.base_color_texture >= 0;
    EXPECT_GE(textured_materials, 7u);
    for (const std::string& warning : warnings) ADD_FAILURE() << "unexpected warning: " << warning;
}

TEST(SharedAssetsTest, SkiesAreValidRadianceMaps) {
    GUSUKU_REQUIRE_SHARED_DATA();
    for (const char* name : {"immenstadter_horn_1k.hdr", "potsdamer_platz_1k.hdr", "rooitou_park_1k.hdr"}) {
        SCOPED_TRACE(name);
        const gusuku::ImageRGBA sky = gusuku::readRadianceMap(gusuku::testing::sharedDataDir() + "/env/" + name);
        EXPECT_EQ(sky.width, 1024);  // "1k" equirectangular: 2:1
        EXPECT_EQ(sky.height, 512);
        double sum = 0.0;
        for (int y = 0; y < sky.height; ++y)
            for (int x = 0; x < sky.width; ++x)
                for (int c = 0; c < 3; ++c) sum += sky.texel(x, y)[c];
        EXPECT_GT(sum / (3.0 * sky.width * sky.height), 0.0);
    }
}

}  // namespace

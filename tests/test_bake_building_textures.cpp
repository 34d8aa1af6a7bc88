// The bake set keeps the building's textures at the detail the runtime draws: building.glb holds a 1024^2 source
// texture texel for texel (the tracers read it at 512, which once was also what building.glb kept: the runtime then
// drew a quarter of the shared shrine's 2048^2 structure texture, docs/measurements.md), and
// BakeOptions::building_texture_size (gusuku-bake bake --texture-size) holds it to a smaller side when asked.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/maths/colour.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;

constexpr int kSourceSide = 1024;

// An 8-bit sRGB code per texel and channel with no two neighbours alike, so any resampling shows.
int sourceCode(int x, int y, int channel) { return (x * 7 + y * 13 + channel * 85) & 255; }

int codeOf(float linear) { return int(std::lround(255.0f * srgbEncode(linear))); }

// The mini site's house with a 1024^2 texture over every face (uv0 from the face's position).
void texturiseBuilding(const std::string& dir) {
    const std::string path = dir + "/building.glb";
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    TriangleMesh house = loadGltf(path, options);
    ImageRGBA texture;
    texture.width = texture.height = kSourceSide;
    texture.texels.resize(size_t(kSourceSide) * kSourceSide * 4);
    for (int y = 0; y < kSourceSide; ++y)
        for (int x = 0; x < kSourceSide; ++x) {
            float* texel = texture.texel(x, y);
            for (int c = 0; c < 3; ++c) texel[c] = srgbDecode(float(sourceCode(x, y, c)) / 255.0f);
            texel[3] = 1.0f;
        }
    house.textures = {texture};
    house.texture_names = {"checker"};
    for (Material& material : house.materials) material.base_color_texture = 0;
    house.uv0.resize(house.positions.size());
    for (size_t v = 0; v < house.positions.size(); ++v)
        house.uv0[v] = {0.25f * (house.positions[v].x + house.positions[v].z), 0.25f * (house.positions[v].y + 1.0f)};
    writeGlb(path, house, glm::inverse(enuFromGltfYUp()));
}

ImageRGBA bakedTexture(const std::string& bake_set) {
    GltfLoadOptions options;
    options.enu_from_model = enuFromGltfYUp();
    const TriangleMesh baked = loadGltf(bake_set + "/building.glb", options);
    if (baked.textures.size() != 1) ADD_FAILURE() << "building.glb holds " << baked.textures.size() << " textures";
    return baked.textures.empty() ? ImageRGBA{} : baked.textures.front();
}

class BakeBuildingTexturesTest : public GpuTest {
protected:
    std::string bakeTexturedSite(const std::string& name, int building_texture_size) {
        const std::string dir = gusuku::testing::makeTemporaryDirectory(name);
        gusuku::testing::MiniSiteOptions site_options;
        site_options.samples_per_texel = 2;
        site_options.with_overcast_slot = false;
        gusuku::testing::writeMiniSite(dir, site_options);
        texturiseBuilding(dir);
        BakeOptions options;
        options.show_progress = false;
        options.output_dir = dir + "/out";
        if (building_texture_size > 0) options.building_texture_size = building_texture_size;
        EXPECT_TRUE(runBake(context(), loadSiteConfig(dir + "/site.json"), options).completed);
        return options.output_dir;
    }
};

TEST_F(BakeBuildingTexturesTest, BuildingGlbKeepsTheSourceTextureTexelForTexel) {
    ASSERT_GT(kDefaultBuildingTextureSize, BakeOptions{}.max_texture_size)
        << "the runtime's textures should be finer than what the tracers read";
    const ImageRGBA texture = bakedTexture(bakeTexturedSite("gusuku-building-textures", 0));
    ASSERT_EQ(texture.width, kSourceSide);
    ASSERT_EQ(texture.height, kSourceSide);
    size_t differing = 0;
    for (int y = 0; y < kSourceSide; ++y)
        for (int x = 0; x < kSourceSide; ++x)
            for (int c = 0; c < 3; ++c) differing += codeOf(texture.texel(x, y)[c]) != sourceCode(x, y, c);
    EXPECT_EQ(differing, 0u) << "of " << 3 * kSourceSide * kSourceSide << " texel channels";
}

TEST_F(BakeBuildingTexturesTest, TextureSizeOptionHoldsTheTextureToItsSide) {
    const ImageRGBA texture = bakedTexture(bakeTexturedSite("gusuku-building-textures-small", 256));
    EXPECT_EQ(texture.width, 256);
    EXPECT_EQ(texture.height, 256);
}

}  // namespace
}  // namespace gusuku::bake

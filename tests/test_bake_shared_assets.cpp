// The real assets in ../shared/data bake (issue 3): the shrine has no lightmap UVs and gets generated charts;
// the PlayCanvas house's own TEXCOORD_1 overlaps (one lightmap per mesh) and is replaced with a warning; the
// photographed skies give their sun discs to the sun. Skipped with a message when ../shared/data is absent.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_output_checks.h"
#include "gpu_test_support.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;

std::string writeSharedSite(const std::string& dir, const std::string& building, double scale) {
    const std::string data = gusuku::testing::sharedDataDir();
    const nlohmann::json site = {
        {"format", "gusuku-site/1"},
        {"site", {{"name", "shared assets"}, {"latitude_deg", 26.2856}, {"longitude_deg", 127.8008},
                  {"height_m", 160.0}, {"utc_offset", "+09:00"}}},
        {"building", {{"path", data + "/building/" + building}, {"enu_offset_m", {0.0, 0.0, 0.0}}, {"scale", scale}}},
        {"skies", {{"sunny", {{"path", data + "/env/rooitou_park_1k.hdr"}}},
                   {"overcast", {{"path", data + "/env/potsdamer_platz_1k.hdr"}}}}},
        {"bake", {{"date", "2026-03-20"},
                  {"slots", {{{"name", "morning"}, {"sky", "sunny"}, {"local_time", "09:00"}},
                             {{"name", "cloudy"}, {"sky", "overcast"}}}},
                  {"texels_per_metre", 12.0}, {"samples_per_texel", 4}, {"max_bounces", 2}, {"ground_cell_m", 0.5}}},
    };
    std::ofstream(dir + "/site.json") << site.dump(2);
    return dir + "/site.json";
}

nlohmann::json bakeAndCheck(gusuku::VulkanContext& context, const std::string& site_path, const std::string& out) {
    BakeOptions options;
    options.output_dir = out;
    options.show_progress = false;
    const BakeReport report = runBake(context, loadSiteConfig(site_path), options);
    EXPECT_TRUE(report.completed);
    EXPECT_GT(report.building_texels, 1000u);
    EXPECT_GT(gusuku::testing::expectExrImagesFinite(out), 0);
    std::ifstream manifest(out + "/manifest.json");
    return nlohmann::json::parse(manifest);
}

class BakeSharedAssetsTest : public gusuku::testing::GpuTest {};

TEST_F(BakeSharedAssetsTest, ShrineWithoutLightmapUvsBakes) {
    GUSUKU_REQUIRE_SHARED_DATA();
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-shrine");
    const nlohmann::json manifest =
        bakeAndCheck(context(), writeSharedSite(dir, "japan_temple_yankobe/scene.gltf", 1.0), dir + "/bake");
    EXPECT_NE(manifest["building"]["lightmap_uv_source"].get<std::string>().find("generated charts"), std::string::npos);
    const nlohmann::json& sun = manifest["slots"][0]["sun"];
    EXPECT_TRUE(sun["present"].get<bool>());
    EXPECT_NE(sun["irradiance_source"].get<std::string>().find("sky map sun disc"), std::string::npos)
        << "rooitou_park holds an unclipped sun";
    EXPECT_FALSE(manifest["slots"][1]["sun"]["present"].get<bool>());
}

TEST_F(BakeSharedAssetsTest, HouseWithOverlappingLightmapUvsGetsChartsAndAWarning) {
    GUSUKU_REQUIRE_SHARED_DATA();
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-house");
    const nlohmann::json manifest =
        bakeAndCheck(context(), writeSharedSite(dir, "playcanvas_house_lightmapUV/house.glb", 20.0), dir + "/bake");
    EXPECT_NE(manifest["building"]["lightmap_uv_source"].get<std::string>().find("generated charts"), std::string::npos);
    std::string warnings = manifest["warnings"].dump();
    EXPECT_NE(warnings.find("TEXCOORD_1"), std::string::npos) << warnings;
}

}  // namespace
}  // namespace gusuku::bake

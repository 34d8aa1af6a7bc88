// What a bake refuses or reports before tracing (issue 7, part A.1 and A.4), by the command line as a user
// runs it, each with a time limit so a hang fails instead of hanging: a ground grid with no ground under it
// (the SfM mesh far away, a cell larger than the site) bakes at once with empty ground terms; a building with
// no surface to bake, and buffers over the device's storage-buffer limit, are refused naming the site.json
// field; `check` says the same.
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku_bake/ground_grid.h"
#include "mini_site.h"

namespace {

namespace fs = std::filesystem;
using gusuku::testing::readTextFile;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct BakeRun {
    int exit_code = 0;
    std::string out, err;
};

BakeRun runBake(const std::string& dir, const std::vector<std::string>& args, double timeout_seconds = 60.0) {
    const pid_t pid = gusuku::testing::spawnBakeProcess(args, dir + "/run.out", dir + "/run.err");
    BakeRun run;
    run.exit_code = gusuku::testing::waitBakeProcess(pid, timeout_seconds);
    run.out = readTextFile(dir + "/run.out");
    run.err = readTextFile(dir + "/run.err");
    return run;
}

// The mini site with an SfM mesh: a flat square of half-size `ground_half_m` whose centre is at ENU
// `ground_offset_m` (metres east), and ground cells of `cell_m`.
std::string writeSiteWithSfmGround(const std::string& dir, double ground_half_m, double ground_offset_m,
                                   double cell_m) {
    gusuku::testing::writeMiniSite(dir);
    gusuku::writeGlb(dir + "/ground.glb", gusuku::bake::makeFlatGround(ground_half_m), glm::dmat4(1.0));
    nlohmann::json site = nlohmann::json::parse(readTextFile(dir + "/site.json"));
    site["sfm_mesh"] = {{"path", "ground.glb"},
                        {"scale", 1},
                        {"rotation_wxyz", {1, 0, 0, 0}},
                        {"translation_enu_m", {ground_offset_m, 0, 0}}};
    site["bake"]["ground_cell_m"] = cell_m;
    site["bake"]["samples_per_texel"] = 2;
    std::ofstream(dir + "/site.json") << site.dump(2);
    return dir + "/site.json";
}

void expectGroundTermsEmpty(const std::string& bakeset) {
    int images = 0;
    for (const auto& entry : fs::directory_iterator(bakeset)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("ground_", 0) != 0 || name == "ground_geometry.exr" || name == "ground_albedo.exr") continue;
        const gusuku::ImageRGBA image = gusuku::readImage(entry.path().string());
        for (size_t i = 3; i < image.texels.size(); i += 4) ASSERT_EQ(image.texels[i], 0.0f) << name;
        ++images;
    }
    EXPECT_EQ(images, 4) << "two slots, with and without the building";
}

TEST(BakePreflight, NoGroundCellUnderTheBuildingBakesAtOnceWithEmptyGroundTerms) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-far-ground");
    const std::string site = writeSiteWithSfmGround(dir, 5.0, 1000.0, 0.5);  // the SfM ground 1 km east
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"});
    ASSERT_NE(bake.exit_code, gusuku::testing::kTimedOut) << "the bake of an empty ground set hung";
    ASSERT_EQ(bake.exit_code, 0) << bake.err;
    EXPECT_TRUE(contains(bake.err, "ground terms will be empty")) << bake.err;
    EXPECT_TRUE(contains(bake.out, "ground:          0 cells")) << bake.out;
    expectGroundTermsEmpty(dir + "/out");

    const BakeRun check = runBake(dir, {"check", site});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    EXPECT_TRUE(contains(check.out, "lies over the SfM mesh")) << check.out;
    EXPECT_TRUE(contains(check.out, "ground terms will be empty")) << check.out;
}

TEST(BakePreflight, GroundCellLargerThanTheSiteBakesAtOnce) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-big-cell");
    // A 4 m ground under the 2 m house, cells of 100 m: the one cell's centre lies tens of metres off it.
    const std::string site = writeSiteWithSfmGround(dir, 2.0, 0.0, 100.0);
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"});
    ASSERT_NE(bake.exit_code, gusuku::testing::kTimedOut) << "the bake of an empty ground set hung";
    ASSERT_EQ(bake.exit_code, 0) << bake.err;
    EXPECT_TRUE(contains(bake.err, "1 x 1 ground grid (cell 100 m")) << bake.err;
    expectGroundTermsEmpty(dir + "/out");
}

void expectRefusedBeforeWriting(const BakeRun& run, const std::string& out_dir, const std::string& message) {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_TRUE(contains(run.err, message)) << run.err;
    if (fs::exists(out_dir)) {
        for (const auto& entry : fs::directory_iterator(out_dir)) {
            EXPECT_EQ(entry.path().filename(), ".lock") << "written before the refusal: " << entry.path();
        }
    }
}

TEST(BakePreflight, BuildingOfDegenerateTrianglesIsRefusedByBakeAndCheck) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-flat-building");
    const std::string site = gusuku::testing::writeMiniSite(dir);
    gusuku::TriangleMesh flat = gusuku::bake::makeFlatGround(1.0);
    for (glm::vec3& position : flat.positions) position.y = 0.0f;  // every triangle collapses onto a line
    gusuku::writeGlb(dir + "/building.glb", flat, glm::inverse(gusuku::enuFromGltfYUp()));
    const std::string message = "site.json: /building/path: ";
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"});
    expectRefusedBeforeWriting(bake, dir + "/out", message);
    EXPECT_TRUE(contains(bake.err, "has no surface to bake")) << bake.err;
    const BakeRun check = runBake(dir, {"check", site});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_TRUE(contains(check.err, message + dir + "/building.glb has no surface to bake")) << check.err;
}

TEST(BakePreflight, BuildingSoFarAwayThatFloatsCollapseItIsRefused) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-antipode");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    nlohmann::json site = nlohmann::json::parse(readTextFile(site_path));
    // A quarter of the way round the Earth: thousands of km east and down of the reference, where a float's
    // step is about 0.5 m on every axis, while the house, scaled down to 10 cm, is smaller than that.
    site["building"].erase("enu_offset_m");
    site["building"]["position"] = {{"latitude_deg", 26.2856}, {"longitude_deg", -142.1992}, {"height_m", 0}};
    site["building"]["scale"] = 0.05;
    std::ofstream(site_path) << site.dump(2);
    const BakeRun bake = runBake(dir, {"bake", site_path, "-o", dir + "/out", "--quiet"});
    ASSERT_NE(bake.exit_code, gusuku::testing::kTimedOut);
    expectRefusedBeforeWriting(bake, dir + "/out", "site.json: /building/path: ");
}

// A building no bake can hold is refused before any chart is cut, naming the field: charts were cut and packed at
// the requested density first, so a 1.6 km building or 1000 texels/m on a large one ran for minutes in packing
// (and building.scale 1e6 ran out of memory) before the density was lowered or the bake refused.
TEST(BakePreflight, BuildingTooLargeOrTooDenseIsRefusedBeforeItsChartsAreMade) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-huge-building");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    const nlohmann::json original = nlohmann::json::parse(readTextFile(site_path));
    const auto refusal = [&](const std::function<void(nlohmann::json&)>& change) {
        nlohmann::json site = original;
        change(site);
        std::ofstream(site_path) << site.dump(2);
        const BakeRun check = runBake(dir, {"check", site_path}, 30.0);
        EXPECT_NE(check.exit_code, gusuku::testing::kTimedOut) << "check ran past 30 s";
        EXPECT_EQ(check.exit_code, 1) << check.err;
        const BakeRun bake = runBake(dir, {"bake", site_path, "-o", dir + "/out", "--quiet"}, 30.0);
        EXPECT_FALSE(fs::exists(dir + "/out/manifest.json"));
        EXPECT_EQ(bake.exit_code, 1) << bake.err;
        // The bake refuses with check's own line.
        const std::string check_line = check.err.substr(check.err.find("site.json"));
        EXPECT_TRUE(contains(bake.err, check_line.substr(0, check_line.find('\n')))) << bake.err << check.err;
        return check.err;
    };
    const std::string huge = refusal([](nlohmann::json& site) { site["building"]["scale"] = 1e6; });
    EXPECT_TRUE(contains(huge, "site.json: /building/scale: the building spans")) << huge;
    EXPECT_TRUE(contains(huge, "more than 1e+04 m")) << huge;
    // 200 times the mini house at 1000 texels/m: far more texels than the largest lightmap can take.
    const std::string dense = refusal([](nlohmann::json& site) {
        site["building"]["scale"] = 40;
        site["bake"]["texels_per_metre"] = 1000;
    });
    EXPECT_TRUE(contains(dense, "site.json: /bake/texels_per_metre: 1000 texels/m on the building's")) << dense;
    EXPECT_TRUE(contains(dense, "more than the limit 2.684e+08 (16 x 4096^2): at most")) << dense;
}

TEST(BakePreflight, BuffersOverTheDeviceLimitAreRefusedNamingTheField) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-limits");
    gusuku::testing::MiniSiteOptions options;
    options.texels_per_metre = 40.0;  // about 38k texels: 1.8 MB of query points
    const std::string site = gusuku::testing::writeMiniSite(dir, options);
    // The mini site's sunny sky (128 x 64) needs 128 KiB of radiance; allow 1 MiB per buffer: more than the
    // texels' least estimate before charting (half of them), less than their query points.
    setenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES", "1048576", 1);
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"});
    const BakeRun check = runBake(dir, {"check", site});
    // 64 KiB: the sky is over it, and named, at the mini site's own 4 texels/m (18 KiB of query points).
    const std::string sky_dir = dir + "/sky";
    fs::create_directories(sky_dir);
    const std::string sky_site = gusuku::testing::writeMiniSite(sky_dir);
    setenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES", "65536", 1);
    const BakeRun sky_bake = runBake(sky_dir, {"bake", sky_site, "-o", sky_dir + "/out", "--quiet"});
    unsetenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES");

    const std::string texels = "site.json: /bake/texels_per_metre: building query points (";
    expectRefusedBeforeWriting(bake, dir + "/out", texels);
    EXPECT_TRUE(contains(bake.err, "over the device's maxStorageBufferRange of 1.0 MiB")) << bake.err;
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_TRUE(contains(check.err, texels)) << check.err;
    expectRefusedBeforeWriting(sky_bake, sky_dir + "/out", "site.json: /skies/sunny/path: sky radiance (128 x 64)");

    const BakeRun fits = runBake(dir, {"check", site});  // the device's own limit: everything fits
    EXPECT_EQ(fits.exit_code, 0) << fits.err;
}

// A texel density whose lightmap's query points would pass the device's buffer limit for certain is refused before
// the charts are made (issue 39 item 10): `check` of the sample house at 1000 texels/m charted and rasterised 12.8
// million texels for 246 s and 1.27 GB before the same refusal. The mini house at 1000 texels/m asks for about
// 2.4e7 texels (its 24 m^2): at least half of the 4096^2 lightmap the density is lowered to, 8.4e6 texels, 384 MiB
// of query points over a limit of 128 MiB (set here, so a GPU with a larger one refuses the same).
TEST(BakePreflight, TexelDensityOverTheDeviceLimitIsRefusedBeforeCharting) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-dense-device");
    gusuku::testing::MiniSiteOptions options;
    options.texels_per_metre = 1000.0;
    const std::string site = gusuku::testing::writeMiniSite(dir, options);
    setenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES", std::to_string(128 << 20).c_str(), 1);
    // Before charting it takes a moment; charting first took minutes: 20 s tells them apart on a loaded machine.
    const BakeRun check = runBake(dir, {"check", site}, 20.0);
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"}, 20.0);
    unsetenv("GUSUKU_MAX_STORAGE_BUFFER_BYTES");
    ASSERT_NE(check.exit_code, gusuku::testing::kTimedOut) << "check ran past 20 s";
    ASSERT_NE(bake.exit_code, gusuku::testing::kTimedOut) << "bake ran past 20 s";
    const std::string message = "site.json: /bake/texels_per_metre: 1000 texels/m on the building's ";
    EXPECT_EQ(check.exit_code, 1) << check.err;
    EXPECT_TRUE(contains(check.err, message)) << check.err;
    EXPECT_TRUE(contains(check.err, "over the device's maxStorageBufferRange of 128 MiB (refused before charting)"))
        << check.err;
    EXPECT_FALSE(contains(check.out, "lightmap:")) << "no lightmap was made: " << check.out;
    expectRefusedBeforeWriting(bake, dir + "/out", message);
}

// A NaN texture coordinate in the building's glb is the glb's fault, named by its accessor: the bake blamed its
// output folder (issue 39 item 10).
TEST(BakePreflight, NaNTexcoordInTheBuildingIsBlamedOnTheGlb) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-nan-uv");
    const std::string site = gusuku::testing::writeMiniSite(dir);
    gusuku::TriangleMesh building = gusuku::loadGltf(dir + "/building.glb", {});
    building.uv0[1].x = std::numeric_limits<float>::quiet_NaN();
    gusuku::writeGlb(dir + "/building.glb", building, glm::dmat4(1.0));
    const BakeRun bake = runBake(dir, {"bake", site, "-o", dir + "/out", "--quiet"});
    expectRefusedBeforeWriting(bake, dir + "/out", dir + "/building.glb: meshes[0].primitives[0].attributes.TEXCOORD_0: accessor ");
    EXPECT_TRUE(contains(bake.err, "vertex 1 is NaN")) << bake.err;
    const BakeRun check = runBake(dir, {"check", site});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_TRUE(contains(check.err, dir + "/building.glb: meshes[0].primitives[0].attributes.TEXCOORD_0: "))
        << check.err;
}

TEST(BakePreflight, CheckReportsSunsBelowTheHorizon) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-night");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    nlohmann::json site = nlohmann::json::parse(readTextFile(site_path));
    site["bake"]["slots"][0]["local_time"] = "23:00";
    std::ofstream(site_path) << site.dump(2);
    const BakeRun check = runBake(dir, {"check", site_path});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    EXPECT_TRUE(contains(check.out, "slot noon: the sun is below the horizon (apparent elevation -")) << check.out;
}

}  // namespace

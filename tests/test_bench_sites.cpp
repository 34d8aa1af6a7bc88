// The real-model sites of the benchmark (scripts/bench-sites.sh): gusuku-bench's --views reader and its
// --sample-results reader (bench/bench/bench_views.h), the site writer (scripts/write-bench-site.py), whose
// site.json the project's own loader must accept naming the shared files where they are, and the script's
// message when the shared data is absent. The poses are checked against the numbers written in them; the written
// sites against the placement and bake settings the writer documents.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bench_views.h"
#include "gusuku/assets/site.h"
#include "gusuku/formats/input_error.h"

namespace gusuku::bench {
namespace {

namespace fs = std::filesystem;

const fs::path kRepository = fs::path(GUSUKU_GOLDEN_DIR).parent_path().parent_path();
const fs::path kSharedData = fs::path(GUSUKU_SHARED_DATA_DIR);

struct Ran {
    int exit_status = -1;
    std::string output;  // stdout and stderr together
};

Ran runCommand(const std::string& command) {
    Ran ran;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return ran;
    char buffer[4096];
    for (size_t read; (read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) ran.output.append(buffer, read);
    const int status = pclose(pipe);
    ran.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return ran;
}

fs::path freshFolder(const std::string& name) {
    const fs::path folder = fs::temp_directory_path() / ("gusuku_test_bench_sites_" + name);
    fs::remove_all(folder);
    return folder;
}

std::string messageOf(const std::string& views) {
    try {
        parseBenchViews(views);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "(accepted)";
}

TEST(BenchViews, ReadsTheScriptsPoses) {
    const std::vector<NamedView> views = parseBenchViews("front:2,-5,3.2:2,3.5,3;corner:-5,-2.5,3.2:2,3.5,2.8:45.5");
    ASSERT_EQ(views.size(), 2u);
    EXPECT_EQ(views[0].name, "front");
    EXPECT_DOUBLE_EQ(views[0].view.position_enu.y, -5.0);
    EXPECT_DOUBLE_EQ(views[0].view.position_enu.z, 3.2);
    EXPECT_DOUBLE_EQ(views[0].view.look_at_enu.y, 3.5);
    EXPECT_DOUBLE_EQ(views[0].view.horizontal_fov_deg, 60.0);  // the default
    EXPECT_EQ(views[1].name, "corner");
    EXPECT_DOUBLE_EQ(views[1].view.position_enu.x, -5.0);
    EXPECT_DOUBLE_EQ(views[1].view.look_at_enu.z, 2.8);
    EXPECT_DOUBLE_EQ(views[1].view.horizontal_fov_deg, 45.5);
}

TEST(BenchViews, RefusesBadPosesNamingThePoseAndTheField) {
    EXPECT_EQ(messageOf(""), "--views: names no pose");
    EXPECT_EQ(messageOf("front:2,-5,3.2"), "--views: pose 1 'front:2,-5,3.2' is not NAME:E,N,U:E,N,U[:FOV]");
    EXPECT_EQ(messageOf("a:0,0,1:0,1,1;b:0,0,1:0,1"),
              "--views: pose 2 ('b'): look-at '0,1' needs three numbers E,N,U (site ENU metres)");
    EXPECT_EQ(messageOf("a:0,0x1,1:0,1,1"),
              "--views: pose 1 ('a'): position '0,0x1,1': '0x1' is not a number within [-100000, 100000] m");
    EXPECT_EQ(messageOf("a:0,0,1:0,0,1"), "--views: pose 1 ('a'): the look-at point is the camera's position");
    EXPECT_EQ(messageOf("a:0,0,1:0,1,1:170"),
              "--views: pose 1 ('a'): field of view '170' is not a number of degrees in (1, 170)");
    EXPECT_EQ(messageOf("Front:0,0,1:0,1,1"), "--views: pose 1 ('Front'): the name must be 1-32 of a-z, 0-9, _");
    EXPECT_EQ(messageOf("a:0,0,1:0,1,1;a:0,0,2:0,1,1"), "--views: pose 2 ('a'): the name is given twice");
    EXPECT_EQ(messageOf("a:0,0,1:0,1,1;"), "--views: pose 2 '' is not NAME:E,N,U:E,N,U[:FOV]");
}

TEST(BenchSampleResults, ReadsEachPosesProposedFrame) {
    const fs::path folder = freshFolder("results");
    fs::create_directories(folder);
    const fs::path good = folder / "results.json", bad = folder / "bad.json";
    std::ofstream(good) << R"({"site": {"views": [{"name": "front", "frame_1280x720": {"proposed_ms": 31.5}},
                                                   {"name": "corner", "frame_1280x720": {"proposed_ms": 28}}]}})";
    const std::map<std::string, double> frame_ms = sampleFrameTimesFrom(good.string());
    ASSERT_EQ(frame_ms.size(), 2u);
    EXPECT_DOUBLE_EQ(frame_ms.at("front"), 31.5);
    EXPECT_DOUBLE_EQ(frame_ms.at("corner"), 28.0);
    std::ofstream(bad) << R"({"site": {"views": [{"name": "front", "frame_1280x720": {"proposed_ms": "fast"}}]}})";
    try {
        sampleFrameTimesFrom(bad.string());
        FAIL() << "a frame time as text was accepted";
    } catch (const InputError& error) {
        EXPECT_EQ(error.field(), "/site/views/0/frame_1280x720/proposed_ms");
    }
    std::ofstream(bad) << R"({"timing": {}})";
    try {
        sampleFrameTimesFrom(bad.string());
        FAIL() << "a results.json without the site section was accepted";
    } catch (const InputError& error) {
        EXPECT_EQ(error.field(), "/site/views");
    }
    EXPECT_THROW(sampleFrameTimesFrom((folder / "none.json").string()), InputError);
    fs::remove_all(folder);
}

TEST(BenchSiteWriter, WritesSitesTheLoaderAcceptsNamingTheSharedFiles) {
    if (!fs::exists(kSharedData / "building/japan_temple_yankobe/scene.gltf"))
        GTEST_SKIP() << kSharedData.string() << " is absent: the shared data is not there";
    const fs::path folder = freshFolder("writer");
    ASSERT_EQ(runCommand(std::string(GUSUKU_BAKE_EXECUTABLE) + " sample " + (folder / "sample").string()).exit_status, 0);
    const SiteConfig sample = loadSiteConfig((folder / "sample/site.json").string());
    for (const std::string site : {"shrine", "house"}) {
        const fs::path written = folder / site / "site.json";
        const Ran ran = runCommand("python3 " + (kRepository / "scripts/write-bench-site.py").string() + " " +
                                   (folder / "sample/site.json").string() + " " + kSharedData.string() + " " + site +
                                   " " + written.string());
        ASSERT_EQ(ran.exit_status, 0) << ran.output;
        const SiteConfig config = loadSiteConfig(written.string());  // every file it names exists, every field valid
        const std::string building = site == "shrine" ? "building/japan_temple_yankobe/scene.gltf"
                                                      : "building/playcanvas_house_lightmapUV/house.glb";
        EXPECT_EQ(fs::canonical(config.building.path), fs::canonical(kSharedData / building));
        EXPECT_EQ(fs::canonical(config.sunny_sky.path), fs::canonical(kSharedData / "env/rooitou_park_1k.hdr"));
        ASSERT_TRUE(config.overcast_sky);
        EXPECT_EQ(fs::canonical(config.overcast_sky->path), fs::canonical(kSharedData / "env/potsdamer_platz_1k.hdr"));
        // The sample terrace, and the building where the sample house stands.
        ASSERT_TRUE(config.sfm_mesh && sample.sfm_mesh);
        EXPECT_EQ(fs::canonical(config.sfm_mesh->path), fs::canonical(sample.sfm_mesh->path));
        ASSERT_TRUE(config.building.enu_offset_m && sample.building.enu_offset_m);
        EXPECT_EQ(*config.building.enu_offset_m, *sample.building.enu_offset_m);
        EXPECT_EQ(config.building.scale, site == "shrine" ? 1.0 : 16.0);
        EXPECT_EQ(config.bake.texels_per_metre, site == "shrine" ? 16.0 : 12.0);
        EXPECT_EQ(config.bake.samples_per_texel, 192);
        // Nothing copied: the site's folder holds its site.json alone.
        EXPECT_EQ(std::distance(fs::directory_iterator(folder / site), fs::directory_iterator()), 1);
    }
    fs::remove_all(folder);
}

TEST(BenchSiteWriter, NamesTheMissingSharedFile) {
    const fs::path folder = freshFolder("writer_missing");
    ASSERT_EQ(runCommand(std::string(GUSUKU_BAKE_EXECUTABLE) + " sample " + (folder / "sample").string()).exit_status, 0);
    const Ran ran = runCommand("python3 " + (kRepository / "scripts/write-bench-site.py").string() + " " +
                               (folder / "sample/site.json").string() + " " + (folder / "no_data").string() +
                               " shrine " + (folder / "shrine/site.json").string());
    EXPECT_EQ(ran.exit_status, 1);
    EXPECT_EQ(ran.output, "write-bench-site: " + (folder / "no_data/building/japan_temple_yankobe/scene.gltf").string() +
                              ": not found (the shared data is not there)\n");
    EXPECT_FALSE(fs::exists(folder / "shrine/site.json"));
    fs::remove_all(folder);
}

TEST(BenchSitesScript, SkipsWithAMessageWhenTheSharedDataIsAbsent) {
    const fs::path folder = freshFolder("script");
    const Ran ran = runCommand("GUSUKU_SHARED_DATA=" + (folder / "no_data").string() + " bash " +
                               (kRepository / "scripts/bench-sites.sh").string() + " " + (folder / "work").string());
    EXPECT_EQ(ran.exit_status, 0) << ran.output;
    EXPECT_EQ(ran.output, "scripts/bench-sites.sh: skipping the real-model sites: " +
                              (folder / "no_data").string() +
                              "/building/japan_temple_yankobe/scene.gltf not found (the shared data is not there); "
                              "nothing run\n");
    EXPECT_FALSE(fs::exists(folder / "work"));  // nothing written
}

}  // namespace
}  // namespace gusuku::bench

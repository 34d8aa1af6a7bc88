// A bake set is complete and matching its inputs, or visibly not (issue 7, part A.2 and A.3): an output folder
// that is or holds an input is refused before anything is written; the old manifest is gone before the first
// file of a new bake replaces an old one; the input hash covers a glTF's external buffer and --no-denoise; a
// second bake into a folder being baked is refused, and a killed bake leaves no lock behind.
#include <signal.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_folder_lock.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::GpuTest;
using gusuku::testing::readTextFile;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::set<std::string> namesIn(const std::string& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) names.insert(entry.path().string());
    return names;
}

// Rewrites dir/building.glb as a .gltf whose buffer is an external file at `bin_uri` (relative to dir).
void splitBuildingIntoGltfAndBin(const std::string& dir, const std::string& bin_uri) {
    const std::string glb = readTextFile(dir + "/building.glb");
    const auto word = [&](size_t offset) {
        uint32_t value = 0;
        for (int i = 3; i >= 0; --i) value = (value << 8) | uint32_t(static_cast<unsigned char>(glb[offset + i]));
        return value;
    };
    const uint32_t json_length = word(12);
    nlohmann::json document = nlohmann::json::parse(glb.substr(20, json_length));
    const size_t bin_chunk = 20 + json_length;
    const std::string bin = glb.substr(bin_chunk + 8, word(bin_chunk));
    document["buffers"][0]["uri"] = bin_uri;
    fs::create_directories(fs::path(dir + "/" + bin_uri).parent_path());
    std::ofstream(dir + "/" + bin_uri, std::ios::binary) << bin;
    std::ofstream(dir + "/building.gltf") << document.dump();
    nlohmann::json site = nlohmann::json::parse(readTextFile(dir + "/site.json"));
    site["building"]["path"] = "building.gltf";
    std::ofstream(dir + "/site.json") << site.dump(2);
    fs::remove(dir + "/building.glb");
}

// Scales the first vertex's x in the external buffer by 0.999: a valid glTF whose .gltf text is unchanged.
void nudgeFirstPosition(const std::string& dir) {
    const nlohmann::json document = nlohmann::json::parse(readTextFile(dir + "/building.gltf"));
    const nlohmann::json& accessor =
        document["accessors"][document["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
    const nlohmann::json& view = document["bufferViews"][accessor["bufferView"].get<int>()];
    const size_t offset = view.value("byteOffset", size_t(0)) + accessor.value("byteOffset", size_t(0));
    std::string bin = readTextFile(dir + "/building.bin");
    float x = 0.0f;
    std::memcpy(&x, bin.data() + offset, sizeof x);
    x *= 0.999f;
    std::memcpy(bin.data() + offset, &x, sizeof x);
    std::ofstream(dir + "/building.bin", std::ios::binary) << bin;
}

class BakeOutputFolderTest : public GpuTest {
protected:
    BakeOptions quietOptions(const std::string& out) {
        BakeOptions options;
        options.show_progress = false;
        options.output_dir = out;
        return options;
    }
};

TEST_F(BakeOutputFolderTest, FolderThatIsOrHoldsAnInputIsRefusedBeforeWriting) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-out-holds-input");
    gusuku::testing::writeMiniSite(dir);
    splitBuildingIntoGltfAndBin(dir, "assets/building.bin");
    const SiteConfig site = loadSiteConfig(dir + "/site.json");
    const std::set<std::string> before = namesIn(dir);
    for (const std::string& out : {dir, dir + "/.", dir + "/assets", dir + "/assets/building.bin",
                                   dir + "/assets/../"}) {
        try {
            runBake(context(), site, quietOptions(out));
            ADD_FAILURE() << "baking into " << out << " was not refused";
        } catch (const InputError& error) {
            EXPECT_EQ(error.file(), out);
            EXPECT_EQ(error.field(), "-o");
            EXPECT_TRUE(contains(error.problem(), "is an input") || contains(error.problem(), "holds ")) << error.what();
        }
    }
    EXPECT_EQ(namesIn(dir), before) << "nothing was created or written";
}

TEST_F(BakeOutputFolderTest, HashCoversExternalBuffersAndDenoiseAndOldManifestGoesFirst) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-out-hash");
    gusuku::testing::MiniSiteOptions site_options;
    site_options.samples_per_texel = 2;
    gusuku::testing::writeMiniSite(dir, site_options);
    splitBuildingIntoGltfAndBin(dir, "building.bin");
    const SiteConfig site = loadSiteConfig(dir + "/site.json");
    BakeOptions options = quietOptions(dir + "/out");
    ASSERT_TRUE(runBake(context(), site, options).completed);
    ASSERT_TRUE(runBake(context(), site, options).up_to_date);

    options.denoise = false;
    const BakeReport undenoised = runBake(context(), site, options);
    EXPECT_FALSE(undenoised.up_to_date) << "--no-denoise changes the output, so the hash";
    EXPECT_TRUE(undenoised.completed);

    nudgeFirstPosition(dir);  // building.gltf and site.json unchanged
    const std::string old_manifest = readTextFile(dir + "/out/manifest.json");
    ASSERT_FALSE(old_manifest.empty());
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 2; };  // after the first traced chunk
    const BakeReport stopped = runBake(context(), site, options);
    EXPECT_FALSE(stopped.up_to_date) << "the hash covers the glTF's external buffer";
    EXPECT_FALSE(stopped.completed);
    EXPECT_FALSE(fs::exists(dir + "/out/manifest.json"))
        << "an interrupted rebake left the old manifest over new files";
    options.should_stop = nullptr;
    ASSERT_TRUE(runBake(context(), site, options).completed);
    EXPECT_NE(readTextFile(dir + "/out/manifest.json"), old_manifest);
}

TEST_F(BakeOutputFolderTest, LockedFolderIsRefused) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-out-lock");
    const SiteConfig site = loadSiteConfig(gusuku::testing::writeMiniSite(dir));
    {
        const BakeFolderLock held(dir + "/out");
        try {
            runBake(context(), site, quietOptions(dir + "/out"));
            ADD_FAILURE() << "a second bake into a locked folder was not refused";
        } catch (const InputError& error) {
            EXPECT_TRUE(contains(error.what(), "another gusuku-bake is baking into this folder")) << error.what();
        }
    }
    EXPECT_TRUE(runBake(context(), site, quietOptions(dir + "/out")).completed) << "the lock is released";
}

// Two real processes: the second bake is refused while the first runs; once the first is killed (SIGKILL, no
// clean-up), a third bake runs and finishes.
TEST(BakeFolderLockProcess, SecondBakeRefusedAndKilledBakeLeavesNoLock) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-two-bakes");
    const std::string site = gusuku::testing::writeMiniSite(dir);
    const std::string out = dir + "/out";
    const pid_t first =
        gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet", "--samples", "100000"});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!(fs::exists(out + "/.checkpoint") && !fs::is_empty(out + "/.checkpoint")) &&
           std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const pid_t second = gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet"}, "/dev/null",
                                                           dir + "/second.err");
    const int second_exit = gusuku::testing::waitBakeProcess(second, 60);
    kill(first, SIGKILL);
    const int first_exit = gusuku::testing::waitBakeProcess(first, 60);
    if (first_exit == 0) GTEST_SKIP() << "the first bake finished before the second started";
    EXPECT_EQ(second_exit, 1);
    EXPECT_TRUE(contains(readTextFile(dir + "/second.err"), "another gusuku-bake is baking into this folder"))
        << readTextFile(dir + "/second.err");
    const pid_t third = gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet", "--samples", "8"});
    EXPECT_EQ(gusuku::testing::waitBakeProcess(third, 120), 0) << "the killed bake left the folder locked";
}

}  // namespace
}  // namespace gusuku::bake

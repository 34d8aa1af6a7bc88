// Bit-identical means bytes (issue 7, part A.6): two bakes of the same inputs, and a bake stopped and resumed,
// write byte-identical files, headers included (no write time, no software version that could differ). The
// one exception is the manifest's "statistics" (this run's rays and seconds), compared separately.
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::GpuTest;
using gusuku::testing::readTextFile;

// Relative path -> bytes, for every regular file under dir.
std::map<std::string, std::string> filesUnder(const std::string& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file())
            files[fs::relative(entry.path(), dir).string()] = readTextFile(entry.path().string());
    return files;
}

nlohmann::json manifestWithoutStatistics(const std::string& text) {
    nlohmann::json manifest = nlohmann::json::parse(text);
    manifest.erase("statistics");
    return manifest;
}

void expectSameBytes(const std::string& expected_dir, const std::string& actual_dir) {
    const auto expected = filesUnder(expected_dir);
    const auto actual = filesUnder(actual_dir);
    std::vector<std::string> expected_names, actual_names;
    for (const auto& [name, bytes] : expected) expected_names.push_back(name);
    for (const auto& [name, bytes] : actual) actual_names.push_back(name);
    ASSERT_EQ(expected_names, actual_names);
    int exr_count = 0;
    for (const auto& [name, bytes] : expected) {
        if (name == "manifest.json") {
            EXPECT_EQ(manifestWithoutStatistics(bytes), manifestWithoutStatistics(actual.at(name)));
            continue;
        }
        exr_count += fs::path(name).extension() == ".exr";
        const std::string& other = actual.at(name);
        ASSERT_EQ(bytes.size(), other.size()) << name;
        const auto mismatch = std::mismatch(bytes.begin(), bytes.end(), other.begin());
        EXPECT_TRUE(mismatch.first == bytes.end())
            << name << ": first differing byte at offset " << (mismatch.first - bytes.begin()) << " of "
            << bytes.size();
    }
    EXPECT_GE(exr_count, 7) << "ground geometry and two slots of three images each";
}

class BakeBytesTest : public GpuTest {};

TEST_F(BakeBytesTest, RepeatedAndResumedBakesWriteIdenticalBytes) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-bytes");
    const SiteConfig site = gusuku::testing::loadMiniSite(dir, 4);

    BakeOptions options = gusuku::testing::stoppableBakeOptions(dir + "/first");
    ASSERT_TRUE(runBake(context(), site, options).completed);
    options.output_dir = dir + "/second";
    ASSERT_TRUE(runBake(context(), site, options).completed);
    expectSameBytes(dir + "/first", dir + "/second");

    options.output_dir = dir + "/resumed";
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 7; };
    ASSERT_FALSE(runBake(context(), site, options).completed);
    options.should_stop = nullptr;
    const BakeReport resumed = runBake(context(), site, options);
    ASSERT_TRUE(resumed.completed);
    EXPECT_GT(resumed.resumed_fraction, 0.0);
    expectSameBytes(dir + "/first", dir + "/resumed");
}

}  // namespace
}  // namespace gusuku::bake

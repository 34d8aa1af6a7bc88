// `gusuku-bake init` (issue 42 item 5): the starter site.json is valid as written (with the sample's four files put
// beside it under the names it gives, `check` passes, so its comments and fields are what the site reader takes),
// it holds the place and the day given, and bad or missing values and an existing site.json are refused with
// nothing written.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_command.h"
#include "gusuku/assets/site.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
using testing::runBakeCommand;

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

class BakeInitTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("gusuku_init_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    testing::CommandResult init(const std::string& folder, std::vector<std::string> extra = {}) {
        std::vector<std::string> args = {"init", folder, "--lat", "26.2856", "--lon", "127.8008", "--height", "160",
                                         "--utc-offset", "+09:00", "--date", "2026-06-21", "--name", "Terrace \"A\""};
        args.insert(args.end(), extra.begin(), extra.end());
        return runBakeCommand(args, dir_.string());
    }
    fs::path dir_;
};

TEST_F(BakeInitTest, TheStarterBesideTheSamplesFilesPassesCheck) {
    const fs::path site = dir_ / "site";
    ASSERT_EQ(runBakeCommand({"sample", (dir_ / "sample").string()}, dir_.string()).exit_code, 0);
    const testing::CommandResult written = init(site.string());
    ASSERT_EQ(written.exit_code, 0) << written.stderr_text;
    const std::string text = readFile(site / "site.json");
    EXPECT_NE(text.find("// "), std::string::npos) << "the starter explains its fields in comments";
    EXPECT_TRUE(fs::is_regular_file(site / "CHECKLIST.md"));
    // Without its files, check names the first one missing: the JSON and its fields were read up to there.
    const testing::CommandResult bare = runBakeCommand({"check", (site / "site.json").string()}, dir_.string());
    EXPECT_EQ(bare.exit_code, 1);
    EXPECT_NE(bare.stderr_text.find("file not found"), std::string::npos) << bare.stderr_text;
    for (const char* file : {"building.glb", "site.glb", "sky_sunny.hdr", "sky_overcast.hdr"})
        fs::copy_file(dir_ / "sample" / file, site / file);
    const testing::CommandResult checked = runBakeCommand({"check", (site / "site.json").string()}, dir_.string());
    EXPECT_EQ(checked.exit_code, 0) << checked.stderr_text;
    // The place and the day given, as the site reader takes them.
    const SiteConfig config = loadSiteConfig((site / "site.json").string());
    EXPECT_EQ(config.site.name, "Terrace \"A\"");
    EXPECT_DOUBLE_EQ(config.site.reference.latitude_deg, 26.2856);
    EXPECT_DOUBLE_EQ(config.site.reference.longitude_deg, 127.8008);
    EXPECT_DOUBLE_EQ(config.site.reference.height_m, 160.0);
    EXPECT_EQ(config.site.utc_offset_minutes, 9 * 60);
    EXPECT_EQ(config.bake.date, "2026-06-21");
}

TEST_F(BakeInitTest, BadValuesAndAnExistingSiteJsonAreRefusedWithNothingWritten) {
    const fs::path site = dir_ / "site";
    struct Case {
        std::vector<std::string> args;
        int exit_code;
        const char* message;
    };
    const Case cases[] = {
        {{"init", site.string(), "--lat", "200", "--lon", "1", "--height", "0", "--utc-offset", "+09:00", "--date",
          "2026-06-21"}, 1, "--lat: 200 is outside [-90, 90]"},
        {{"init", site.string(), "--lat", "20", "--lon", "1", "--height", "0", "--utc-offset", "+15:00", "--date",
          "2026-06-21"}, 1, "--utc-offset: '+15:00' is not"},
        {{"init", site.string(), "--lat", "20", "--lon", "1", "--height", "0", "--utc-offset", "+09:00", "--date",
          "2026-02-30"}, 1, "--date: '2026-02-30' is not a calendar day"},
        {{"init", site.string(), "--lon", "1", "--height", "0", "--utc-offset", "+09:00", "--date", "2026-06-21"}, 2,
         "--lat is missing"},
    };
    for (const Case& bad : cases) {
        const testing::CommandResult result = runBakeCommand(bad.args, dir_.string());
        EXPECT_EQ(result.exit_code, bad.exit_code) << result.stderr_text;
        EXPECT_NE(result.stderr_text.find(bad.message), std::string::npos) << result.stderr_text;
        EXPECT_FALSE(fs::exists(site / "site.json"));
    }
    ASSERT_EQ(init(site.string()).exit_code, 0);
    std::ofstream(site / "site.json") << "{\"mine\": true}";
    const testing::CommandResult again = init(site.string());
    EXPECT_EQ(again.exit_code, 1);
    EXPECT_NE(again.stderr_text.find("already exists; nothing written"), std::string::npos) << again.stderr_text;
    EXPECT_EQ(readFile(site / "site.json"), "{\"mine\": true}");
    EXPECT_EQ(init(site.string(), {"--force"}).exit_code, 0);
    EXPECT_NE(readFile(site / "site.json").find("gusuku-site/1"), std::string::npos);
}

}  // namespace
}  // namespace gusuku

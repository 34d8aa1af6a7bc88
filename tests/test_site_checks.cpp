// Placement checks (issue 42 items 3, 4): `gusuku-bake preview` and `check` warn, naming the file, the field and
// the value to set, when the building floats 1 m above or is sunk 1 m into the site mesh's ground, when the site
// mesh is Y-up (the mini site's own Y-up glTF with the identity rotation: the fix must be the quarter turn the mini
// site uses), and when the sky's sun (painted into an HDR at the SPA sun of a known time, with a known north) is not
// where the computed sun is; "auto" north gives that known north back. Bad values are refused with nothing written.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_command.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/sky_sun.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "mini_site.h"
#include "test_meshes.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
using testing::runBakeCommand;

// The painted sky's north: any value not a multiple of 90, so a swapped sign or axis shows.
constexpr double kTrueNorthDeg = 73.0;
constexpr const char* kTakenAt = "2026-06-21T10:30+09:00";

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void replaceOnce(std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
}

// A dim sky with a sun of 3 x 3 bright texels where the computed sun stands at kTakenAt, seen with kTrueNorthDeg.
ImageRGBA paintedSunSky(const SiteConfig& config, int width) {
    ImageRGBA sky;
    sky.width = width;
    sky.height = width / 2;
    sky.texels.assign(size_t(sky.width) * sky.height * 4, 0.2f);
    const SunPosition sun = computeSunPosition(config.site.sunObserver(), parseIso8601Utc(kTakenAt));
    const glm::dvec2 uv = equirectCoordinates(sun.direction_enu, kTrueNorthDeg);
    const int cx = int(uv.x * sky.width), cy = int(uv.y * sky.height);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            float* texel = sky.texel((cx + dx + sky.width) % sky.width, cy + dy);
            texel[0] = texel[1] = texel[2] = 5000.0f;
        }
    return sky;
}

class SiteChecksTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("gusuku_site_checks_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        testing::MiniSiteOptions options;
        options.with_sfm_mesh = true;
        site_ = testing::writeMiniSite(dir_.string(), options);
        original_ = readFile(site_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    void writeSite(const std::string& text) { std::ofstream(site_, std::ios::binary) << text; }
    testing::CommandResult preview(const std::string& out = "preview") {
        return runBakeCommand({"preview", site_, "-o", (dir_ / out).string(), "--size", "96"}, dir_.string());
    }
    // The sunny sky replaced by the painted one, with these extra fields (north, taken_at).
    void usePaintedSky(const std::string& sky_fields) {
        writeSite(original_);
        writeHdr((dir_ / "sky_painted.hdr").string(), paintedSunSky(loadSiteConfig(site_), 512));
        std::string text = original_;
        replaceOnce(text, R"("sunny": {"path": "sky_sunny.hdr"})",
                    R"("sunny": {"path": "sky_painted.hdr")" + sky_fields + "}");
        writeSite(text);
    }
    fs::path dir_;
    std::string site_, original_;
};

TEST_F(SiteChecksTest, ABuildingOneMetreAboveOrBelowTheGroundIsNamedWithTheHeightThatPutsItOnTheGround) {
    // The mini site's building stands on its ground (z = 0): no placement warning.
    testing::CommandResult placed = preview();
    ASSERT_EQ(placed.exit_code, 0) << placed.stderr_text;
    EXPECT_NE(placed.stdout_text.find("building's base: 0.00 m"), std::string::npos) << placed.stdout_text;
    EXPECT_NE(placed.stdout_text.find("warnings: 0"), std::string::npos) << placed.stdout_text;

    std::string text = original_;
    replaceOnce(text, R"("enu_offset_m": [0, 0, 0])", R"("enu_offset_m": [0, 0, 1])");
    writeSite(text);
    const testing::CommandResult floating = preview();
    ASSERT_EQ(floating.exit_code, 0) << floating.stderr_text;
    EXPECT_NE(floating.stdout_text.find(site_ + ": /building/enu_offset_m: the building floats: its base stands "
                                                "1.00 m above the site mesh's ground"),
              std::string::npos)
        << floating.stdout_text;
    EXPECT_NE(floating.stdout_text.find("set enu_offset_m's up (third number) to 0.00 (now 1.00)"), std::string::npos);
    EXPECT_EQ(readFile(dir_ / "preview" / "checks.txt"), floating.stdout_text.substr(0, floating.stdout_text.find("wrote ")));
    // check prints the same warning (one code for both).
    const testing::CommandResult checked = runBakeCommand({"check", site_}, dir_.string());
    EXPECT_EQ(checked.exit_code, 0) << checked.stderr_text;
    EXPECT_NE(checked.stdout_text.find("/building/enu_offset_m: the building floats"), std::string::npos)
        << checked.stdout_text;

    text = original_;
    replaceOnce(text, R"("enu_offset_m": [0, 0, 0])", R"("enu_offset_m": [0, 0, -1])");
    writeSite(text);
    const testing::CommandResult sunk = preview();
    EXPECT_NE(sunk.stdout_text.find("the building is sunk: its base stands 1.00 m below"), std::string::npos)
        << sunk.stdout_text;
    EXPECT_NE(sunk.stdout_text.find("to 0.00 (now -1.00)"), std::string::npos);

    // Within the 0.25 m tolerance (a plinth, the mesh's noise): nothing.
    text = original_;
    replaceOnce(text, R"("enu_offset_m": [0, 0, 0])", R"("enu_offset_m": [0, 0, 0.2])");
    writeSite(text);
    EXPECT_NE(preview().stdout_text.find("warnings: 0"), std::string::npos);
}

TEST_F(SiteChecksTest, AYUpSiteMeshGetsTheQuarterTurnThatStandsItUp) {
    std::string text = original_;
    replaceOnce(text, R"("rotation_wxyz": [0.7071067811865476, 0.7071067811865476, 0, 0])",
                R"("rotation_wxyz": [1, 0, 0, 0])");
    writeSite(text);
    const testing::CommandResult result = preview();
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    // glTF files are Y-up: with no rotation the ground faces north, and the fix is the mini site's own rotation.
    EXPECT_NE(result.stdout_text.find(site_ + ": /sfm_mesh/rotation_wxyz: the site mesh's ground faces face north"),
              std::string::npos)
        << result.stdout_text;
    EXPECT_NE(result.stdout_text.find("set rotation_wxyz to [0.7071, 0.7071, 0.0000, 0.0000]"), std::string::npos)
        << result.stdout_text;
    // A mesh on its side has no ground under the building: no base warning built on it.
    EXPECT_EQ(result.stdout_text.find("the building floats"), std::string::npos);
}

TEST_F(SiteChecksTest, TheSunInTheSkyFindsItsKnownNorth) {
    // findSkySun on the painted map: the sun's column gives back the painted north within a texel (0.7 deg).
    const SiteConfig config = loadSiteConfig(site_);
    const SkySunSighting seen = findSkySun(paintedSunSky(config, 512));
    ASSERT_TRUE(seen.found);
    const SunPosition sun = computeSunPosition(config.site.sunObserver(), parseIso8601Utc(kTakenAt));
    EXPECT_NEAR(northAzimuthInImageFromSun(seen.image_azimuth_deg, sun.azimuth_deg), kTrueNorthDeg, 0.71);
    EXPECT_NEAR(seen.elevation_deg, sun.apparent_elevation_deg, 0.71);
    EXPECT_FALSE(findSkySun(testing::uniformSky(64, 32, glm::vec3(1.0f))).found) << "a sunless sky has no sun";
    // A clipped sun (an 8-bit photo's flat top: 5 x 5 texels at the clip, the sky at a third of it) is found too.
    ImageRGBA clipped = paintedSunSky(config, 512);
    const glm::dvec2 uv = equirectCoordinates(sun.direction_enu, kTrueNorthDeg);
    for (float& value : clipped.texels) value = std::min(value, 0.3f);
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
            float* texel = clipped.texel(int(uv.x * 512) + dx, int(uv.y * 256) + dy);
            texel[0] = texel[1] = texel[2] = 1.0f;
        }
    const SkySunSighting clipped_seen = findSkySun(clipped);
    ASSERT_TRUE(clipped_seen.found);
    EXPECT_NEAR(northAzimuthInImageFromSun(clipped_seen.image_azimuth_deg, sun.azimuth_deg), kTrueNorthDeg, 0.71);

    // "auto" resolves at load to the painted north.
    usePaintedSky(std::string(R"(, "north_azimuth_in_image_deg": "auto", "taken_at": ")") + kTakenAt + "\"");
    EXPECT_NEAR(loadSiteConfig(site_).sunny_sky.north_azimuth_in_image_deg, kTrueNorthDeg, 0.71);
    EXPECT_NE(preview().stdout_text.find("north from the sun at taken_at"), std::string::npos);

    // North given as 0 with taken_at: the warning offers the painted north, and the angle.
    usePaintedSky(std::string(R"(, "north_azimuth_in_image_deg": 0, "taken_at": ")") + kTakenAt + "\"");
    const testing::CommandResult wrong = preview();
    ASSERT_EQ(wrong.exit_code, 0) << wrong.stderr_text;
    const std::regex offered(": /skies/sunny/north_azimuth_in_image_deg: .* stands ([0-9.]+) deg from the computed "
                             "sun at .*: set north_azimuth_in_image_deg to ([0-9.]+) \\(now 0.00\\)");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(wrong.stdout_text, match, offered)) << wrong.stdout_text;
    EXPECT_NEAR(std::stod(match[2]), kTrueNorthDeg, 0.71);
    EXPECT_GT(std::stod(match[1]), 10.0);
    // The right north (as a number): no warning.
    usePaintedSky(std::string(R"(, "north_azimuth_in_image_deg": 73, "taken_at": ")") + kTakenAt + "\"");
    EXPECT_NE(preview().stdout_text.find("warnings: 0"), std::string::npos);
    // Without taken_at, the sun's path on bake.date (the same day) still shows a north 73 deg off.
    usePaintedSky(R"(, "north_azimuth_in_image_deg": 0)");
    EXPECT_NE(preview().stdout_text.find("deg from the nearest point of the sun's path on 2026-06-21"),
              std::string::npos);
}

TEST_F(SiteChecksTest, BadNorthAndTakenAtAreRefusedWithNothingWritten) {
    struct Case {
        std::string fields;
        std::string message;
    };
    const Case cases[] = {
        {R"(, "north_azimuth_in_image_deg": "auto")", "/skies/sunny/north_azimuth_in_image_deg: \"auto\" needs taken_at"},
        {R"(, "north_azimuth_in_image_deg": "north")", "/skies/sunny/north_azimuth_in_image_deg: \"north\" is not a number"},
        {R"(, "taken_at": "2026-06-21 10:30")", "/skies/sunny/taken_at: \"2026-06-21 10:30\" is not a time of the form"},
        // Three hours off: the painted sun is 20-odd degrees lower than the computed one.
        {R"(, "north_azimuth_in_image_deg": "auto", "taken_at": "2026-06-21T13:30+09:00")",
         "/skies/sunny/taken_at: the sun in the sky stands at elevation"},
    };
    for (const Case& bad : cases) {
        usePaintedSky(bad.fields);
        const testing::CommandResult result = preview("refused");
        EXPECT_EQ(result.exit_code, 1) << bad.fields;
        EXPECT_NE(result.stderr_text.find(site_ + ": " + bad.message.substr(0, bad.message.find(':')) + ":"),
                  std::string::npos)
            << result.stderr_text;
        EXPECT_NE(result.stderr_text.find(bad.message), std::string::npos) << result.stderr_text;
        EXPECT_FALSE(fs::exists(dir_ / "refused"));
    }
    // "auto" on a sky without a sun.
    std::string text = original_;
    replaceOnce(text, R"("sunny": {"path": "sky_sunny.hdr"})",
                std::string(R"("sunny": {"path": "sky_sunny.hdr", "north_azimuth_in_image_deg": "auto", "taken_at": ")") +
                    kTakenAt + "\"}");
    writeSite(text);
    const testing::CommandResult sunless = preview("refused");
    EXPECT_EQ(sunless.exit_code, 1);
    EXPECT_NE(sunless.stderr_text.find("\"auto\" found no sun in the sky"), std::string::npos) << sunless.stderr_text;
    EXPECT_EQ(runBakeCommand({"preview", site_}, dir_.string()).exit_code, 2) << "-o is required";
}

TEST_F(SiteChecksTest, PreviewDrawsTheBuildingFromAboveAndFromAVisitorsEye) {
    const testing::CommandResult result = preview();
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    const ImageRGBA top = readImage((dir_ / "preview" / "top.png").string());
    const ImageRGBA view = readImage((dir_ / "preview" / "view.png").string());
    EXPECT_EQ(top.width, 96);
    EXPECT_EQ(top.height, 96);
    EXPECT_EQ(view.width, 96);
    EXPECT_EQ(view.height, 54);
    // The building (2 m, at the site's origin, 10 pixels across) fills the top view's centre in its orange, beside
    // the cyan heading line that starts there; the grey ground away from it.
    const float* centre = top.texel(45, 51);
    EXPECT_GT(centre[0], 1.3f * centre[2]) << "building orange at the centre";
    const float* corner = top.texel(88, 88);
    EXPECT_NEAR(corner[0], corner[2], 0.05f) << "grey ground away from it";
    const float* middle = view.texel(48, 30);
    EXPECT_GT(middle[0], 1.3f * middle[2]) << "the building in the middle of the visitor's view";
}

}  // namespace
}  // namespace gusuku

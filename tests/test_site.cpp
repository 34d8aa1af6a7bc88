// loadSiteConfig: a valid site.json with its defaults, one test per kind of error (each checks the file, the
// JSON pointer and that the problem says what is wrong), and the building / SfM placement transforms.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>


#include <sys/stat.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "gpu_test_support.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;


// 2026-06-21T00:00:00Z in Unix seconds (20625 days after 1970-01-01: 56 years, 14 leap days, 171 days into 2026).
constexpr double kJune21_2026_Utc = 1782000000.0;

class SiteJson : public ::testing::Test {
protected:
    void SetUp() override {
        directory_ = gusuku::testing::makeTemporaryDirectory("test_site");
        // The loader only checks that referenced files exist, so small placeholders stand in for them.
        for (const char* name : {"building.glb", "site.glb", "sky.hdr", "sky_overcast.exr"})
            std::ofstream(fs::path(directory_) / name) << "placeholder";
        document_ = json::parse(R"({
            "format": "gusuku-site/1",
            "site": {"name": "Shuri test", "latitude_deg": 26.217, "longitude_deg": 127.7195, "height_m": 120,
                     "utc_offset": "+09:00"},
            "sfm_mesh": {"path": "site.glb", "scale": 1, "rotation_wxyz": [1, 0, 0, 0],
                         "translation_enu_m": [0, 0, 0]},
            "building": {"path": "building.glb", "enu_offset_m": [0, 0, 0]},
            "skies": {"sunny": {"path": "sky.hdr"}, "overcast": {"path": "sky_overcast.exr"}},
            "bake": {"date": "2026-06-21"}
        })");
    }

    std::string sitePath() const { return (fs::path(directory_) / "site.json").string(); }

    std::string writeText(const std::string& text) const {
        std::ofstream(sitePath(), std::ios::binary | std::ios::trunc) << text;
        return sitePath();
    }

    gusuku::SiteConfig load() const { return gusuku::loadSiteConfig(writeText(document_.dump(2))); }

    /// Loads `text` (default: the current document) and returns the InputError it must throw.
    gusuku::InputError loadError(const std::string& text = "") const {
        const std::string path = writeText(text.empty() ? document_.dump(2) : text);
        try {
            gusuku::loadSiteConfig(path);
        } catch (const gusuku::InputError& error) {
            EXPECT_EQ(error.file(), path);
            return error;
        }
        ADD_FAILURE() << "loadSiteConfig accepted an invalid site.json";
        return gusuku::InputError(path, "", "no error");
    }

    std::string directory_;
    json document_;
};

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

TEST_F(SiteJson, ValidFileWithDefaults) {
    const gusuku::SiteConfig config = load();
    EXPECT_EQ(config.file, sitePath());
    EXPECT_EQ(config.site.name, "Shuri test");
    EXPECT_DOUBLE_EQ(config.site.reference.latitude_deg, 26.217);
    EXPECT_DOUBLE_EQ(config.site.reference.longitude_deg, 127.7195);
    EXPECT_DOUBLE_EQ(config.site.reference.height_m, 120.0);
    EXPECT_EQ(config.site.utc_offset_minutes, 9 * 60);
    EXPECT_LT(config.site.pressure_mbar, 0.0);  // standard atmosphere
    EXPECT_DOUBLE_EQ(config.site.temperature_c, 15.0);

    // Paths are stored absolute, resolved against site.json's folder.
    EXPECT_EQ(fs::path(config.building.path), fs::absolute(fs::path(directory_) / "building.glb").lexically_normal());
    EXPECT_TRUE(fs::path(config.sunny_sky.path).is_absolute());
    ASSERT_TRUE(config.sfm_mesh.has_value());
    EXPECT_TRUE(fs::path(config.sfm_mesh->path).is_absolute());
    ASSERT_TRUE(config.overcast_sky.has_value());
    EXPECT_DOUBLE_EQ(config.sunny_sky.north_azimuth_in_image_deg, 0.0);

    EXPECT_DOUBLE_EQ(config.building.heading_deg, 0.0);
    EXPECT_DOUBLE_EQ(config.building.scale, 1.0);
    EXPECT_FALSE(config.building.position.has_value());
    ASSERT_TRUE(config.building.enu_offset_m.has_value());

    const gusuku::BakeSettings& bake = config.bake;
    EXPECT_EQ(bake.date, "2026-06-21");
    EXPECT_DOUBLE_EQ(bake.texels_per_metre, 8.0);
    EXPECT_EQ(bake.samples_per_texel, 256);
    EXPECT_EQ(bake.max_bounces, 4);
    EXPECT_EQ(bake.seed, 1u);
    EXPECT_DOUBLE_EQ(bake.ground_cell_m, 0.25);

    ASSERT_EQ(bake.slots.size(), 4u);
    EXPECT_EQ(bake.slots[0].name, "sunny_0900");
    EXPECT_EQ(bake.slots[1].name, "sunny_1200");
    EXPECT_EQ(bake.slots[2].name, "sunny_1500");
    EXPECT_EQ(bake.slots[3].name, "overcast");
    EXPECT_EQ(bake.slots[0].sky, gusuku::SlotSky::Sunny);
    EXPECT_EQ(bake.slots[3].sky, gusuku::SlotSky::Overcast);
    EXPECT_EQ(bake.slots[0].local_time, "09:00");
    EXPECT_TRUE(bake.slots[3].local_time.empty());
    // 09:00 at +09:00 is 00:00 UTC on the same day.
    EXPECT_DOUBLE_EQ(bake.slots[0].utc_seconds, kJune21_2026_Utc);
    EXPECT_DOUBLE_EQ(bake.slots[1].utc_seconds, kJune21_2026_Utc + 3 * 3600.0);
    EXPECT_DOUBLE_EQ(bake.slots[2].utc_seconds, kJune21_2026_Utc + 6 * 3600.0);
}

TEST_F(SiteJson, ExplicitSettingsAndSlots) {
    document_["site"]["utc_offset"] = "-03:30";
    document_["site"]["pressure_mbar"] = 1013.25;
    document_["site"]["temperature_c"] = 28;
    document_["bake"] = json::parse(R"({"date": "2026-12-31", "texels_per_metre": 16, "samples_per_texel": 1e3,
        "max_bounces": 0, "seed": 4294967295, "ground_cell_m": 0.5,
        "slots": [{"name": "late", "sky": "sunny", "local_time": "22:30"}, {"name": "grey", "sky": "overcast"}]})");
    const gusuku::SiteConfig config = load();
    EXPECT_EQ(config.site.utc_offset_minutes, -210);
    EXPECT_DOUBLE_EQ(config.site.pressure_mbar, 1013.25);
    EXPECT_DOUBLE_EQ(config.site.temperature_c, 28.0);
    EXPECT_EQ(config.bake.samples_per_texel, 1000);
    EXPECT_EQ(config.bake.max_bounces, 0);
    EXPECT_EQ(config.bake.seed, 4294967295u);
    ASSERT_EQ(config.bake.slots.size(), 2u);
    // 22:30 at -03:30 is 02:00 UTC the next day: 2027-01-01T02:00:00Z = 1798768800 (Unix seconds).
    EXPECT_DOUBLE_EQ(config.bake.slots[0].utc_seconds, 1798768800.0);
    EXPECT_EQ(config.bake.slots[1].sky, gusuku::SlotSky::Overcast);
}

TEST_F(SiteJson, DefaultSlotsOmitOvercastWithoutAnOvercastSky) {
    document_["skies"].erase("overcast");
    const gusuku::SiteConfig config = load();
    ASSERT_EQ(config.bake.slots.size(), 3u);
    for (const gusuku::BakeSlot& slot : config.bake.slots) EXPECT_EQ(slot.sky, gusuku::SlotSky::Sunny);
}

TEST_F(SiteJson, MissingFile) {
    const std::string path = (fs::path(directory_) / "absent.json").string();
    try {
        gusuku::loadSiteConfig(path);
        FAIL() << "no error for a missing site.json";
    } catch (const gusuku::InputError& error) {
        EXPECT_EQ(error.file(), path);
        EXPECT_EQ(error.field(), "");
        EXPECT_TRUE(contains(error.problem(), "not found"));
    }
}

TEST_F(SiteJson, InvalidJsonNamesTheByte) {
    // The stray second comma is the 9th byte (1-based): the parser stops there.
    const gusuku::InputError error = loadError(R"({"a": 1,, "b": 2})");
    EXPECT_EQ(error.field(), "byte 9");
    EXPECT_TRUE(contains(error.problem(), "invalid JSON"));
}

TEST_F(SiteJson, DuplicateKeyIsAnError) {
    const gusuku::InputError error = loadError(
        R"({"format": "gusuku-site/1", "site": {"name": "a", "name": "b"}})");
    EXPECT_EQ(error.field(), "/site/name");
    EXPECT_TRUE(contains(error.problem(), "twice"));
}

TEST_F(SiteJson, MissingRequiredField) {
    document_["site"].erase("latitude_deg");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/site/latitude_deg");
    EXPECT_TRUE(contains(error.problem(), "missing"));
}

TEST_F(SiteJson, WrongType) {
    document_["site"]["name"] = 5;
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/site/name");
    EXPECT_TRUE(contains(error.problem(), "expected a string, found a number"));
}

TEST_F(SiteJson, LatitudeOutOfRange) {
    document_["site"]["latitude_deg"] = 200;
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/site/latitude_deg");
    EXPECT_EQ(error.problem(), "200 is outside [-90, 90]");
}

TEST_F(SiteJson, LongitudeOutOfRange) {
    document_["building"].erase("enu_offset_m");
    document_["building"]["position"] = {{"latitude_deg", 26.2}, {"longitude_deg", -181}, {"height_m", 0}};
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/position/longitude_deg");
    EXPECT_EQ(error.problem(), "-181 is outside [-180, 180]");
}

TEST_F(SiteJson, StringWhereANumberGoes) {
    document_["site"]["height_m"] = "NaN";
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/site/height_m");
    EXPECT_TRUE(contains(error.problem(), "expected a number, found a string"));
}

TEST_F(SiteJson, OverflowingNumberIsNotFinite) {
    // JSON has no infinity, but 1e999 overflows a double (nlohmann 3.11 refuses it rather than returning inf;
    // either way the error must name the field). Written by hand: the serialiser cannot write it.
    document_["bake"]["ground_cell_m"] = 0.123456;
    std::string text = document_.dump(2);
    text.replace(text.find("0.123456"), 8, "1e999");
    const gusuku::InputError error = loadError(text);
    EXPECT_EQ(error.field(), "/bake/ground_cell_m");
    EXPECT_TRUE(contains(error.problem(), "not a finite number"));
}

TEST_F(SiteJson, UnknownTopLevelField) {
    document_["colour"] = "red";
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/colour");
    EXPECT_TRUE(contains(error.problem(), "unknown field"));
}

TEST_F(SiteJson, UnknownNestedField) {
    document_["building"]["headng_deg"] = 90;  // a typo must not silently fall back to the default heading
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/headng_deg");
    EXPECT_TRUE(contains(error.problem(), "unknown field"));
    EXPECT_TRUE(contains(error.problem(), "heading_deg"));
}

TEST_F(SiteJson, MissingReferencedFile) {
    document_["skies"]["sunny"]["path"] = "skies/missing.hdr";
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/skies/sunny/path");
    EXPECT_TRUE(contains(error.problem(), "not found"));
    EXPECT_TRUE(contains(error.problem(), "missing.hdr"));
}

TEST_F(SiteJson, EightBitSkyPhotoAndBracket) {
    for (const char* name : {"theta.jpg", "dark.jpg", "bright.png"})
        std::ofstream(fs::path(directory_) / name) << "placeholder";
    document_["skies"]["sunny"] = {{"path", "theta.jpg"}, {"ev100", 14.5}, {"north_azimuth_in_image_deg", 90}};
    document_["skies"]["overcast"] = {{"bracket", json::array({{{"path", "dark.jpg"}}, {{"path", "bright.png"},
                                                                                         {"ev100", 9}}})}};
    const gusuku::SiteConfig config = load();
    ASSERT_EQ(config.sunny_sky.photos.size(), 1u);
    EXPECT_EQ(config.sunny_sky.path, (fs::path(directory_) / "theta.jpg").string());
    EXPECT_EQ(config.sunny_sky.photos[0].path, config.sunny_sky.path);
    EXPECT_EQ(config.sunny_sky.photos[0].ev100, 14.5);
    EXPECT_EQ(config.sunny_sky.north_azimuth_in_image_deg, 90.0);
    ASSERT_EQ(config.overcast_sky->photos.size(), 2u);
    EXPECT_EQ(config.overcast_sky->path, (fs::path(directory_) / "dark.jpg").string());
    EXPECT_FALSE(config.overcast_sky->photos[0].ev100.has_value());  // from its EXIF
    EXPECT_EQ(config.overcast_sky->photos[1].ev100, 9.0);
    EXPECT_FALSE(config.sunny_sky.global_horizontal_lux.has_value());

    document_["skies"]["sunny"]["global_horizontal_lux"] = 86000;
    EXPECT_EQ(load().sunny_sky.global_horizontal_lux, 86000.0);
}

TEST_F(SiteJson, BadSkyPhotoFieldsAreNamed) {
    std::ofstream(fs::path(directory_) / "theta.jpg") << "placeholder";
    const auto expectError = [&](const json& sky, const std::string& field, const std::string& part) {
        document_["skies"]["sunny"] = sky;
        const gusuku::InputError error = loadError();
        EXPECT_EQ(error.field(), field) << error.what();
        EXPECT_TRUE(contains(error.problem(), part));
    };
    expectError({{"path", "sky.hdr"}, {"ev100", 12}}, "/skies/sunny/ev100", "applies to an 8-bit photo");
    expectError({{"path", "theta.jpg"}, {"ev100", 31}}, "/skies/sunny/ev100", "is outside [-10, 30]");
    expectError({{"path", "theta.jpg"}, {"bracket", json::array({{{"path", "theta.jpg"}}})}}, "/skies/sunny/path",
                "not both");
    expectError({{"north_azimuth_in_image_deg", 0}}, "/skies/sunny/path", "give path or bracket");
    expectError({{"bracket", json::array()}}, "/skies/sunny/bracket", "holds 0 photos; expected 1 to 16");
    expectError({{"bracket", json::array({{{"path", "sky.hdr"}}})}}, "/skies/sunny/bracket/0/path",
                "does not end in .jpg or .jpeg or .png");
    expectError({{"bracket", json::array({{{"path", "theta.jpg"}, {"ev", 3}}})}}, "/skies/sunny/bracket/0/ev", "");
    expectError({{"path", "sky.txt"}}, "/skies/sunny/path", "does not end in .hdr or .exr or .jpg");
    expectError({{"path", "sky.hdr"}, {"global_horizontal_lux", 50000}}, "/skies/sunny/global_horizontal_lux",
                "applies to an 8-bit photo");
    expectError({{"path", "theta.jpg"}, {"global_horizontal_lux", 0}}, "/skies/sunny/global_horizontal_lux",
                "is outside (0, 200000]");
    expectError({{"bracket", json::array({{{"path", "theta.jpg"}, {"global_horizontal_lux", 9}}})}},
                "/skies/sunny/bracket/0/global_horizontal_lux", "");
}

TEST_F(SiteJson, PositionAndOffsetBothGiven) {
    document_["building"]["position"] = {{"latitude_deg", 26.2}, {"longitude_deg", 127.7}, {"height_m", 0}};
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/enu_offset_m");
    EXPECT_TRUE(contains(error.problem(), "not both"));
}

TEST_F(SiteJson, NeitherPositionNorOffset) {
    document_["building"].erase("enu_offset_m");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/position");
    EXPECT_TRUE(contains(error.problem(), "missing"));
}

TEST_F(SiteJson, DuplicateSlotNames) {
    document_["bake"]["slots"] = json::parse(R"([{"name": "noon", "sky": "sunny", "local_time": "12:00"},
                                                 {"name": "noon", "sky": "sunny", "local_time": "12:30"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/1/name");
    EXPECT_TRUE(contains(error.problem(), "duplicate"));
}

TEST_F(SiteJson, BadSlotName) {
    document_["bake"]["slots"] = json::parse(R"([{"name": "Noon!", "sky": "sunny", "local_time": "12:00"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/0/name");
    EXPECT_TRUE(contains(error.problem(), "a-z"));
}

TEST_F(SiteJson, OvercastSlotWithoutOvercastSky) {
    document_["skies"].erase("overcast");
    document_["bake"]["slots"] = json::parse(R"([{"name": "grey", "sky": "overcast"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/0/sky");
    EXPECT_TRUE(contains(error.problem(), "skies.overcast"));
}

TEST_F(SiteJson, OvercastSlotWithLocalTime) {
    document_["bake"]["slots"] = json::parse(R"([{"name": "grey", "sky": "overcast", "local_time": "12:00"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/0/local_time");
    EXPECT_TRUE(contains(error.problem(), "not allowed"));
}

TEST_F(SiteJson, SunnySlotWithoutLocalTime) {
    document_["bake"]["slots"] = json::parse(R"([{"name": "noon", "sky": "sunny"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/0/local_time");
    EXPECT_TRUE(contains(error.problem(), "missing"));
}

TEST_F(SiteJson, BadLocalTime) {
    document_["bake"]["slots"] = json::parse(R"([{"name": "late", "sky": "sunny", "local_time": "25:00"}])");
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/slots/0/local_time");
    EXPECT_TRUE(contains(error.problem(), "25:00"));
    EXPECT_TRUE(contains(error.problem(), "not a time of day"));
}

TEST_F(SiteJson, BadDate) {
    document_["bake"]["date"] = "2026-02-29";  // 2026 is not a leap year
    gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/date");
    EXPECT_TRUE(contains(error.problem(), "day outside [1, 28]"));

    document_["bake"]["date"] = "21/06/2026";
    error = loadError();
    EXPECT_EQ(error.field(), "/bake/date");
    EXPECT_TRUE(contains(error.problem(), "YYYY-MM-DD"));
}

TEST_F(SiteJson, BadUtcOffset) {
    document_["site"]["utc_offset"] = "+14:30";
    gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/site/utc_offset");
    EXPECT_TRUE(contains(error.problem(), "outside [-14:00, +14:00]"));

    document_["site"]["utc_offset"] = "9";
    error = loadError();
    EXPECT_EQ(error.field(), "/site/utc_offset");
    EXPECT_TRUE(contains(error.problem(), "+hh:mm"));
}

TEST_F(SiteJson, ZeroScale) {
    document_["building"]["scale"] = 0;
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/scale");
    EXPECT_EQ(error.problem(), "0 is outside [1e-06, 1000000]");
}

// A scale near 0 collapses the mesh onto a point; it is named as the scale, not blamed on a node transform.
TEST_F(SiteJson, SfmScaleNearZeroIsNamed) {
    document_["sfm_mesh"] = {{"path", "building.glb"}, {"scale", 1e-300}, {"rotation_wxyz", {1, 0, 0, 0}},
                             {"translation_enu_m", {0, 0, 0}}};
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/sfm_mesh/scale");
    EXPECT_EQ(error.problem(), "1e-300 is outside [1e-06, 1000000]");
}

TEST_F(SiteJson, HeadingOutOfRange) {
    document_["building"]["heading_deg"] = 400;
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/building/heading_deg");
    EXPECT_EQ(error.problem(), "400 is outside [-360, 360]");
}

TEST_F(SiteJson, NonIntegerSampleCount) {
    document_["bake"]["samples_per_texel"] = 100.5;
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/samples_per_texel");
    EXPECT_TRUE(contains(error.problem(), "whole number"));
}

TEST_F(SiteJson, NonUnitQuaternion) {
    document_["sfm_mesh"]["rotation_wxyz"] = {1.0, 0.0, 0.0, 0.1};  // length 1.005
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/sfm_mesh/rotation_wxyz");
    EXPECT_TRUE(contains(error.problem(), "unit quaternion"));
}

TEST_F(SiteJson, NearlyUnitQuaternionIsNormalised) {
    document_["sfm_mesh"]["rotation_wxyz"] = {0.0, 0.0, 0.0, 1.0005};
    const gusuku::SiteConfig config = load();
    EXPECT_DOUBLE_EQ(config.sfm_mesh->rotation_wxyz[3], 1.0);
}

TEST_F(SiteJson, WrongFormatName) {
    document_["format"] = "gusuku-site/2";
    const gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/format");
    EXPECT_TRUE(contains(error.problem(), "gusuku-site/1"));
}

// --- placement transforms ---------------------------------------------------------------------------------

glm::dvec3 apply(const glm::dmat4& transform, const glm::dvec3& point) {
    return glm::dvec3(transform * glm::dvec4(point, 1.0));
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(BuildingTransform, HeadingZeroKeepsModelNorthNorth) {
    gusuku::BuildingConfig building;
    building.enu_offset_m = glm::dvec3(0.0);
    const glm::dmat4 transform = building.enuFromModel({});
    expectNear(apply(transform, {1, 0, 0}), {1, 0, 0});   // glTF +x: east
    expectNear(apply(transform, {0, 1, 0}), {0, 0, 1});   // glTF +y: up
    expectNear(apply(transform, {0, 0, -1}), {0, 1, 0});  // glTF -z (model north): north
}

TEST(BuildingTransform, HeadingNinetyTurnsModelNorthEast) {
    gusuku::BuildingConfig building;
    building.enu_offset_m = glm::dvec3(0.0);
    building.heading_deg = 90.0;
    const glm::dmat4 transform = building.enuFromModel({});
    expectNear(apply(transform, {0, 0, -1}), {1, 0, 0});  // the model's north faces east
    expectNear(apply(transform, {1, 0, 0}), {0, -1, 0});  // so its +x (east side) faces south
    expectNear(apply(transform, {0, 1, 0}), {0, 0, 1});   // up stays up
}

TEST(BuildingTransform, ScaleThenHeadingThenOffset) {
    gusuku::BuildingConfig building;
    building.enu_offset_m = glm::dvec3(10.0, 20.0, 30.0);
    building.heading_deg = -90.0;  // model north faces west
    building.scale = 2.0;
    const glm::dmat4 transform = building.enuFromModel({});
    expectNear(apply(transform, {0, 0, 0}), {10, 20, 30});
    expectNear(apply(transform, {0, 0, -1}), {8, 20, 30});
    expectNear(apply(transform, {0, 3, 0}), {10, 20, 36});
}

TEST(BuildingTransform, GeodeticPositionBecomesTheOrigin) {
    const gusuku::GeodeticPoint site{26.217, 127.7195, 120.0};
    gusuku::BuildingConfig building;
    building.position = gusuku::GeodeticPoint{26.218, 127.7195, 125.0};
    const glm::dvec3 origin = apply(building.enuFromModel(site), {0, 0, 0});
    // Meridian radius of curvature M = a (1 - e^2) / (1 - e^2 sin^2 phi)^1.5 at 26.2175 deg: 0.001 deg north.
    const double e2 = (1.0 / 298.257223563) * (2.0 - 1.0 / 298.257223563);
    const double sin_phi = std::sin(26.2175 * std::numbers::pi / 180.0);
    const double meridian_radius = 6378137.0 * (1.0 - e2) / std::pow(1.0 - e2 * sin_phi * sin_phi, 1.5);
    EXPECT_NEAR(origin.x, 0.0, 1e-6);
    EXPECT_NEAR(origin.y, (meridian_radius + 122.5) * 0.001 * std::numbers::pi / 180.0, 0.01);
    EXPECT_NEAR(origin.z, 5.0, 0.01);
}

TEST(SfmTransform, QuaternionScaleTranslation) {
    gusuku::SfmMeshConfig mesh;
    // 90 degrees about +z (up): east -> north, north -> west.
    mesh.rotation_wxyz = {std::cos(std::numbers::pi / 4), 0.0, 0.0, std::sin(std::numbers::pi / 4)};
    mesh.scale = 2.0;
    mesh.translation_enu_m = {1.0, 2.0, 3.0};
    const glm::dmat4 transform = mesh.enuFromModel();
    expectNear(apply(transform, {1, 0, 0}), {1, 4, 3});
    expectNear(apply(transform, {0, 1, 0}), {-1, 2, 3});
    expectNear(apply(transform, {0, 0, 1}), {1, 2, 5});
}

TEST(SfmTransform, FlipsAYDownMesh) {
    gusuku::SfmMeshConfig mesh;
    mesh.rotation_wxyz = {0.0, 1.0, 0.0, 0.0};  // 180 degrees about +x: y -> -y, z -> -z
    const glm::dmat4 transform = mesh.enuFromModel();
    expectNear(apply(transform, {0, 1, 0}), {0, -1, 0});
    expectNear(apply(transform, {0, 0, 1}), {0, 0, -1});
    expectNear(apply(transform, {1, 0, 0}), {1, 0, 0});
}

// --- gusuku-bake check ------------------------------------------------------------------------------------

using gusuku::testing::CommandResult;


CommandResult runBakeCheck(const std::string& directory, const std::string& site_path) {
    return gusuku::testing::runBakeCommand({"check", site_path}, directory);
}

TEST_F(SiteJson, CheckCommandReportsFileFieldAndProblem) {
    document_["site"]["latitude_deg"] = 200;
    const std::string path = writeText(document_.dump(2));
    const CommandResult result = runBakeCheck(directory_, path);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.stderr_text, "gusuku-bake: error: " + path + ": /site/latitude_deg: 200 is outside [-90, 90]\n");
}

// A FIFO opened for reading blocks until a writer appears: a referenced sky, glTF or site.json that is one must be
// refused by its type, never opened. A directory or a device is no file either.
TEST_F(SiteJson, FifoDirectoryAndDeviceAsReferencedFilesAreRefusedUnopened) {
    const fs::path fifo = fs::path(directory_) / "sky_fifo.hdr";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    document_["skies"]["sunny"]["path"] = "sky_fifo.hdr";
    gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/skies/sunny/path");
    EXPECT_TRUE(contains(error.problem(), "is a FIFO (named pipe), not a regular file"));

    document_["skies"]["sunny"]["path"] = "sky.hdr";
    fs::create_directory(fs::path(directory_) / "folder.glb");
    document_["building"]["path"] = "folder.glb";
    error = loadError();
    EXPECT_EQ(error.field(), "/building/path");
    EXPECT_TRUE(contains(error.problem(), "is a directory, not a regular file"));

    fs::create_symlink("/dev/zero", fs::path(directory_) / "zero.glb");
    document_["building"]["path"] = "zero.glb";
    error = loadError();
    EXPECT_EQ(error.field(), "/building/path");
    EXPECT_TRUE(contains(error.problem(), "is a character device, not a regular file"));

    const fs::path site_fifo = fs::path(directory_) / "site_fifo.json";
    ASSERT_EQ(mkfifo(site_fifo.c_str(), 0600), 0);
    try {
        gusuku::loadSiteConfig(site_fifo.string());
        ADD_FAILURE() << "a FIFO site.json was accepted";
    } catch (const gusuku::InputError& site_error) {
        EXPECT_EQ(site_error.what(), site_fifo.string() + ": is a FIFO (named pipe), not a regular file; not read");
    }
}

// NREL SPA is fitted for the years -2000..6000 and the sun code refuses instants outside them; a date it would
// refuse is reported at load, with its field, rather than when the bake reaches the sun.
TEST_F(SiteJson, DateOutsideTheSunModelsYearsIsRefusedAtLoad) {
    document_["bake"]["date"] = "7000-06-21";
    gusuku::InputError error = loadError();
    EXPECT_EQ(error.field(), "/bake/date");
    EXPECT_TRUE(contains(error.problem(), "slot \"sunny_0900\" at 7000-06-21T09:00:00+09:00"));
    EXPECT_TRUE(contains(error.problem(), "years -2000 to 6000"));

    // The same file at a date SPA covers loads.
    document_["bake"]["date"] = "2026-06-21";
    EXPECT_EQ(load().bake.slots.size(), 4u);  // the three sunny defaults and overcast
}

// `gusuku-bake check` loads the building through the glTF loader, so its limits are reported on one line too: a
// node DAG whose 2 x 2^21 paths each reach a one-triangle mesh (4,194,306 instanced triangles, over 4,194,304).
TEST_F(SiteJson, CheckCommandReportsAGltfOverTheInstancingLimit) {
    json gltf = json::parse(R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": []})");
    constexpr int kLevels = 22;
    for (int level = 0; level < kLevels; ++level)
        for (int twin = 0; twin < 2; ++twin)
            gltf["nodes"].push_back(level + 1 < kLevels ? json{{"children", {2 * level + 2, 2 * level + 3}}}
                                                        : json{{"mesh", 0}});
    gltf["nodes"][0]["mesh"] = 0;
    gltf["nodes"][1]["mesh"] = 0;
    gltf["scenes"] = {{{"nodes", {0, 1}}}};
    std::ofstream(fs::path(directory_) / "dag.gltf") << gltf.dump();
    document_["building"]["path"] = "dag.gltf";
    const std::string path = writeText(document_.dump(2));
    const CommandResult result = runBakeCheck(directory_, path);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.stderr_text, "gusuku-bake: error: " + (fs::path(directory_) / "dag.gltf").string() +
                                      ": nodes: the scene expands to 4194306 instanced triangles, above the limit "
                                      "4194304 (a node used by several parents repeats its whole subtree); refused "
                                      "before expanding\n");
}

TEST_F(SiteJson, FileOverOneMebibyteIsRefusedUnread) {
    std::string text = document_.dump();
    text.insert(text.size() - 1, std::string(size_t(1) << 20, ' '));  // valid JSON, padded with whitespace
    const gusuku::InputError error = loadError(text);
    EXPECT_EQ(error.problem(), "is " + std::to_string(text.size()) + " bytes, more than the 1048576 a site.json may have");
}

TEST_F(SiteJson, CheckCommandReportsADateTheSunCannotTake) {
    document_["bake"]["date"] = "9999-01-01";
    const std::string path = writeText(document_.dump(2));
    const CommandResult result = runBakeCheck(directory_, path);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.stderr_text, "gusuku-bake: error: " + path +
                                      ": /bake/date: slot \"sunny_0900\" at 9999-01-01T09:00:00+09:00 is outside the "
                                      "UTC years -2000 to 6000 that the sun position (NREL SPA) covers\n");
}

TEST_F(SiteJson, CheckCommandSummarisesASharedDataSite) {
    GUSUKU_REQUIRE_SHARED_DATA();
    const fs::path data = gusuku::testing::sharedDataDir();
    document_.erase("sfm_mesh");
    document_["building"]["path"] = (data / "building/playcanvas_house_lightmapUV/house.glb").string();
    document_["skies"]["sunny"]["path"] = (data / "env/rooitou_park_1k.hdr").string();
    document_["skies"]["overcast"]["path"] = (data / "env/potsdamer_platz_1k.hdr").string();
    const CommandResult result = runBakeCheck(directory_, writeText(document_.dump(2)));
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    // 09:00 at +09:00 on 2026-06-21 is midnight UTC; both clocks are printed.
    EXPECT_TRUE(contains(result.stdout_text, "2026-06-21T09:00:00+09:00"));
    EXPECT_TRUE(contains(result.stdout_text, "2026-06-21T00:00:00"));
    EXPECT_TRUE(contains(result.stdout_text, "1024 x 512"));
    EXPECT_TRUE(contains(result.stdout_text, "triangles"));
    EXPECT_TRUE(contains(result.stdout_text, "no sfm_mesh"));  // the warning for a site without surroundings
}

TEST(CheckCommand, HelpAndUsage) {
    const std::string directory = gusuku::testing::makeTemporaryDirectory("test_site_cli");
    const CommandResult help = gusuku::testing::runBakeCommand({"check", "--help"}, directory);
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_TRUE(contains(help.stdout_text + help.stderr_text, "usage: gusuku-bake check SITE_JSON"));
    EXPECT_EQ(gusuku::testing::runBakeCommand({"check"}, directory).exit_code, 2);
}

}  // namespace

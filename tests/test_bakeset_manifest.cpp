// The bake set manifest (gusuku/formats/bakeset_manifest.h, gusuku/assets/bakeset_manifest_json.h, docs/bakeset.md): a
// manifest written and read back is the same manifest and the same bytes; every reader error names the file and
// the field (JSON pointer); the writer refuses what the reader would refuse; and a manifest written by a real
// small bake reads back, with the bytes the baker wrote reproduced by the shared writer.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace {

using gusuku::BakeSetManifest;
using gusuku::BakeSetSky;
using nlohmann::json;

/// The ENU unit vector towards a sun at azimuth (east of north) and elevation, degrees (docs/design.md 2).
glm::dvec3 sunDirection(double azimuth_deg, double elevation_deg) {
    const double degree = std::acos(-1.0) / 180.0;
    const double e = elevation_deg * degree, a = azimuth_deg * degree;
    return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

/// A manifest using every part of the format: three kinds of slot (sun measured, sun below the horizon,
/// overcast), one without colour statistics, every input role, warnings, awkward numbers.
BakeSetManifest exampleManifest() {
    BakeSetManifest m;
    m.input_hash = 0x0123456789abcdefull;
    m.inputs = {{"site", "/sites/a/site.json", "00000000deadbeef"},
                {"building", "/sites/a/house.glb", "1111111111111111"},
                {"sfm_mesh", "/sites/a/site.glb", "2222222222222222"},
                {"sunny_sky", "/sites/a/sky.hdr", "3333333333333333"},
                {"overcast_sky", "/sites/a/overcast.hdr", "4444444444444444"}};
    m.site = {"Nakagusuku \"terrace\"", 26.2856, 127.8008, 160.0, 540};
    m.settings = {512, 4, 4294967295u, true};
    m.building.lightmap_uv_source = "generated charts (14 charts)";
    m.building.lightmap_resolution = 200;
    m.building.texels_per_metre = 10.0 / 3.0;
    m.building.texels = 16779;
    m.ground_grid.grid.origin_enu_m = {-12.625, -9.1 / 3.0};
    m.ground_grid.grid.cell_m = 0.25;
    m.ground_grid.grid.columns = 49;
    m.ground_grid.grid.rows = 50;
    m.ground_grid.ground_source = "sfm_mesh";

    gusuku::BakeSetSlot sunny;
    sunny.name = "sunny_0900";
    sunny.sky = BakeSetSky::Sunny;
    sunny.sky_map = "/sites/a/sky.hdr";
    sunny.local_time = "2026-06-21T09:00:00+09:00";
    sunny.utc = "2026-06-21T00:00:00Z";
    sunny.sun.present = true;
    sunny.sun.irradiance_source = "sky map sun disc (measured at 40.000000 deg elevation, carried by the clear-sky model)";
    sunny.sun.position = gusuku::BakeSetSunPosition{83.25, 40.125, sunDirection(83.25, 40.125)};
    sunny.sun.irradiance_rgb = {31.4159, 30.0, 1e-7};
    sunny.sun.angular_radius_deg = 0.2675;
    sunny.sky_sampling_method = "cosine + map (MIS)";
    sunny.cosine_relative_variance = 2.6;
    sunny.building_irradiance = "building_sunny_0900.exr";
    sunny.ground_irradiance_with_building = "ground_sunny_0900_with.exr";
    sunny.ground_irradiance_without_building = "ground_sunny_0900_without.exr";
    sunny.invalid_texels = 12;
    sunny.colour_statistics = gusuku::BakeSetColourStatistics{
        glm::dvec3(glm::vec3(52.381f, -1.25f, 7.5f)), glm::dvec3(glm::vec3(10.1f, 2.2f, 3.3f)), 16767};

    gusuku::BakeSetSlot night = sunny;
    night.name = "sunny_2100";
    night.local_time = "2026-06-21T21:00:00+09:00";
    night.utc = "2026-06-21T12:00:00Z";
    night.sun.present = false;
    night.sun.irradiance_source = "none: sun below the horizon";
    night.sun.position = gusuku::BakeSetSunPosition{300.0, -12.5, sunDirection(300.0, -12.5)};
    night.sun.position->direction_enu /= glm::length(night.sun.position->direction_enu);
    night.sun.irradiance_rgb = glm::dvec3(0.0);
    night.sun.angular_radius_deg = 0.0;
    night.building_irradiance = "building_sunny_2100.exr";
    night.ground_irradiance_with_building = "ground_sunny_2100_with.exr";
    night.ground_irradiance_without_building = "ground_sunny_2100_without.exr";
    night.colour_statistics.reset();

    gusuku::BakeSetSlot overcast;
    overcast.name = "overcast";
    overcast.sky = BakeSetSky::Overcast;
    overcast.sky_map = "/sites/a/overcast.hdr";
    overcast.sun.irradiance_source = "none: overcast";
    overcast.sky_sampling_method = "cosine";
    overcast.cosine_relative_variance = 0.46;
    overcast.building_irradiance = "building_overcast.exr";
    overcast.ground_irradiance_with_building = "ground_overcast_with.exr";
    overcast.ground_irradiance_without_building = "ground_overcast_without.exr";
    overcast.colour_statistics = gusuku::BakeSetColourStatistics{{40.0, 0.5, -0.5}, {8.0, 1.0, 1.0}, 16767};

    m.slots = {sunny, night, overcast};
    m.statistics = {83000000000ull, 98.7, 83000000000.0 / 98.7, 101.25};
    m.warnings = {"slot sunny_2100: the sun is below the horizon", "a warning with \"quotes\" and \\ / slashes"};
    return m;
}

const char* kFile = "bakes/x/manifest.json";

TEST(BakeSetManifest, WriteReadRoundTripIsLosslessAndByteStable) {
    const BakeSetManifest manifest = exampleManifest();
    const std::string text = gusuku::bakeSetManifestJson(manifest);
    const BakeSetManifest read = gusuku::parseBakeSetManifest(kFile, text);
    EXPECT_TRUE(read == manifest);
    // Spot checks, so a field lost on both sides would still show.
    ASSERT_EQ(read.slots.size(), 3u);
    EXPECT_EQ(read.slots[0].sun.irradiance_rgb, glm::dvec3(31.4159, 30.0, 1e-7));
    EXPECT_EQ(read.slots[0].colour_statistics->lab_mean.x, double(52.381f));
    EXPECT_FALSE(read.slots[1].colour_statistics.has_value());
    EXPECT_FALSE(read.slots[2].sun.position.has_value());
    EXPECT_EQ(read.statistics.rays_traced, 83000000000ull);
    EXPECT_EQ(read.settings.seed, 4294967295u);
    EXPECT_EQ(read.input_hash, 0x0123456789abcdefull);
    EXPECT_EQ(read.ground_grid.grid.origin_enu_m.y, -9.1 / 3.0);
    EXPECT_EQ(gusuku::bakeSetManifestJson(read), text);
    // The text is the documented layout: format first, members in name order, two-space indent.
    EXPECT_EQ(text.rfind("{\n  \"building\": {", 0), 0u);
    EXPECT_NE(text.find("\"format\": \"gusuku-bakeset/1\""), std::string::npos);
    EXPECT_NE(text.find("\"input_hash\": \"0123456789abcdef\""), std::string::npos);
    EXPECT_EQ(text.back(), '\n');
}

TEST(BakeSetManifest, FileRoundTrip) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-manifest");
    const std::string path = dir + "/manifest.json";
    gusuku::writeBakeSetManifest(path, exampleManifest());
    EXPECT_TRUE(gusuku::readBakeSetManifest(path) == exampleManifest());
    try {
        gusuku::readBakeSetManifest(dir + "/missing.json");
        FAIL() << "a missing manifest must be an InputError";
    } catch (const gusuku::InputError& error) {
        EXPECT_EQ(error.file(), dir + "/missing.json");
        EXPECT_EQ(std::string(error.what()).rfind(dir + "/missing.json: ", 0), 0u) << error.what();
    }
}

TEST(BakeSetManifest, WriterRefusesWhatTheReaderWouldRefuse) {
    BakeSetManifest manifest = exampleManifest();
    manifest.site.latitude_deg = std::nan("");
    try {
        gusuku::bakeSetManifestJson(manifest);
        FAIL() << "NaN must not be written (JSON would get null)";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("/site/latitude_deg"), std::string::npos) << error.what();
    }
    manifest = exampleManifest();
    manifest.slots[0].sun.irradiance_rgb.y = INFINITY;
    EXPECT_THROW(gusuku::bakeSetManifestJson(manifest), std::invalid_argument);
    manifest = exampleManifest();
    manifest.slots[2].sun.position = gusuku::BakeSetSunPosition{};
    EXPECT_THROW(gusuku::bakeSetManifestJson(manifest), std::invalid_argument);
    manifest = exampleManifest();
    manifest.slots[0].sun.position.reset();
    EXPECT_THROW(gusuku::bakeSetManifestJson(manifest), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------------------------
// Reader errors: FILE: FIELD: PROBLEM
// ------------------------------------------------------------------------------------------------------------

struct BadManifest {
    std::string what;     ///< the case, for the failure message
    std::string text;     ///< the manifest's text
    std::string field;    ///< the JSON pointer the error must name
    std::string problem;  ///< a part of the problem text it must give
};

json exampleJson() { return json::parse(gusuku::bakeSetManifestJson(exampleManifest())); }

BadManifest withValue(const std::string& what, const std::string& pointer, const json& value,
                      const std::string& problem) {
    json document = exampleJson();
    document[json::json_pointer(pointer)] = value;
    return {what, document.dump(2), pointer, problem};
}

BadManifest without(const std::string& what, const std::string& parent, const std::string& name) {
    json document = exampleJson();
    document[json::json_pointer(parent)].erase(name);
    return {what, document.dump(2), parent + "/" + name, "required field is missing"};
}

std::vector<BadManifest> badManifests() {
    std::vector<BadManifest> cases = {
        withValue("newer format", "/format", "gusuku-bakeset/2", "\"gusuku-bakeset/2\" is not a format this reader knows"),
        withValue("format not a string", "/format", 1, "expected a string, found a number"),
        without("no format", "", "format"),
        without("no latitude", "/site", "latitude_deg"),
        without("no slots", "", "slots"),
        withValue("an empty slot list", "/slots", json::array(), "empty: a bake set holds at least one slot"),
        withValue("a ground cell of 1e308 m", "/ground_grid/cell_m", 1e308, "is outside [0.001, 100]"),
        withValue("a ground cell of 1e-300 m", "/ground_grid/cell_m", 1e-300, "is outside [0.001, 100]"),
        withValue("a grid origin 1e30 m away", "/ground_grid/origin_enu_m/0", 1e30, "is outside [-100000, 100000]"),
        withValue("a sun of 1e300", "/slots/0/sun/irradiance_rgb/1", 1e300, "is outside [0, 1e+18]"),
        withValue("a sun direction that is not its angles", "/slots/0/sun/direction_enu",
                  json::array({0.0, 0.0, 1.0}), "degrees from the direction azimuth_deg and apparent_elevation_deg give"),
        withValue("local time 25:00", "/slots/0/local_time", "25:00", "is not a time of day HH:MM"),
        withValue("a utc that is no time", "/slots/0/utc", "yesterday", "is not an ISO 8601 time"),
        withValue("1e12 invalid texels", "/slots/0/invalid_texels", 1e12, "is outside [0, 67108864]"),
        withValue("a site input that is not a site.json", "/inputs/0/path", "/etc/passwd",
                  "\"/etc/passwd\" is not a .json file, as the site input is"),
        withValue("a sky input that is no sky", "/inputs/3/path", "sky.txt",
                  "is not a .hdr or .exr map or a .jpg, .jpeg or .png photo"),
        [] {
            json document = exampleJson();  // the night slot (-12.5 degrees) claiming its sun shines
            document["slots"][1]["sun"]["present"] = true;
            return BadManifest{"a sun below the horizon marked present", document.dump(2),
                               "/slots/1/sun/apparent_elevation_deg", "is below the horizon, yet present is true"};
        }(),
        without("no sun in a slot", "/slots/0", "sun"),
        without("sunny slot without utc", "/slots/0", "utc"),
        without("sunny slot without sun position", "/slots/1/sun", "direction_enu"),
        without("present sun without irradiance", "/slots/0/sun", "irradiance_rgb"),
        without("input without role", "/inputs/2", "role"),
        without("no ground grid rows", "/ground_grid", "rows"),
        without("no statistics", "", "statistics"),
        withValue("latitude as text", "/site/latitude_deg", "26.3", "expected a number, found a string"),
        withValue("latitude out of range", "/site/latitude_deg", 200.0, "200 is outside [-90, 90]"),
        withValue("denoised as text", "/settings/denoised", "yes", "expected true or false, found a string"),
        withValue("samples zero", "/settings/samples_per_texel", 0, "0 is outside [1, 4294967295]"),
        withValue("seed too large", "/settings/seed", 4294967296ull, "4294967296 is outside [0, 4294967295]"),
        withValue("texels not whole", "/building/texels", 1.5, "1.5 is not a whole number"),
        withValue("negative count", "/statistics/rays_traced", -5, "-5 is negative"),
        withValue("irradiance channel as text", "/slots/0/sun/irradiance_rgb/1", "x", "expected a number, found a string"),
        withValue("negative irradiance", "/slots/0/sun/irradiance_rgb/2", -1.0, "-1 is outside [0, 1e+18]"),
        withValue("irradiance of two channels", "/slots/0/sun/irradiance_rgb", json::array({1.0, 2.0}),
                  "expected 3 numbers, found 2"),
        withValue("direction not unit", "/slots/0/sun/direction_enu", json::array({1.0, 1.0, 0.0}),
                  "(1, 1, 0) has length 1.41421356, not 1"),
        withValue("zero cell", "/ground_grid/cell_m", 0.0, "0 is outside [0.001, 100]"),
        withValue("columns as float", "/ground_grid/columns", 4.5, "4.5 is not a whole number"),
        withValue("origin of one number", "/ground_grid/origin_enu_m", json::array({1.0}), "expected 2 numbers, found 1"),
        withValue("row 0 south", "/ground_grid/row_0", "south edge", "expected \"north edge\""),
        withValue("other uv set", "/building/lightmap_uv", "TEXCOORD_0", "expected \"TEXCOORD_1\""),
        withValue("input hash short", "/input_hash", "abc", "\"abc\" is not 16 lower-case hex digits"),
        withValue("input hash upper case", "/input_hash", "0123456789ABCDEF", "is not 16 lower-case hex digits"),
        withValue("file hash bad", "/inputs/1/fnv1a64", "zz23456789abcdef", "is not 16 lower-case hex digits"),
        withValue("unknown sky", "/slots/0/sky", "cloudy", "\"cloudy\" is neither \"sunny\" nor \"overcast\""),
        withValue("overcast slot with a time", "/slots/2/local_time", "2026-06-21T12:00:00+09:00",
                  "only a sunny slot has a time"),
        withValue("overcast slot with a sun position", "/slots/2/sun/azimuth_deg", 10.0,
                  "only a sunny slot has a sun position"),
        withValue("overcast slot with a sun", "/slots/2/sun/present", true, "an overcast slot has no sun"),
        withValue("absent sun with irradiance", "/slots/1/sun/irradiance_rgb", json::array({1.0, 1.0, 1.0}),
                  "only a present sun has an irradiance"),
        withValue("repeated slot name", "/slots/2/name", "sunny_0900", "is already the name of /slots/0"),
        withValue("empty file name", "/slots/1/building_irradiance", "", "is empty"),
        withValue("warning not a string", "/warnings/1", 3, "expected a string, found a number"),
        withValue("unknown field", "/building/extra", 1, "unknown field"),
        withValue("slot not an object", "/slots/1", "x", "expected an object, found a string"),
        withValue("slots not an array", "/slots", json::object(), "expected an array, found an object"),
        withValue("colour space changed", "/slots/0/colour_statistics/space", "sRGB", "expected \"CIE Lab (D65)"),
        withValue("negative sigma", "/slots/0/colour_statistics/lab_sigma/0", -0.5, "-0.5 is outside [0, 1000000000] CIE Lab"),
        withValue("a Lab mean of 1e300", "/slots/0/colour_statistics/lab_mean/0", 1e300, "is outside [-1000000000, 1000000000]"),
    };
    // Non-finite numbers: JSON has none, but a literal too large for a double overflows when parsed.
    std::string overflow = exampleJson().dump(2);
    const std::string height = "\"height_m\": 160.0";
    overflow.replace(overflow.find(height), height.size(), "\"height_m\": 1e999");
    cases.push_back({"height overflows a double", overflow, "/site/height_m", "is not a finite number"});
    std::string bad_json = exampleJson().dump(2);
    bad_json.resize(bad_json.size() / 2);
    cases.push_back({"truncated file", bad_json, "byte " + std::to_string(bad_json.size() + 1), "invalid JSON"});
    cases.push_back({"not an object", "[1, 2]", "", "expected an object, found an array"});
    return cases;
}

TEST(BakeSetManifest, EveryReaderErrorNamesTheFileAndTheField) {
    for (const BadManifest& bad : badManifests()) {
        SCOPED_TRACE(bad.what);
        try {
            gusuku::parseBakeSetManifest(kFile, bad.text);
            ADD_FAILURE() << "accepted";
        } catch (const gusuku::InputError& error) {
            EXPECT_EQ(error.file(), kFile);
            EXPECT_EQ(error.field(), bad.field);
            EXPECT_NE(error.problem().find(bad.problem), std::string::npos) << error.what();
            const std::string prefix = bad.field.empty() ? std::string(kFile) + ": " : std::string(kFile) + ": " + bad.field + ": ";
            EXPECT_EQ(std::string(error.what()).rfind(prefix, 0), 0u) << error.what();
        }
    }
}

// docs/bakeset.md's table of ranges lists exactly the ranges the reader and writer use (bakeset_ranges.h).
TEST(BakeSetManifest, TheDocumentedRangesAreTheReadersRanges) {
    std::ifstream docs(std::string(GUSUKU_GOLDEN_DIR) + "/../../docs/bakeset.md");
    ASSERT_TRUE(docs) << "docs/bakeset.md not found";
    std::vector<std::string> rows;
    for (std::string line; std::getline(docs, line);)
        if (line.rfind("| `", 0) == 0 && line.find("] |") != std::string::npos) rows.push_back(line);
    std::vector<std::string> expected;
    for (const gusuku::BakeSetRange& range : gusuku::kBakeSetRanges) {
        std::string also;
        const auto add = [&](const std::string& note) { also += (also.empty() ? "" : "; ") + note; };
        if (range.source == gusuku::BakeSetRangeSource::kTexels) add("each texel");
        if (range.whole_number) add("a whole number");
        if (range.when_sun_present) add("a present sun's");
        if (range.length_tolerance > 0.0) {
            char note[64];
            std::snprintf(note, sizeof note, "length 1 within %g", range.length_tolerance);
            add(note);
        }
        char row[512];
        std::snprintf(row, sizeof row, "| `%s` | [%.10g, %.10g] | %s | %s |", range.field, range.minimum, range.maximum,
                      range.unit, also.empty() ? "-" : also.c_str());
        expected.push_back(row);
    }
    EXPECT_EQ(rows, expected);
}

// ------------------------------------------------------------------------------------------------------------
// A real small bake
// ------------------------------------------------------------------------------------------------------------

class BakeSetManifestBake : public gusuku::testing::GpuTest {};

TEST_F(BakeSetManifestBake, ManifestOfARealBakeReadsBackAndRewritesToTheSameBytes) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-manifest-bake");
    gusuku::testing::MiniSiteOptions site_options;
    site_options.samples_per_texel = 2;
    const gusuku::SiteConfig site = gusuku::loadSiteConfig(gusuku::testing::writeMiniSite(dir, site_options));
    gusuku::bake::BakeOptions options;
    options.output_dir = dir + "/bake";
    options.show_progress = false;
    const gusuku::bake::BakeReport report = gusuku::bake::runBake(context(), site, options);
    ASSERT_TRUE(report.completed);

    const BakeSetManifest manifest = gusuku::readBakeSetManifest(report.manifest_path);
    ASSERT_EQ(manifest.slots.size(), site.bake.slots.size());
    EXPECT_EQ(manifest.settings.samples_per_texel, 2u);
    EXPECT_EQ(manifest.site.latitude_deg, site.site.reference.latitude_deg);
    EXPECT_EQ(manifest.building.lightmap_resolution, report.lightmap_resolution);
    EXPECT_EQ(manifest.building.texels, report.building_texels);
    EXPECT_EQ(manifest.statistics.rays_traced, report.rays_traced);
    EXPECT_EQ(manifest.ground_grid.ground_source, "flat plane at z = 0");  // the mini site has no SfM mesh
    EXPECT_GT(manifest.ground_grid.grid.cellCount(), 0u);
    size_t sunny = 0;
    for (const gusuku::BakeSetSlot& slot : manifest.slots) {
        SCOPED_TRACE(slot.name);
        for (const std::string& file : {slot.building_irradiance, slot.ground_irradiance_with_building,
                                        slot.ground_irradiance_without_building})
            EXPECT_TRUE(std::filesystem::exists(options.output_dir + "/" + file)) << file;
        ASSERT_TRUE(slot.colour_statistics.has_value());
        if (slot.sky != BakeSetSky::Sunny) continue;
        ++sunny;
        ASSERT_TRUE(slot.sun.present);
        EXPECT_GT(slot.sun.irradiance_rgb.y, 0.0);
        EXPECT_EQ(slot.sun.irradiance_source.rfind("clear-sky model", 0), 0u);  // the mini sky has no disc
    }
    EXPECT_EQ(sunny, 1u);
    EXPECT_TRUE(std::filesystem::exists(options.output_dir + "/" + manifest.ground_grid.geometry));

    // The shared writer reproduces the baker's bytes from what the reader got: nothing is lost or reformatted.
    std::ifstream file(report.manifest_path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    EXPECT_EQ(gusuku::bakeSetManifestJson(manifest), bytes.str());
}

}  // namespace

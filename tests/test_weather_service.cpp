// gusuku/weather/weather_service.h on saved answers of the documented shapes (tests/data/weather/): Open-Meteo's
// current and hourly blocks on a local clock and in unixtime, METAR sky groups with their okta values, and the
// one-line InputError for each malformed answer.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/weather/weather_service.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"

namespace {

const std::filesystem::path kWeatherData = GUSUKU_WEATHER_DATA_DIR;

std::string readText(const std::string& file_name) {
    std::ifstream file(kWeatherData / file_name, std::ios::binary);
    EXPECT_TRUE(file) << "cannot read " << (kWeatherData / file_name);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// The data lines (not '#' comments) of a file, each split at its first ';' (FIELD;REST) into its parts.
std::vector<std::vector<std::string>> dataLines(const std::string& file_name, size_t parts) {
    std::vector<std::vector<std::string>> lines;
    std::istringstream text(readText(file_name));
    std::string line;
    while (std::getline(text, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> split;
        for (size_t part = 1; part < parts; ++part) {
            const size_t separator = line.find(';');
            split.push_back(line.substr(0, separator));
            line = separator == std::string::npos ? "" : line.substr(separator + 1);
        }
        split.push_back(line);
        lines.push_back(split);
    }
    return lines;
}

template <typename Call> std::string inputErrorOf(Call call) {
    try {
        call();
    } catch (const gusuku::InputError& error) {
        return error.what();
    }
    return "";
}

// 2026-06-21T01:30Z: 10:30 in Kyoto (JST, +09:00).
const double kKyotoMorning = gusuku::parseIso8601Utc("2026-06-21T10:30:00+09:00");

TEST(WeatherService, OpenMeteoCurrentOnTheAnswersClock) {
    const gusuku::WeatherReading reading =
        gusuku::weatherFromOpenMeteoCurrent(readText("open_meteo_current_kyoto.json"));
    EXPECT_FLOAT_EQ(reading.weather.cloud_cover, 0.37f);
    EXPECT_EQ(reading.utc_unix_seconds, gusuku::parseIso8601Utc("2026-06-21T01:30:00Z"));
    EXPECT_EQ(reading.source, gusuku::WeatherSource::kOpenMeteoCurrent);
    EXPECT_EQ(reading.read_from, "/current/cloud_cover");
    ASSERT_TRUE(reading.is_day.has_value());
    EXPECT_TRUE(*reading.is_day);
    EXPECT_TRUE(reading.station.empty());
}

TEST(WeatherService, OpenMeteoCurrentInUnixtimeAtNight) {
    const std::string answer = readText("open_meteo_current_unixtime_london.json");
    const gusuku::WeatherReading reading = gusuku::weatherFromOpenMeteoCurrent(answer);
    EXPECT_FLOAT_EQ(reading.weather.cloud_cover, 1.0f);
    EXPECT_EQ(reading.utc_unix_seconds, gusuku::parseIso8601Utc("2026-12-02T06:45:00Z"));
    ASSERT_TRUE(reading.is_day.has_value());
    EXPECT_FALSE(*reading.is_day);
    // The answer has both blocks: weatherFromOpenMeteo takes the current one, the hourly reader the nearest hour.
    EXPECT_EQ(gusuku::weatherFromOpenMeteo(answer, reading.utc_unix_seconds).read_from, "/current/cloud_cover");
    const gusuku::WeatherReading hourly = gusuku::weatherFromOpenMeteoHourly(answer, reading.utc_unix_seconds);
    EXPECT_EQ(hourly.read_from, "/hourly/cloud_cover/1");  // 07:00Z is 15 min away, 06:00Z 45 min
    EXPECT_FLOAT_EQ(hourly.weather.cloud_cover, 1.0f);
}

TEST(WeatherService, OpenMeteoHourlyTakesTheNearestHour) {
    const std::string answer = readText("open_meteo_hourly_kyoto.json");
    // 10:20 JST: the 10:00 hour (index 10, 28 %), day.
    const gusuku::WeatherReading reading = gusuku::weatherFromOpenMeteoHourly(answer, kKyotoMorning - 600.0);
    EXPECT_EQ(reading.source, gusuku::WeatherSource::kOpenMeteoHourly);
    EXPECT_EQ(reading.read_from, "/hourly/cloud_cover/10");
    EXPECT_FLOAT_EQ(reading.weather.cloud_cover, 0.28f);
    EXPECT_EQ(reading.utc_unix_seconds, gusuku::parseIso8601Utc("2026-06-21T01:00:00Z"));
    ASSERT_TRUE(reading.is_day.has_value());
    EXPECT_TRUE(*reading.is_day);
    // 10:40 JST: the 11:00 hour (22 %); 02:00 JST: night, overcast.
    EXPECT_FLOAT_EQ(gusuku::weatherFromOpenMeteoHourly(answer, kKyotoMorning + 600.0).weather.cloud_cover, 0.22f);
    const gusuku::WeatherReading night =
        gusuku::weatherFromOpenMeteo(answer, gusuku::parseIso8601Utc("2026-06-21T02:00:00+09:00"));
    EXPECT_FLOAT_EQ(night.weather.cloud_cover, 0.98f);
    EXPECT_FALSE(night.is_day.value_or(true));
    // The last hour has no value (null): asking for it names the element.
    EXPECT_NE(inputErrorOf([&] {
                  gusuku::weatherFromOpenMeteoHourly(answer, gusuku::parseIso8601Utc("2026-06-21T23:10:00+09:00"));
              }).find("/hourly/cloud_cover/23: expected a number, found null"),
              std::string::npos);
    // A day later: no hour is near.
    EXPECT_NE(inputErrorOf([&] { gusuku::weatherFromOpenMeteoHourly(answer, kKyotoMorning + 86400.0); })
                  .find("/hourly/time: the asked instant 2026-06-22T01:30:00"),
              std::string::npos);
}

TEST(WeatherService, MalformedOpenMeteoAnswersNameTheField) {
    struct Case {
        std::string file, expected;
    };
    const Case cases[] = {
        // The standard-library JSON reader counts bytes from 0: the '<' of "<html>" is byte 0.
        {"open_meteo_not_json.txt", "Open-Meteo answer: byte 0: not JSON"},
        {"open_meteo_missing_cloud_cover.json",
         "Open-Meteo answer: /current/cloud_cover: missing (ask with &current=cloud_cover,is_day)"},
        {"open_meteo_cover_140.json", "Open-Meteo answer: /current/cloud_cover: 140 is outside [0, 100] %"},
        {"open_meteo_error.json", "Open-Meteo answer: /error: the service refused the request: 'Cannot initialize"},
        {"open_meteo_hourly_kyoto.json", "Open-Meteo answer: /current: missing"},
    };
    for (const Case& c : cases) {
        const std::string message = inputErrorOf([&] { gusuku::weatherFromOpenMeteoCurrent(readText(c.file)); });
        EXPECT_EQ(message.rfind(c.expected, 0), 0u) << c.file << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_NE(inputErrorOf([] {
                  gusuku::weatherFromOpenMeteoHourly(readText("open_meteo_hourly_lengths_differ.json"), kKyotoMorning);
              }).find("/hourly/cloud_cover: expected an array of 3 values (as /hourly/time), found 2 values"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] {
                  gusuku::weatherFromOpenMeteo("{\"current\": {\"time\": \"2026-06-21T10:30\", \"cloud_cover\": -5}}",
                                               0.0, "https://api.open-meteo.com/v1/forecast");
              }).find("https://api.open-meteo.com/v1/forecast: /current/cloud_cover: -5 is outside [0, 100] %"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] {
                  gusuku::weatherFromOpenMeteoCurrent("{\"current\": {\"time\": \"21/06/2026\", \"cloud_cover\": 5}}");
              }).find("/current/time: '21/06/2026' is not a local time"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { gusuku::weatherFromOpenMeteoCurrent("{\"current\": {\"cloud_cover\": 1e999}}"); })
                  .find("Open-Meteo answer"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { gusuku::weatherFromOpenMeteoCurrent("[1, 2]"); }).find("/: expected an object"),
              std::string::npos);
}

TEST(WeatherService, MetarSkyGroupsGiveTheLargestLayersOktas) {
    const double reference = gusuku::parseIso8601Utc("2026-12-02T12:30:00Z");
    const std::vector<std::vector<std::string>> reports = dataLines("metar_reports.txt", 3);
    ASSERT_EQ(reports.size(), 15u);
    for (const std::vector<std::string>& report : reports) {
        const gusuku::WeatherReading reading = gusuku::weatherFromMetar(report[2], reference);
        EXPECT_FLOAT_EQ(reading.weather.cloud_cover, std::stof(report[0]) / 8.0f) << report[2];
        EXPECT_EQ(reading.read_from, report[1]) << report[2];
        EXPECT_EQ(reading.source, gusuku::WeatherSource::kMetar);
        EXPECT_FALSE(reading.is_day.has_value());
    }
    const gusuku::WeatherReading heathrow = gusuku::weatherFromMetar(reports[0][2], reference);
    EXPECT_EQ(heathrow.station, "EGLL");
    EXPECT_EQ(heathrow.utc_unix_seconds, gusuku::parseIso8601Utc("2026-12-02T11:50:00Z"));
    // The okta values stated in the header: FEW 1.5, SCT 3.5, BKN 6, OVC and VV 8.
    EXPECT_FLOAT_EQ(gusuku::weatherFromMetar("EGLL 021150Z FEW020", reference).weather.cloud_cover, 0.1875f);
    EXPECT_FLOAT_EQ(gusuku::weatherFromMetar("EGLL 021150Z SCT020", reference).weather.cloud_cover, 0.4375f);
    EXPECT_FLOAT_EQ(gusuku::weatherFromMetar("EGLL 021150Z BKN020", reference).weather.cloud_cover, 0.75f);
    EXPECT_FLOAT_EQ(gusuku::weatherFromMetar("egll 021150z ovc020", reference).weather.cloud_cover, 1.0f);
}

// The cloud base of the group that gave the cover, and the regime it gives the sun (issue 41 item 3): a high
// overcast (cirrostratus, OVC200) keeps the sun where a low one hides it.
TEST(WeatherService, MetarCloudBaseGivesTheSunsRegime) {
    const double reference = gusuku::parseIso8601Utc("2026-12-02T12:30:00Z");
    const auto reading = [&](const char* metar) { return gusuku::weatherFromMetar(metar, reference); };
    EXPECT_FLOAT_EQ(reading("EGLL 021150Z FEW020 BKN035 OVC200").cover_base_feet, 20000.0f);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z OVC200")), gusuku::SkyRegime::kHighThinOvercast);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z FEW020 OVC200")), gusuku::SkyRegime::kHighThinOvercast);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z OVC008")), gusuku::SkyRegime::kOvercast);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z VV002")), gusuku::SkyRegime::kOvercast);  // fog
    // The first of equal layers counts: OVC012 under OVC250 is a low overcast.
    EXPECT_FLOAT_EQ(reading("EGLL 021150Z OVC012 OVC250").cover_base_feet, 1200.0f);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z BKN035")), gusuku::SkyRegime::kBroken);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z SCT040")), gusuku::SkyRegime::kBroken);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z FEW040")), gusuku::SkyRegime::kClear);
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z CAVOK")), gusuku::SkyRegime::kClear);
    EXPECT_FLOAT_EQ(reading("EGLL 021150Z CAVOK").cover_base_feet, -1.0f);
    EXPECT_FLOAT_EQ(reading("EGLL 021150Z OVC///").cover_base_feet, -1.0f);  // not measured: taken as low
    EXPECT_EQ(gusuku::skyRegimeOf(reading("EGLL 021150Z OVC///")), gusuku::SkyRegime::kOvercast);
}

TEST(WeatherService, MetarTimeIsTheNearestMonthsDay) {
    // Fetched just after midnight on 1 April: day 31, 23:50 is 31 March.
    const double april_first = gusuku::parseIso8601Utc("2026-04-01T00:10:00Z");
    EXPECT_EQ(gusuku::weatherFromMetar("METAR RJTT 312350Z 34008KT 9999 FEW030", april_first).utc_unix_seconds,
              gusuku::parseIso8601Utc("2026-03-31T23:50:00Z"));
    // Fetched on 31 December, a report stamped day 01 00:05 (a clock running ahead) is 1 January of the next year.
    const double new_years_eve = gusuku::parseIso8601Utc("2026-12-31T23:58:00Z");
    EXPECT_EQ(gusuku::weatherFromMetar("METAR RJTT 010005Z 34008KT 9999 FEW030", new_years_eve).utc_unix_seconds,
              gusuku::parseIso8601Utc("2027-01-01T00:05:00Z"));
    // Day 30 fetched on 1 March: February has none and 30 March is still to come, so it is 30 January (old).
    const double march_first = gusuku::parseIso8601Utc("2026-03-01T06:00:00Z");
    EXPECT_EQ(gusuku::weatherFromMetar("METAR RJTT 301200Z 34008KT 9999 FEW030", march_first).utc_unix_seconds,
              gusuku::parseIso8601Utc("2026-01-30T12:00:00Z"));
    // Same day, an hour later than the reference at most: 02 12:25 fetched at 02 12:30 is today.
    const double reference = gusuku::parseIso8601Utc("2026-12-02T12:30:00Z");
    EXPECT_EQ(gusuku::weatherFromMetar("EGLL 021225Z FEW020", reference).utc_unix_seconds, reference - 300.0);
    // Two hours ahead of the reference on the same day: last month's.
    EXPECT_EQ(gusuku::weatherFromMetar("EGLL 021430Z FEW020", reference).utc_unix_seconds,
              gusuku::parseIso8601Utc("2026-11-02T14:30:00Z"));
}

TEST(WeatherService, MalformedMetarsNameTheGroup) {
    const double reference = gusuku::parseIso8601Utc("2026-12-02T12:30:00Z");
    const std::vector<std::vector<std::string>> reports = dataLines("metar_malformed.txt", 2);
    ASSERT_EQ(reports.size(), 14u);
    for (const std::vector<std::string>& report : reports) {
        const std::string message = inputErrorOf([&] { gusuku::weatherFromMetar(report[1], reference); });
        EXPECT_EQ(message.rfind("METAR: " + report[0], 0), 0u) << report[1] << " -> " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_NE(inputErrorOf([] { gusuku::weatherFromMetar("EGLL 021150Z FEW020", NAN); }).find("reference instant"),
              std::string::npos);
}

}  // namespace

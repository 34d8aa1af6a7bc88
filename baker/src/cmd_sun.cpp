// `gusuku-bake sun`: prints the sun's position (NREL SPA) for a place and an ISO 8601 time, for people or, with
// --json, as one JSON object for scripts. Exit codes follow commands.h: 0 ok, 1 bad input, 2 bad usage.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku/assets/site.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku::bake_cli {

namespace {

// |UT1 - UTC| stays under a second by the definition of UTC (leap seconds); --delta-ut1 accepts up to this.
constexpr double kMaxDeltaUt1S = 0.9;

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake sun` must say. The
// defaults are SunObserver's (gusuku/maths/sun.h), which the parser keeps when an option is absent.
CommandHelp sunHelp() {
    const SunObserver defaults;
    const auto range = [](const SiteValueRange& values) {
        return "[" + defaultNumber(values.minimum) + ", " + defaultNumber(values.maximum) + "]";
    };
    CommandHelp help;
    help.usage = "usage: gusuku-bake sun --lat DEG --lon DEG --time ISO8601 [options]";
    help.description = "Prints the sun's position seen from a place at an instant (NREL SPA, Reda and Andreas 2004).";
    help.options = {
        {"--lat", "", "DEG", "geodetic latitude, north positive, " + range(kSiteLatitudeRangeDeg) + " (required)", ""},
        {"--lon", "", "DEG", "longitude, east positive, " + range(kSiteLongitudeRangeDeg) + " (required)", ""},
        {"--time", "", "ISO8601",
         "instant with an explicit offset, e.g. 2026-06-21T09:00:00+09:00 or ...Z (required)", ""},
        {"--height", "", "M", "height above the WGS84 ellipsoid, metres, " + range(kSiteHeightRangeM),
         defaultNumber(defaults.height_m)},
        {"--pressure", "", "MBAR", "annual mean pressure for refraction, mbar, " + range(kSitePressureRangeMbar),
         "the standard atmosphere at --height, " + defaultNumber(standardAtmospherePressureMbar(0.0)) +
             " mbar at 0 m"},
        {"--temperature", "", "C",
         "annual mean temperature for refraction, Celsius, " + range(kSiteTemperatureRangeC),
         defaultNumber(defaults.temperature_c)},
        {"--delta-t", "", "S", "Delta T = TT - UT1, seconds (the default is the IERS value for the mid-2020s)",
         defaultNumber(defaults.delta_t_s)},
        {"--delta-ut1", "", "S", "UT1 - UTC, seconds, [-" + defaultNumber(kMaxDeltaUt1S) + ", " + defaultNumber(kMaxDeltaUt1S) + "]",
         defaultNumber(defaults.delta_ut1_s)},
        {"--json", "", "", "print one JSON object instead of text", ""},
    };
    help.notes =
        "Azimuth is east of north; elevation and zenith are apparent (refracted) unless said otherwise.\n"
        "The ENU vector points towards the sun: (cos e sin A, cos e cos A, sin e).\n"
        "The ranges are site.json's. Exit status: 0 ok, 1 bad value, 2 bad usage.";
    return help;
}

// The zone the user wrote the time in (minutes east of UTC), so the local time is echoed back in it. The text
// has already been accepted by parseIso8601Utc, so it ends in 'Z' or '+hh:mm'/'-hh:mm'.
int utcOffsetMinutesOf(const std::string& iso_text) {
    if (iso_text.back() == 'Z') return 0;
    const std::string suffix = iso_text.substr(iso_text.size() - 6);
    const int minutes = std::stoi(suffix.substr(1, 2)) * 60 + std::stoi(suffix.substr(4, 2));
    return suffix[0] == '-' ? -minutes : minutes;
}

// computeSunPosition names the SunObserver field in its message; the user typed an option.
std::string optionOfField(const std::string& message) {
    static const std::map<std::string, std::string> kOptionByField = {
        {"latitude_deg", "--lat"},       {"longitude_deg", "--lon"},  {"height_m", "--height"},
        {"pressure_mbar", "--pressure"}, {"temperature_c", "--temperature"}, {"delta_t_s", "--delta-t"},
        {"delta_ut1_s", "--delta-ut1"},  {"utc_seconds", "--time"},
    };
    const std::string field = message.substr(0, message.find(' '));
    const auto found = kOptionByField.find(field);
    return found == kOptionByField.end() ? "" : found->second;
}

struct SunRequest {
    SunObserver observer;
    std::string time_text;
    double utc_seconds = 0.0;
    bool json = false;
};

SunRequest parseArguments(CommandLine& line) {
    SunRequest request;
    request.json = line.flag("--json");
    // The same ranges as site.json's (gusuku/assets/site.h), so the command refuses what a site would.
    auto inRange = [&](const char* option, const SiteValueRange& range) {
        return line.number(option, range.minimum, range.maximum);
    };
    const std::optional<double> latitude = inRange("--lat", kSiteLatitudeRangeDeg);
    const std::optional<double> longitude = inRange("--lon", kSiteLongitudeRangeDeg);
    request.observer.height_m = inRange("--height", kSiteHeightRangeM).value_or(request.observer.height_m);
    // Absent, the pressure stays negative: SunObserver then takes the standard atmosphere at the height.
    if (const std::optional<double> pressure = inRange("--pressure", kSitePressureRangeMbar))
        request.observer.pressure_mbar = *pressure;
    request.observer.temperature_c =
        inRange("--temperature", kSiteTemperatureRangeC).value_or(request.observer.temperature_c);
    request.observer.delta_t_s = line.number("--delta-t", -1e6, 1e6).value_or(request.observer.delta_t_s);
    request.observer.delta_ut1_s =
        line.number("--delta-ut1", -kMaxDeltaUt1S, kMaxDeltaUt1S).value_or(request.observer.delta_ut1_s);
    const std::optional<std::string> time_text = line.text("--time");
    line.finish();  // anything else, positionals included, is bad usage

    if (!latitude) line.failValue("--lat", "missing; give the latitude in degrees, north positive");
    if (!longitude) line.failValue("--lon", "missing; give the longitude in degrees, east positive");
    if (!time_text)
        line.failValue("--time", "missing; give an ISO 8601 time with an offset, e.g. 2026-06-21T09:00:00+09:00");
    request.observer.latitude_deg = *latitude;
    request.observer.longitude_deg = *longitude;
    request.time_text = *time_text;
    try {
        request.utc_seconds = parseIso8601Utc(*time_text);
    } catch (const std::invalid_argument& error) {
        line.failValue("--time", error.what());
    }
    return request;
}

// The pressure the refraction used: the user's, or sun.h's documented standard-atmosphere default.
double pressureUsedMbar(const SunObserver& observer) {
    return observer.pressure_mbar >= 0.0 ? observer.pressure_mbar : standardAtmospherePressureMbar(observer.height_m);
}

void printJson(const SunRequest& request, const SunPosition& sun) {
    const SunObserver& observer = request.observer;
    nlohmann::ordered_json json;
    json["utc"] = formatIso8601(request.utc_seconds, 0);
    json["local_time"] = formatIso8601(request.utc_seconds, utcOffsetMinutesOf(request.time_text));
    json["julian_day"] = sun.julian_day;
    json["latitude_deg"] = observer.latitude_deg;
    json["longitude_deg"] = observer.longitude_deg;
    json["height_m"] = observer.height_m;
    json["pressure_mbar"] = pressureUsedMbar(observer);
    json["temperature_c"] = observer.temperature_c;
    json["delta_t_s"] = observer.delta_t_s;
    json["delta_ut1_s"] = observer.delta_ut1_s;
    json["azimuth_deg"] = sun.azimuth_deg;
    json["apparent_elevation_deg"] = sun.apparent_elevation_deg;
    json["apparent_zenith_deg"] = sun.apparent_zenith_deg;
    json["topocentric_zenith_deg"] = sun.topocentric_zenith_deg;
    json["enu"] = {sun.direction_enu.x, sun.direction_enu.y, sun.direction_enu.z};
    json["above_horizon"] = sun.above_horizon;
    std::printf("%s\n", json.dump(2).c_str());
}

void printText(const SunRequest& request, const SunPosition& sun) {
    const SunObserver& observer = request.observer;
    std::printf("sun seen from %.6f %s, %.6f %s, %.1f m\n", std::fabs(observer.latitude_deg),
                observer.latitude_deg < 0.0 ? "S" : "N", std::fabs(observer.longitude_deg),
                observer.longitude_deg < 0.0 ? "W" : "E", observer.height_m);
    std::printf("  time (UTC)              %s\n", formatIso8601(request.utc_seconds, 0).c_str());
    std::printf("  time (local)            %s\n",
                formatIso8601(request.utc_seconds, utcOffsetMinutesOf(request.time_text)).c_str());
    std::printf("  julian day (UT)         %.6f\n", sun.julian_day);
    std::printf("  azimuth                 %.4f deg east of north\n", sun.azimuth_deg);
    std::printf("  apparent elevation      %.4f deg\n", sun.apparent_elevation_deg);
    std::printf("  apparent zenith         %.4f deg (%.4f deg without refraction)\n", sun.apparent_zenith_deg,
                sun.topocentric_zenith_deg);
    std::printf("  direction (E, N, U)     (%.6f, %.6f, %.6f)\n", sun.direction_enu.x, sun.direction_enu.y,
                sun.direction_enu.z);
    std::printf("  refraction air          %.1f mbar%s, %.1f C; delta T %.1f s, delta UT1 %.3f s\n",
                pressureUsedMbar(observer), observer.pressure_mbar < 0.0 ? " (standard atmosphere)" : "",
                observer.temperature_c, observer.delta_t_s, observer.delta_ut1_s);
    if (!sun.above_horizon) std::printf("  the sun is below the horizon\n");
}

}  // namespace

int runSunCommand(const std::vector<std::string>& args) {
    SunRequest request;
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake sun", args, sunHelp(), true,
                                                             [&](CommandLine& line) { request = parseArguments(line); }))
        return *exit_code;
    SunPosition sun;
    try {
        sun = computeSunPosition(request.observer, request.utc_seconds);
    } catch (const std::invalid_argument& error) {
        // The sun code's own checks: reported naming the option, exit 1, like CommandLine's OptionValueError.
        const std::string option = optionOfField(error.what());
        std::fprintf(stderr, "gusuku-bake sun: %s%s%s\n", option.c_str(), option.empty() ? "" : ": ", error.what());
        return 1;
    }
    if (request.json) printJson(request, sun);
    else printText(request, sun);
    return 0;
}

}  // namespace gusuku::bake_cli

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
#include "gusuku/sun.h"
#include "gusuku/time_utc.h"

namespace gusuku::bake_cli {

namespace {

constexpr const char* kSunUsage =
    "usage: gusuku-bake sun --lat DEG --lon DEG --time ISO8601 [options]\n"
    "\n"
    "Prints the sun's position seen from a place at an instant (NREL SPA, Reda and Andreas 2004).\n"
    "\n"
    "required:\n"
    "  --lat DEG            geodetic latitude, north positive, [-90, 90]\n"
    "  --lon DEG            longitude, east positive, [-180, 180]\n"
    "  --time ISO8601       instant with an explicit offset, e.g. 2026-06-21T09:00:00+09:00 or ...Z\n"
    "options:\n"
    "  --height M           height above the WGS84 ellipsoid, metres (default 0)\n"
    "  --pressure MBAR      annual mean pressure for refraction, (0, 5000] mbar\n"
    "                       (default: the standard atmosphere at --height, 1013.25 mbar at 0 m)\n"
    "  --temperature C      annual mean temperature for refraction, Celsius (default 15)\n"
    "  --delta-t S          Delta T = TT - UT1, seconds (default 69.2, the IERS value for the mid-2020s)\n"
    "  --delta-ut1 S        UT1 - UTC, seconds, |S| < 1 (default 0)\n"
    "  --json               print one JSON object instead of text\n"
    "  -h, --help           print this help\n"
    "\n"
    "Azimuth is east of north; elevation and zenith are apparent (refracted) unless said otherwise.\n"
    "The ENU vector points towards the sun: (cos e sin A, cos e cos A, sin e).\n"
    "Exit status: 0 ok, 1 bad value, 2 bad usage.\n";

// A problem with one option's value: reported naming the option, exit 1.
struct BadValue {
    std::string option;
    std::string problem;
};

// A malformed command line (unknown option, missing value): exit 2.
struct BadUsage {
    std::string problem;
};

double parseNumber(const std::string& option, const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (text.empty() || end != begin + text.size() || !std::isfinite(value))
        throw BadValue{option, "'" + text + "' is not a finite number"};
    return value;
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
    bool help = false;
};

SunRequest parseArguments(const std::vector<std::string>& args) {
    SunRequest request;
    std::optional<double> latitude, longitude;
    std::optional<std::string> time_text;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& option = args[i];
        if (option == "-h" || option == "--help") {
            request.help = true;
            return request;
        }
        if (option == "--json") {
            request.json = true;
            continue;
        }
        static const char* kValueOptions[] = {"--lat",         "--lon",     "--height",    "--time",
                                              "--pressure",    "--temperature", "--delta-t", "--delta-ut1"};
        bool known = false;
        for (const char* name : kValueOptions) known = known || option == name;
        if (!known) throw BadUsage{"unknown option '" + option + "'"};
        if (i + 1 >= args.size()) throw BadUsage{option + " needs a value"};
        const std::string& value = args[++i];
        if (option == "--lat") latitude = parseNumber(option, value);
        else if (option == "--lon") longitude = parseNumber(option, value);
        else if (option == "--height") request.observer.height_m = parseNumber(option, value);
        else if (option == "--time") time_text = value;
        else if (option == "--pressure") {
            // A typed pressure must be a real one: SunObserver reads a negative value as "use the default".
            request.observer.pressure_mbar = parseNumber(option, value);
            if (request.observer.pressure_mbar <= 0.0) throw BadValue{option, value + " mbar is not in (0, 5000]"};
        }
        else if (option == "--temperature") request.observer.temperature_c = parseNumber(option, value);
        else if (option == "--delta-t") request.observer.delta_t_s = parseNumber(option, value);
        else if (option == "--delta-ut1") request.observer.delta_ut1_s = parseNumber(option, value);
    }
    if (!latitude) throw BadValue{"--lat", "missing; give the latitude in degrees, north positive"};
    if (!longitude) throw BadValue{"--lon", "missing; give the longitude in degrees, east positive"};
    if (!time_text)
        throw BadValue{"--time", "missing; give an ISO 8601 time with an offset, e.g. 2026-06-21T09:00:00+09:00"};
    request.observer.latitude_deg = *latitude;
    request.observer.longitude_deg = *longitude;
    request.time_text = *time_text;
    try {
        request.utc_seconds = parseIso8601Utc(*time_text);
    } catch (const std::invalid_argument& error) {
        throw BadValue{"--time", error.what()};
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
    try {
        const SunRequest request = parseArguments(args);
        if (request.help) {
            std::printf("%s", kSunUsage);
            return 0;
        }
        SunPosition sun;
        try {
            sun = computeSunPosition(request.observer, request.utc_seconds);
        } catch (const std::invalid_argument& error) {
            throw BadValue{optionOfField(error.what()), error.what()};
        }
        if (request.json) printJson(request, sun);
        else printText(request, sun);
        return 0;
    } catch (const BadValue& bad) {
        std::fprintf(stderr, "gusuku-bake sun: %s%s%s\n", bad.option.c_str(), bad.option.empty() ? "" : ": ",
                     bad.problem.c_str());
        return 1;
    } catch (const BadUsage& bad) {
        std::fprintf(stderr, "gusuku-bake sun: %s\n\n%s", bad.problem.c_str(), kSunUsage);
        return 2;
    }
}

}  // namespace gusuku::bake_cli

// Open-Meteo's /v1/forecast answer into gusuku::Weather (gusuku/loader/weather_service.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gusuku/loader/weather_service.h"
#include "gusuku/maths/input_error.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku {

namespace {

using nlohmann::json;

// Open-Meteo's largest zone offsets are +-14 h; 18 h is ISO 8601's bound.
constexpr double kLargestUtcOffsetSeconds = 18.0 * 3600.0;
// The asked instant may lie this far outside the hourly arrays' span (the hour nearest it is still one hour off).
constexpr double kHourlySpanMarginSeconds = 3600.0;
// UTC seconds a time may be (some 3000 years either side of 1970: within what formatIso8601 writes).
constexpr double kLargestUtcSeconds = 1e11;

std::string numberText(double value) {
    std::ostringstream text;
    text.precision(10);
    text << value;
    return text.str();
}

std::string typeOf(const json& value) {
    switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "an unsupported value";
    }
}

// nlohmann's what() without its "[json.exception.parse_error.101] " prefix.
std::string withoutPrefix(const std::string& what) {
    const size_t end = what.find("] ");
    return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

json parseAnswer(const std::string& text, const std::string& name) {
    json answer;
    try {
        answer = json::parse(text);
    } catch (const json::parse_error& error) {
        throw InputError(name, "byte " + std::to_string(error.byte), "not JSON: " + withoutPrefix(error.what()));
    } catch (const json::exception& error) {
        // 1e999 overflows a double: refused by the parser without a position.
        throw InputError(name, "", "not JSON Open-Meteo writes: " + withoutPrefix(error.what()));
    }
    if (!answer.is_object()) throw InputError(name, "/", "expected an object, found " + typeOf(answer));
    // Open-Meteo answers a bad request with {"error": true, "reason": "..."}.
    const auto error = answer.find("error");
    if (error != answer.end() && error->is_boolean() && error->get<bool>()) {
        const auto reason = answer.find("reason");
        throw InputError(name, "/error", "the service refused the request: " +
                                             (reason != answer.end() && reason->is_string()
                                                  ? quotedForMessage(reason->get<std::string>())
                                                  : std::string("no reason given")));
    }
    return answer;
}

const json& member(const json& object, const std::string& key, const std::string& pointer, const std::string& name,
                   const std::string& hint) {
    const auto found = object.find(key);
    if (found == object.end()) throw InputError(name, pointer + "/" + key, "missing" + hint);
    return *found;
}

const json& objectMember(const json& object, const std::string& key, const std::string& name,
                         const std::string& hint) {
    const json& value = member(object, key, "", name, hint);
    if (!value.is_object()) throw InputError(name, "/" + key, "expected an object, found " + typeOf(value));
    return value;
}

double finiteNumber(const json& value, const std::string& pointer, const std::string& name) {
    if (!value.is_number()) throw InputError(name, pointer, "expected a number, found " + typeOf(value));
    const double number = value.get<double>();
    if (!std::isfinite(number)) throw InputError(name, pointer, "is not a finite number");
    return number;
}

double utcOffsetSeconds(const json& answer, const std::string& name) {
    const auto found = answer.find("utc_offset_seconds");
    if (found == answer.end()) return 0.0;  // GMT, Open-Meteo's default zone
    const double offset = finiteNumber(*found, "/utc_offset_seconds", name);
    if (std::fabs(offset) > kLargestUtcOffsetSeconds)
        throw InputError(name, "/utc_offset_seconds", numberText(offset) + " is outside [-64800, 64800] s");
    return offset;
}

// A time value: UTC seconds (timeformat=unixtime) or the answer's local "YYYY-MM-DDThh:mm".
double utcOfTime(const json& value, double utc_offset_seconds, const std::string& pointer, const std::string& name) {
    if (value.is_number()) {
        const double utc = finiteNumber(value, pointer, name);
        if (std::fabs(utc) > kLargestUtcSeconds)
            throw InputError(name, pointer, numberText(utc) + " UTC seconds is outside [-1e11, 1e11]");
        return utc;
    }
    if (!value.is_string())
        throw InputError(name, pointer, "expected a time (a string or UTC seconds), found " + typeOf(value));
    const std::string local = value.get<std::string>();
    if (local.empty() || !std::isdigit(static_cast<unsigned char>(local.back())))
        throw InputError(name, pointer, quotedForMessage(local) + " is not a local time YYYY-MM-DDThh:mm");
    try {
        return parseIso8601Utc(local + "Z") - utc_offset_seconds;
    } catch (const std::invalid_argument&) {
        throw InputError(name, pointer, quotedForMessage(local) + " is not a local time YYYY-MM-DDThh:mm");
    }
}

Weather weatherOfPercent(const json& value, const std::string& pointer, const std::string& name) {
    const double percent = finiteNumber(value, pointer, name);
    if (percent < 0.0 || percent > 100.0)
        throw InputError(name, pointer, numberText(percent) + " is outside [0, 100] %");
    return Weather{float(percent / 100.0)};
}

// "current_units" / "hourly_units", when present, must say the cover is in percent.
void checkPercentUnit(const json& answer, const std::string& units_key, const std::string& name) {
    const auto units = answer.find(units_key);
    if (units == answer.end() || !units->is_object()) return;
    const auto unit = units->find("cloud_cover");
    if (unit == units->end()) return;
    if (!unit->is_string() || unit->get<std::string>() != "%")
        throw InputError(name, "/" + units_key + "/cloud_cover",
                         "expected \"%\", found " + (unit->is_string() ? quotedForMessage(unit->get<std::string>())
                                                                       : typeOf(*unit)));
}

bool isDayOf(const json& value, const std::string& pointer, const std::string& name) {
    if (value.is_boolean()) return value.get<bool>();
    const double number = finiteNumber(value, pointer, name);
    if (number != 0.0 && number != 1.0) throw InputError(name, pointer, numberText(number) + " is neither 0 nor 1");
    return number == 1.0;
}

const char* const kCurrentHint = " (ask with &current=cloud_cover,is_day)";
const char* const kHourlyHint = " (ask with &hourly=cloud_cover)";

}  // namespace

WeatherReading weatherFromOpenMeteoCurrent(const std::string& json_text, const std::string& name) {
    const json answer = parseAnswer(json_text, name);
    const json& current = objectMember(answer, "current", name, kCurrentHint);
    checkPercentUnit(answer, "current_units", name);
    WeatherReading reading;
    reading.source = WeatherSource::kOpenMeteoCurrent;
    reading.read_from = "/current/cloud_cover";
    reading.weather = weatherOfPercent(member(current, "cloud_cover", "/current", name, kCurrentHint),
                                       reading.read_from, name);
    reading.utc_unix_seconds = utcOfTime(member(current, "time", "/current", name, ""), utcOffsetSeconds(answer, name),
                                         "/current/time", name);
    const auto is_day = current.find("is_day");
    if (is_day != current.end()) reading.is_day = isDayOf(*is_day, "/current/is_day", name);
    return reading;
}

WeatherReading weatherFromOpenMeteoHourly(const std::string& json_text, double utc_unix_seconds,
                                          const std::string& name) {
    if (!(std::fabs(utc_unix_seconds) <= kLargestUtcSeconds))
        throw InputError(name, "the asked instant",
                         numberText(utc_unix_seconds) + " UTC seconds is outside [-1e11, 1e11]");
    const json answer = parseAnswer(json_text, name);
    const json& hourly = objectMember(answer, "hourly", name, kHourlyHint);
    checkPercentUnit(answer, "hourly_units", name);
    const json& times = member(hourly, "time", "/hourly", name, "");
    const json& covers = member(hourly, "cloud_cover", "/hourly", name, kHourlyHint);
    if (!times.is_array() || times.empty())
        throw InputError(name, "/hourly/time", "expected a non-empty array, found " + typeOf(times));
    if (!covers.is_array() || covers.size() != times.size())
        throw InputError(name, "/hourly/cloud_cover",
                         "expected an array of " + std::to_string(times.size()) + " values (as /hourly/time), found " +
                             (covers.is_array() ? std::to_string(covers.size()) + " values" : typeOf(covers)));
    const double offset = utcOffsetSeconds(answer, name);
    size_t nearest = 0;
    double nearest_distance = INFINITY, first = INFINITY, last = -INFINITY;
    for (size_t i = 0; i < times.size(); ++i) {
        const double utc = utcOfTime(times[i], offset, "/hourly/time/" + std::to_string(i), name);
        first = std::min(first, utc);
        last = std::max(last, utc);
        const double distance = std::fabs(utc - utc_unix_seconds);
        if (distance < nearest_distance) nearest_distance = distance, nearest = i;
    }
    if (utc_unix_seconds < first - kHourlySpanMarginSeconds || utc_unix_seconds > last + kHourlySpanMarginSeconds)
        throw InputError(name, "/hourly/time",
                         "the asked instant " + formatIso8601(utc_unix_seconds, 0) + " is over an hour outside " +
                             formatIso8601(first, 0) + " to " + formatIso8601(last, 0));
    WeatherReading reading;
    reading.source = WeatherSource::kOpenMeteoHourly;
    reading.read_from = "/hourly/cloud_cover/" + std::to_string(nearest);
    reading.weather = weatherOfPercent(covers[nearest], reading.read_from, name);
    reading.utc_unix_seconds = utcOfTime(times[nearest], offset, "/hourly/time/" + std::to_string(nearest), name);
    const auto is_day = hourly.find("is_day");
    if (is_day != hourly.end() && is_day->is_array() && is_day->size() == times.size())
        reading.is_day = isDayOf((*is_day)[nearest], "/hourly/is_day/" + std::to_string(nearest), name);
    return reading;
}

WeatherReading weatherFromOpenMeteo(const std::string& json_text, double utc_unix_seconds, const std::string& name) {
    const json answer = parseAnswer(json_text, name);
    if (answer.contains("current")) return weatherFromOpenMeteoCurrent(json_text, name);
    if (answer.contains("hourly")) return weatherFromOpenMeteoHourly(json_text, utc_unix_seconds, name);
    throw InputError(name, "/current", "missing, and no /hourly either (ask with &current=cloud_cover,is_day)");
}

}  // namespace gusuku

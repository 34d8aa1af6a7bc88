// Open-Meteo's /v1/forecast answer into gusuku::Weather (gusuku/weather/weather_service.h), read with the
// standard-library JSON reader (json_reader.h) so that a phone build has it.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gusuku/weather/weather_service.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"
#include "json_reader.h"

namespace gusuku {

namespace {

using json_detail::JsonValue;
using Type = JsonValue::Type;

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

const char* typeOf(const JsonValue& value) {
    switch (value.type) {
    case Type::kNull: return "null";
    case Type::kObject: return "an object";
    case Type::kArray: return "an array";
    case Type::kString: return "a string";
    case Type::kBool: return "a boolean";
    case Type::kNumber: return "a number";
    }
    return "an unsupported value";
}

JsonValue parseAnswer(const std::string& text, const std::string& name) {
    JsonValue answer;
    try {
        answer = json_detail::parseJson(text, name);
    } catch (const InputError& error) {
        // The reader names the byte (from 0) where the text stops being JSON.
        throw InputError(name, error.field(), "not JSON: " + error.problem());
    }
    if (answer.type != Type::kObject)
        throw InputError(name, "/", std::string("expected an object, found ") + typeOf(answer));
    // Open-Meteo answers a bad request with {"error": true, "reason": "..."}.
    const JsonValue* error = answer.find("error");
    if (error != nullptr && error->type == Type::kBool && error->boolean) {
        const JsonValue* reason = answer.find("reason");
        throw InputError(name, "/error", "the service refused the request: " +
                                             (reason != nullptr && reason->type == Type::kString
                                                  ? quotedForMessage(reason->text)
                                                  : std::string("no reason given")));
    }
    return answer;
}

const JsonValue& member(const JsonValue& object, const std::string& key, const std::string& pointer,
                        const std::string& name, const std::string& hint) {
    const JsonValue* found = object.find(key);
    if (found == nullptr) throw InputError(name, pointer + "/" + key, "missing" + hint);
    return *found;
}

const JsonValue& objectMember(const JsonValue& object, const std::string& key, const std::string& name,
                              const std::string& hint) {
    const JsonValue& value = member(object, key, "", name, hint);
    if (value.type != Type::kObject)
        throw InputError(name, "/" + key, std::string("expected an object, found ") + typeOf(value));
    return value;
}

double finiteNumber(const JsonValue& value, const std::string& pointer, const std::string& name) {
    if (value.type != Type::kNumber)
        throw InputError(name, pointer, std::string("expected a number, found ") + typeOf(value));
    const double number = value.number;
    if (!std::isfinite(number)) throw InputError(name, pointer, "is not a finite number");
    return number;
}

double utcOffsetSeconds(const JsonValue& answer, const std::string& name) {
    const JsonValue* found = answer.find("utc_offset_seconds");
    if (found == nullptr) return 0.0;  // GMT, Open-Meteo's default zone
    const double offset = finiteNumber(*found, "/utc_offset_seconds", name);
    if (std::fabs(offset) > kLargestUtcOffsetSeconds)
        throw InputError(name, "/utc_offset_seconds", numberText(offset) + " is outside [-64800, 64800] s");
    return offset;
}

// A time value: UTC seconds (timeformat=unixtime) or the answer's local "YYYY-MM-DDThh:mm".
double utcOfTime(const JsonValue& value, double utc_offset_seconds, const std::string& pointer,
                 const std::string& name) {
    if (value.type == Type::kNumber) {
        const double utc = finiteNumber(value, pointer, name);
        if (std::fabs(utc) > kLargestUtcSeconds)
            throw InputError(name, pointer, numberText(utc) + " UTC seconds is outside [-1e11, 1e11]");
        return utc;
    }
    if (value.type != Type::kString)
        throw InputError(name, pointer, std::string("expected a time (a string or UTC seconds), found ") + typeOf(value));
    const std::string& local = value.text;
    if (local.empty() || !std::isdigit(static_cast<unsigned char>(local.back())))
        throw InputError(name, pointer, quotedForMessage(local) + " is not a local time YYYY-MM-DDThh:mm");
    try {
        return parseIso8601Utc(local + "Z") - utc_offset_seconds;
    } catch (const std::invalid_argument&) {
        throw InputError(name, pointer, quotedForMessage(local) + " is not a local time YYYY-MM-DDThh:mm");
    }
}

Weather weatherOfPercent(const JsonValue& value, const std::string& pointer, const std::string& name) {
    const double percent = finiteNumber(value, pointer, name);
    if (percent < 0.0 || percent > 100.0)
        throw InputError(name, pointer, numberText(percent) + " is outside [0, 100] %");
    return Weather{float(percent / 100.0)};
}

// "current_units" / "hourly_units", when present, must say the cover is in percent.
void checkPercentUnit(const JsonValue& answer, const std::string& units_key, const std::string& name) {
    const JsonValue* units = answer.find(units_key);
    if (units == nullptr || units->type != Type::kObject) return;
    const JsonValue* unit = units->find("cloud_cover");
    if (unit == nullptr) return;
    if (unit->type != Type::kString || unit->text != "%")
        throw InputError(name, "/" + units_key + "/cloud_cover",
                         "expected \"%\", found " + (unit->type == Type::kString ? quotedForMessage(unit->text)
                                                                                 : std::string(typeOf(*unit))));
}

bool isDayOf(const JsonValue& value, const std::string& pointer, const std::string& name) {
    if (value.type == Type::kBool) return value.boolean;
    const double number = finiteNumber(value, pointer, name);
    if (number != 0.0 && number != 1.0) throw InputError(name, pointer, numberText(number) + " is neither 0 nor 1");
    return number == 1.0;
}

const char* const kCurrentHint = " (ask with &current=cloud_cover,is_day)";
const char* const kHourlyHint = " (ask with &hourly=cloud_cover)";

}  // namespace

WeatherReading weatherFromOpenMeteoCurrent(const std::string& json_text, const std::string& name) {
    const JsonValue answer = parseAnswer(json_text, name);
    const JsonValue& current = objectMember(answer, "current", name, kCurrentHint);
    checkPercentUnit(answer, "current_units", name);
    WeatherReading reading;
    reading.source = WeatherSource::kOpenMeteoCurrent;
    reading.read_from = "/current/cloud_cover";
    reading.weather = weatherOfPercent(member(current, "cloud_cover", "/current", name, kCurrentHint),
                                       reading.read_from, name);
    reading.utc_unix_seconds = utcOfTime(member(current, "time", "/current", name, ""), utcOffsetSeconds(answer, name),
                                         "/current/time", name);
    const JsonValue* is_day = current.find("is_day");
    if (is_day != nullptr) reading.is_day = isDayOf(*is_day, "/current/is_day", name);
    return reading;
}

WeatherReading weatherFromOpenMeteoHourly(const std::string& json_text, double utc_unix_seconds,
                                          const std::string& name) {
    if (!(std::fabs(utc_unix_seconds) <= kLargestUtcSeconds))
        throw InputError(name, "the asked instant",
                         numberText(utc_unix_seconds) + " UTC seconds is outside [-1e11, 1e11]");
    const JsonValue answer = parseAnswer(json_text, name);
    const JsonValue& hourly = objectMember(answer, "hourly", name, kHourlyHint);
    checkPercentUnit(answer, "hourly_units", name);
    const JsonValue& time_member = member(hourly, "time", "/hourly", name, "");
    const JsonValue& cover_member = member(hourly, "cloud_cover", "/hourly", name, kHourlyHint);
    if (time_member.type != Type::kArray || time_member.items.empty())
        throw InputError(name, "/hourly/time",
                         std::string("expected a non-empty array, found ") +
                             (time_member.type == Type::kArray ? "an empty array" : typeOf(time_member)));
    const std::vector<JsonValue>& times = time_member.items;
    if (cover_member.type != Type::kArray || cover_member.items.size() != times.size())
        throw InputError(name, "/hourly/cloud_cover",
                         "expected an array of " + std::to_string(times.size()) + " values (as /hourly/time), found " +
                             (cover_member.type == Type::kArray ? std::to_string(cover_member.items.size()) + " values"
                                                                : std::string(typeOf(cover_member))));
    const std::vector<JsonValue>& covers = cover_member.items;
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
    const JsonValue* is_day = hourly.find("is_day");
    if (is_day != nullptr && is_day->type == Type::kArray && is_day->items.size() == times.size())
        reading.is_day = isDayOf(is_day->items[nearest], "/hourly/is_day/" + std::to_string(nearest), name);
    return reading;
}

WeatherReading weatherFromOpenMeteo(const std::string& json_text, double utc_unix_seconds, const std::string& name) {
    const JsonValue answer = parseAnswer(json_text, name);
    if (answer.find("current") != nullptr) return weatherFromOpenMeteoCurrent(json_text, name);
    if (answer.find("hourly") != nullptr) return weatherFromOpenMeteoHourly(json_text, utc_unix_seconds, name);
    throw InputError(name, "/current", "missing, and no /hourly either (ask with &current=cloud_cover,is_day)");
}

}  // namespace gusuku

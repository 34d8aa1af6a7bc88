// A METAR's sky-cover groups into gusuku::Weather (gusuku/weather/weather_service.h).
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gusuku/weather/weather_service.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku {

namespace {

// The reference instant must lie between 1970 and some 3000 years on (what formatIso8601 writes as YYYY).
constexpr double kLargestReferenceSeconds = 1e11;
// How far a report's time may lie after the reference (the app's clock or the station's running ahead).
constexpr double kClockSkewSeconds = 3600.0;

std::vector<std::string> tokensOf(const std::string& text) {
    std::vector<std::string> tokens;
    std::string token;
    for (const char c : text) {
        if (std::isspace(static_cast<unsigned char>(c))) {
            if (!token.empty()) tokens.push_back(token), token.clear();
        } else {
            token += char(std::toupper(static_cast<unsigned char>(c)));
        }
    }
    if (!token.empty()) tokens.push_back(token);
    // A report ends with '=' in bulletins: on the last group, or alone.
    if (!tokens.empty() && tokens.back().back() == '=') {
        tokens.back().pop_back();
        if (tokens.back().empty()) tokens.pop_back();
    }
    return tokens;
}

bool allDigits(const std::string& text) {
    if (text.empty()) return false;
    for (const char c : text)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

bool isStation(const std::string& token) {
    if (token.size() != 4 || !std::isalpha(static_cast<unsigned char>(token[0]))) return false;
    for (const char c : token)
        if (!std::isalnum(static_cast<unsigned char>(c))) return false;
    return true;
}

// Where the observation ends: remarks and trends describe other weather than the observed sky.
bool endsObservation(const std::string& token) {
    if (token == "RMK" || token == "TEMPO" || token == "BECMG" || token == "NOSIG") return true;
    if (token.rfind("PROB", 0) == 0 && allDigits(token.substr(4))) return true;
    return token.size() > 2 && token.rfind("FM", 0) == 0 && allDigits(token.substr(2));
}

// A height field: three digits (hundreds of feet) or /// (not measured).
bool isHeight(const std::string& text) { return text == "///" || (text.size() == 3 && allDigits(text)); }

// The oktas of a sky-cover group; nothing when the token is no sky group (or "//////", cover not observed);
// InputError when it starts as one but is malformed.
std::optional<float> skyGroupOktas(const std::string& token, const std::string& name) {
    if (token == "SKC" || token == "CLR" || token == "NSC" || token == "NCD" || token == "CAVOK")
        return kMetarClearOktas;
    struct Amount {
        const char* code;
        float oktas;
    };
    static const Amount kAmounts[] = {{"FEW", kMetarFewOktas},
                                      {"SCT", kMetarScatteredOktas},
                                      {"BKN", kMetarBrokenOktas},
                                      {"OVC", kMetarOvercastOktas}};
    for (const Amount& amount : kAmounts) {
        if (token.rfind(amount.code, 0) != 0) continue;
        const std::string height = token.substr(3, 3), type = token.size() > 6 ? token.substr(6) : "";
        if (!isHeight(height) || !(type.empty() || type == "CB" || type == "TCU" || type == "///"))
            throw InputError(name, quotedForMessage(token),
                             "is not a sky-cover group (FEW, SCT, BKN or OVC, a 3-digit height in hundreds of "
                             "feet or ///, then nothing, CB, TCU or ///)");
        return amount.oktas;
    }
    if (token.rfind("VV", 0) == 0) {
        if (!isHeight(token.substr(2)))
            throw InputError(name, quotedForMessage(token),
                             "is not a vertical visibility group (VV and a 3-digit height in hundreds of feet)");
        return kMetarVerticalVisibilityOktas;
    }
    return std::nullopt;
}

// The base of a sky-cover or vertical-visibility group that skyGroupOktas accepted, in feet above the station
// (METAR's heights are hundreds of feet); -1 where it has none (SKC, CAVOK, ...) or it was not measured (///).
float skyGroupBaseFeet(const std::string& token) {
    const size_t digits_at = token.rfind("VV", 0) == 0 ? 2 : 3;
    if (token.size() < digits_at + 3) return -1.0f;
    const std::string height = token.substr(digits_at, 3);
    return allDigits(height) ? float(std::stoi(height)) * 100.0f : -1.0f;
}

int twoDigits(const std::string& text, size_t at) { return (text[at] - '0') * 10 + (text[at + 1] - '0'); }

// The latest instant with DDhhmmZ's day and time that is not after the reference by more than the clock skew
// allowed (a report is an observation: it lies in the past), searched from the month after the reference back
// two months (any three months in a row have a day 29, 30 and 31).
double observationUtc(const std::string& token, double reference_utc, const std::string& name) {
    if (token.size() != 7 || token[6] != 'Z' || !allDigits(token.substr(0, 6)))
        throw InputError(name, "observation time", quotedForMessage(token) + " is not a DDhhmmZ group");
    const int day = twoDigits(token, 0), hour = twoDigits(token, 2), minute = twoDigits(token, 4);
    if (day < 1 || day > 31 || hour > 23 || minute > 59)
        throw InputError(name, "observation time",
                         quotedForMessage(token) + ": day 01-31, hour 00-23 and minute 00-59 expected");
    const std::string reference = formatIso8601(reference_utc, 0);  // "YYYY-MM-..."
    const int reference_year = std::stoi(reference.substr(0, 4)), reference_month = std::stoi(reference.substr(5, 2));
    std::optional<double> latest;
    for (int month_step = -2; month_step <= 1; ++month_step) {
        const int month_index = reference_year * 12 + (reference_month - 1) + month_step;
        char text[64];  // room for any int fields, which -Wformat-truncation counts
        std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:00Z", month_index / 12, month_index % 12 + 1, day,
                      hour, minute);
        double candidate;
        try {
            candidate = parseIso8601Utc(text);
        } catch (const std::invalid_argument&) {
            continue;  // that month has no such day
        }
        if (candidate <= reference_utc + kClockSkewSeconds && (!latest || candidate > *latest)) latest = candidate;
    }
    return *latest;
}

}  // namespace

WeatherReading weatherFromMetar(const std::string& metar, double reference_utc_unix_seconds,
                                const std::string& name) {
    if (!(reference_utc_unix_seconds >= 0.0 && reference_utc_unix_seconds <= kLargestReferenceSeconds))
        throw InputError(name, "the reference instant", "must be UTC seconds in [0, 1e11]");
    const std::vector<std::string> tokens = tokensOf(metar);
    size_t at = 0;
    if (at < tokens.size() && (tokens[at] == "METAR" || tokens[at] == "SPECI")) ++at;
    if (at < tokens.size() && tokens[at] == "COR") ++at;
    if (at >= tokens.size()) throw InputError(name, "station", "missing (the report is empty)");
    if (!isStation(tokens[at]))
        throw InputError(name, "station",
                         quotedForMessage(tokens[at]) +
                             " is not an ICAO station (4 letters or digits, a letter first)");
    WeatherReading reading;
    reading.source = WeatherSource::kMetar;
    reading.station = tokens[at++];
    if (at >= tokens.size()) throw InputError(name, "observation time", "missing (DDhhmmZ after the station)");
    reading.utc_unix_seconds = observationUtc(tokens[at++], reference_utc_unix_seconds, name);
    std::optional<float> largest_oktas;
    for (; at < tokens.size() && !endsObservation(tokens[at]); ++at) {
        const std::optional<float> oktas = skyGroupOktas(tokens[at], name);
        if (!oktas || (largest_oktas && *oktas <= *largest_oktas)) continue;
        largest_oktas = oktas;
        reading.read_from = tokens[at];
        reading.cover_base_feet = skyGroupBaseFeet(tokens[at]);
    }
    if (!largest_oktas)
        throw InputError(name, "sky cover",
                         "no sky-cover group (FEW, SCT, BKN, OVC, VV, SKC, CLR, NSC, NCD or CAVOK) before the "
                         "remarks or a trend");
    reading.weather = Weather{*largest_oktas / 8.0f};
    return reading;
}

}  // namespace gusuku

// gusuku_weather.h's C entry points: weather_service.h's readers behind the C API's error convention (gusuku.h).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "gusuku/formats/input_error.h"
#include "gusuku/weather/gusuku_weather.h"
#include "gusuku/weather/weather_service.h"
#include "gusuku_c_errors.h"

namespace {

using gusuku::c_api_detail::fail;

// Copies text into a fixed field, cut to fit and always zero-terminated.
template <size_t kCapacity>
void copyText(char (&field)[kCapacity], const std::string& text) {
    const size_t length = text.size() < kCapacity - 1 ? text.size() : kCapacity - 1;
    std::memcpy(field, text.data(), length);
    field[length] = '\0';
}

gusuku_weather_source sourceOf(gusuku::WeatherSource source) {
    switch (source) {
    case gusuku::WeatherSource::kOpenMeteoCurrent: return GUSUKU_WEATHER_SOURCE_OPEN_METEO_CURRENT;
    case gusuku::WeatherSource::kOpenMeteoHourly: return GUSUKU_WEATHER_SOURCE_OPEN_METEO_HOURLY;
    case gusuku::WeatherSource::kMetar: return GUSUKU_WEATHER_SOURCE_METAR;
    }
    return GUSUKU_WEATHER_SOURCE_METAR;
}

// The arguments every entry point checks; the message names the first bad one.
gusuku_result checkArguments(const char* function, const char* text, const char* text_name,
                             const gusuku_weather_reading* out_reading) {
    char message[GUSUKU_MESSAGE_CAPACITY];
    if (out_reading == nullptr) {
        std::snprintf(message, sizeof message, "%s: out_reading: is NULL", function);
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message);
    }
    if (out_reading->struct_size != sizeof(gusuku_weather_reading)) {
        std::snprintf(message, sizeof message, "%s: out_reading.struct_size: %u is not %u (sizeof gusuku_weather_reading)",
                      function, unsigned(out_reading->struct_size), unsigned(sizeof(gusuku_weather_reading)));
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message);
    }
    if (text == nullptr) {
        std::snprintf(message, sizeof message, "%s: %s: is NULL", function, text_name);
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message);
    }
    return GUSUKU_OK;
}

// Runs one reader; a text it refuses (InputError) is an invalid argument, named by the reader's message.
template <typename Read>
gusuku_result readInto(const char* function, gusuku_weather_reading* out_reading, Read read) noexcept {
    try {
        const gusuku::WeatherReading reading = read();
        gusuku_weather_reading converted{};
        converted.struct_size = sizeof(gusuku_weather_reading);
        converted.weather.cloud_cover = reading.weather.cloud_cover;
        converted.utc_unix_seconds = reading.utc_unix_seconds;
        converted.source = sourceOf(reading.source);
        converted.is_day = reading.is_day.has_value() ? int32_t(*reading.is_day) : -1;
        copyText(converted.read_from, reading.read_from);
        copyText(converted.station, reading.station);
        converted.cover_base_feet = reading.cover_base_feet;
        converted.regime = gusuku_sky_regime(gusuku::skyRegimeOf(reading));
        *out_reading = converted;  // written whole, only on success
        return GUSUKU_OK;
    } catch (const gusuku::InputError& error) {
        char message[GUSUKU_MESSAGE_CAPACITY];
        std::snprintf(message, sizeof message, "%s: %s", function, error.what());
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message);
    } catch (...) {
        return gusuku::c_api_detail::failFromCurrentException(function);
    }
}

}  // namespace

extern "C" gusuku_result gusuku_weather_from_metar(const char* metar, double reference_utc_unix_seconds,
                                                   gusuku_weather_reading* out_reading) {
    const char* const function = "gusuku_weather_from_metar";
    if (const gusuku_result problem = checkArguments(function, metar, "metar", out_reading)) return problem;
    return readInto(function, out_reading,
                    [&] { return gusuku::weatherFromMetar(metar, reference_utc_unix_seconds); });
}

extern "C" gusuku_result gusuku_weather_from_open_meteo(const char* json_text, double utc_unix_seconds,
                                                        gusuku_weather_reading* out_reading) {
    const char* const function = "gusuku_weather_from_open_meteo";
    if (const gusuku_result problem = checkArguments(function, json_text, "json_text", out_reading)) return problem;
    return readInto(function, out_reading, [&] { return gusuku::weatherFromOpenMeteo(json_text, utc_unix_seconds); });
}

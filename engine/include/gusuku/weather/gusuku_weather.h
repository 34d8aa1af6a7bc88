/* gusuku_weather.h: the C entry points of gusuku_weather (CMake gusuku::weather), which reads a weather service's
 * answer (the text an app fetched; this library makes no network call) into the runtime's gusuku_weather (gusuku.h).
 * C99; include it from C or C++. It wraps gusuku/weather/weather_service.h one to one: read that header for the
 * services (Open-Meteo's /v1/forecast, a METAR), how a METAR class becomes oktas (BKN: 6, OVC: 8) and which times
 * are taken. docs/platform-light.md gives the loop an app runs.
 *
 * Library: the C++ standard library only (its own JSON reader), built in the runtime-only (phone) configuration
 * and installed with the runtime component; it links gusuku::runtime for the C API's results and messages.
 * Errors follow gusuku.h: a gusuku_result, and the message in gusuku_last_error_message(). A text that is not
 * the service's answer (not JSON, a missing or out-of-range cover, a METAR group that is not one) is
 * GUSUKU_ERROR_INVALID_ARGUMENT with "FUNCTION: NAME: FIELD: PROBLEM", FIELD a JSON pointer such as
 * /current/cloud_cover or the METAR group ("gusuku_weather_from_metar: METAR: BKN0X0: ..."); the reading is
 * then untouched. Pure functions of their text: any thread, any time. They allocate while parsing and take
 * microseconds: call them when an answer arrives, not per frame. */
#ifndef GUSUKU_GUSUKU_WEATHER_H
#define GUSUKU_GUSUKU_WEATHER_H

#include <stdint.h>

#include "gusuku/runtime/gusuku.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gusuku_weather_source {
    GUSUKU_WEATHER_SOURCE_OPEN_METEO_CURRENT = 0,  /* Open-Meteo's "current" block */
    GUSUKU_WEATHER_SOURCE_OPEN_METEO_HOURLY = 1,   /* the hour of Open-Meteo's "hourly" arrays nearest the instant */
    GUSUKU_WEATHER_SOURCE_METAR = 2                /* a METAR's sky-cover groups */
} gusuku_weather_source;

/* Bytes of gusuku_weather_reading's text fields, with their terminating zero (longer texts are cut). */
#define GUSUKU_WEATHER_READ_FROM_CAPACITY 64
#define GUSUKU_WEATHER_STATION_CAPACITY 8

/* A service's answer as the runtime takes it (weather_service.h's WeatherReading). struct_size as gusuku.h's
 * rule: the app sets it to sizeof(gusuku_weather_reading); this is the first layout, the one accepted. */
typedef struct gusuku_weather_reading {
    uint32_t struct_size;
    gusuku_weather weather;                           /* cloud_cover in [0, 1]: percent / 100, or oktas / 8 */
    double utc_unix_seconds;                          /* when the answer holds: Open-Meteo's interval or hour
                                                         start, the METAR's observation */
    gusuku_weather_source source;
    int32_t is_day;                                   /* Open-Meteo's is_day: 1 day, 0 night; -1 not given
                                                         (always -1 for a METAR) */
    char read_from[GUSUKU_WEATHER_READ_FROM_CAPACITY];  /* what gave the cover: "/current/cloud_cover",
                                                         "/hourly/cloud_cover/13", "BKN035", "CAVOK" */
    char station[GUSUKU_WEATHER_STATION_CAPACITY];    /* METAR: the ICAO station ("EGLL"); Open-Meteo: "" */
} gusuku_weather_reading;

/* A METAR or SPECI report (zero-terminated), its DDhhmmZ time taken as the latest such instant at most an hour
 * after reference_utc_unix_seconds (when the app fetched it; UTC seconds in [0, 1e11]): weatherFromMetar. */
gusuku_result gusuku_weather_from_metar(const char* metar, double reference_utc_unix_seconds,
                                        gusuku_weather_reading* out_reading);

/* An Open-Meteo /v1/forecast answer (zero-terminated JSON): its "current" block when it has one, else the hour of
 * its "hourly" arrays nearest utc_unix_seconds (which must lie within an hour of their span): weatherFromOpenMeteo. */
gusuku_result gusuku_weather_from_open_meteo(const char* json_text, double utc_unix_seconds,
                                             gusuku_weather_reading* out_reading);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_WEATHER_H */

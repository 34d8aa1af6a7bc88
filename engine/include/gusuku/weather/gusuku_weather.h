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

/* What a report says of the sun (gusuku/maths/sun_visibility.h's SkyRegime): the prior of the sun filter below. */
typedef enum gusuku_sky_regime {
    GUSUKU_SKY_REGIME_UNKNOWN = 0,             /* no report: the frame alone decides */
    GUSUKU_SKY_REGIME_CLEAR = 1,               /* up to 2 oktas: the sun is out */
    GUSUKU_SKY_REGIME_BROKEN = 2,              /* 3-6 oktas: out or hidden */
    GUSUKU_SKY_REGIME_OVERCAST = 3,            /* 7-8 oktas of low or middle cloud: hidden */
    GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST = 4   /* 7-8 oktas based at 16,500 ft or more: a veiled sun, still shadows */
} gusuku_sky_regime;

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
    float cover_base_feet;                            /* METAR: the base of the group that gave the cover, feet
                                                         above the station; -1 not known (and Open-Meteo) */
    gusuku_sky_regime regime;                         /* the sun's prior from the cover and its base */
} gusuku_weather_reading;

/* A METAR or SPECI report (zero-terminated), its DDhhmmZ time taken as the latest such instant at most an hour
 * after reference_utc_unix_seconds (when the app fetched it; UTC seconds in [0, 1e11]): weatherFromMetar. */
gusuku_result gusuku_weather_from_metar(const char* metar, double reference_utc_unix_seconds,
                                        gusuku_weather_reading* out_reading);

/* An Open-Meteo /v1/forecast answer (zero-terminated JSON): its "current" block when it has one, else the hour of
 * its "hourly" arrays nearest utc_unix_seconds (which must lie within an hour of their span): weatherFromOpenMeteo. */
gusuku_result gusuku_weather_from_open_meteo(const char* json_text, double utc_unix_seconds,
                                             gusuku_weather_reading* out_reading);

/* The sun's state apart from the sky's (gusuku/maths/sun_visibility.h's SunVisibilityFilter, docs/platform-light.md):
 * the regime's prior and the frame's evidence decide whether the sun is out, with hysteresis (thresholds 0.3 and
 * 0.7, held 0.5 s) and a 1.5 s ramp. Pass state.sun_visibility * state.sun_strength as the frame's sun_scale
 * (gusuku_frame_input.sun_scale) and the reading's cloud cover as its weather.cloud_cover. */
typedef struct gusuku_sun_evidence {
    float sun_out_probability;  /* [0, 1] */
    float confidence;           /* [0, 1]: 0 no cue in view */
    float sun_strength;         /* measured E_sun over the clear sky's; <= 0 or NaN: not measured */
} gusuku_sun_evidence;

typedef struct gusuku_sun_state {
    int32_t sun_out;            /* the decided state: 1 out, 0 hidden */
    float sun_visibility;       /* [0, 1]: 0 or 1 but during a transition */
    float sun_strength;         /* E_sun's scale while out */
    float posterior;            /* this update's probability of the sun being out */
    int32_t decided_by_frame;   /* 1: the frame's evidence decided; 0: the regime's prior */
    uint32_t changes;           /* state changes since the filter was made */
} gusuku_sun_state;

typedef struct gusuku_sun_filter gusuku_sun_filter;

/* Makes a filter with the default settings (the one allocation; update allocates nothing). */
gusuku_result gusuku_sun_filter_create(gusuku_sun_filter** out_filter);
/* One frame at time_seconds (any monotonic clock); evidence may be NULL. Writes the state after this frame. */
gusuku_result gusuku_sun_filter_update(gusuku_sun_filter* filter, double time_seconds, gusuku_sky_regime regime,
                                       const gusuku_sun_evidence* evidence, gusuku_sun_state* out_state);
/* NULL is a no-op. */
void gusuku_sun_filter_free(gusuku_sun_filter* filter);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_WEATHER_H */

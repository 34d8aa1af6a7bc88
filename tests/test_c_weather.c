/* The weather readers' C entry points (gusuku/weather/gusuku_weather.h) from C99, linked against gusuku_weather
 * alone (it brings the runtime). Checked against values worked out here, not by gusuku:
 *   - a METAR whose only sky group is BKN030: broken is read as 6 oktas (the middle of 5 to 7), cover 6 / 8; its
 *     day-7 12:20Z time, fetched at 2026-12-07T12:30Z, is 1796646000 UTC seconds (Python's datetime);
 *   - an Open-Meteo "current" answer at UTC+1: 40 % is cover 0.4, local 13:15 is 12:15Z (1796645700), is_day 1;
 *   - an "hourly" answer asked at 12:40Z takes the 13:00 hour (the nearer one): 90 %;
 *   - the regime: BKN030 is broken with its base at 3,000 ft; OVC200 (cirrostratus at 20,000 ft) a high thin overcast;
 *     Open-Meteo gives no base (-1);
 *   - the sun filter: under a high veil with no evidence the sun is out at 0.6 strength; a confident frame with no
 *     shadow hides it after the 0.5 s hold and fades it over 1.5 s (frames at 0.1 s: hidden at the 6th frame after,
 *     visibility 0 fifteen frames later);
 *   - bad input (a malformed group, a cover over 100 %, text that is not JSON, NULL text, NULL or unsized reading)
 *     is GUSUKU_ERROR_INVALID_ARGUMENT with a message naming the function and the field, the reading untouched. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gusuku/weather/gusuku_weather.h"
#include "support/c_checks.h"


/* The thread's last message starts with `text` (the whole "FUNCTION: NAME: FIELD: PROBLEM" prefix). */
#define CHECK_MESSAGE_STARTS(text)                                                                                \
    do {                                                                                                          \
        const char* message_ = gusuku_last_error_message();                                                       \
        if (strncmp(message_, (text), strlen(text)) != 0) {                                                       \
            fprintf(stderr, "%s:%d: message \"%s\" does not start \"%s\"\n", __FILE__, __LINE__, message_, (text)); \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

static const double kFetchedAt = 1796646600.0; /* 2026-12-07T12:30:00Z */

static gusuku_weather_reading emptyReading(void) {
    gusuku_weather_reading reading;
    memset(&reading, 0, sizeof reading);
    reading.struct_size = sizeof reading;
    return reading;
}

static void metarBrokenIsSixOktas(void) {
    gusuku_weather_reading reading = emptyReading();
    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z 24008KT 9999 BKN030 05/01 Q1012", kFetchedAt, &reading),
                 GUSUKU_OK);
    CHECK(fabsf(reading.weather.cloud_cover - 6.0f / 8.0f) < 1e-6f);
    CHECK(reading.utc_unix_seconds == 1796646000.0);
    CHECK(reading.source == GUSUKU_WEATHER_SOURCE_METAR);
    CHECK(reading.is_day == -1);
    CHECK(strcmp(reading.read_from, "BKN030") == 0);
    CHECK(strcmp(reading.station, "EDDB") == 0);
    CHECK(reading.struct_size == sizeof reading);
    CHECK(reading.cover_base_feet == 3000.0f);
    CHECK(reading.regime == GUSUKU_SKY_REGIME_BROKEN);
    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z 24008KT 9999 OVC200 05/01 Q1012", kFetchedAt, &reading),
                 GUSUKU_OK);
    CHECK(reading.cover_base_feet == 20000.0f);
    CHECK(reading.regime == GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST);
}

static void openMeteoCurrentAndHourly(void) {
    gusuku_weather_reading reading = emptyReading();
    CHECK_RESULT(gusuku_weather_from_open_meteo(
                     "{\"utc_offset_seconds\": 3600, \"current_units\": {\"cloud_cover\": \"%\"},"
                     " \"current\": {\"time\": \"2026-12-07T13:15\", \"interval\": 900, \"cloud_cover\": 40,"
                     " \"is_day\": 1}}",
                     kFetchedAt, &reading),
                 GUSUKU_OK);
    CHECK(fabsf(reading.weather.cloud_cover - 0.4f) < 1e-6f);
    CHECK(reading.utc_unix_seconds == 1796645700.0);
    CHECK(reading.source == GUSUKU_WEATHER_SOURCE_OPEN_METEO_CURRENT);
    CHECK(reading.is_day == 1);
    CHECK(strcmp(reading.read_from, "/current/cloud_cover") == 0);
    CHECK(reading.station[0] == '\0');
    CHECK(reading.cover_base_feet == -1.0f);
    CHECK(reading.regime == GUSUKU_SKY_REGIME_BROKEN); /* 40 %: 3.2 oktas */

    reading = emptyReading();
    CHECK_RESULT(gusuku_weather_from_open_meteo(
                     "{\"hourly\": {\"time\": [\"2026-12-07T12:00\", \"2026-12-07T13:00\"], \"cloud_cover\": [10, 90]}}",
                     1796647200.0 /* 12:40Z */, &reading),
                 GUSUKU_OK);
    CHECK(fabsf(reading.weather.cloud_cover - 0.9f) < 1e-6f);
    CHECK(reading.utc_unix_seconds == 1796648400.0);
    CHECK(reading.source == GUSUKU_WEATHER_SOURCE_OPEN_METEO_HOURLY);
    CHECK(reading.is_day == -1);
    CHECK(strcmp(reading.read_from, "/hourly/cloud_cover/1") == 0);
}

/* A failed call leaves the reading as it was: every byte of a marked reading survives. */
static void badInputNamesTheField(void) {
    gusuku_weather_reading marked;
    memset(&marked, 0xA5, sizeof marked);
    marked.struct_size = sizeof marked;
    gusuku_weather_reading reading = marked;

    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z 24008KT 9999 BKN0X0 05/01 Q1012", kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_metar: METAR: 'BKN0X0': is not a sky-cover group");
    CHECK(memcmp(&reading, &marked, sizeof reading) == 0);

    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z 24008KT 9999 05/01 Q1012", kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_metar: METAR: sky cover: no sky-cover group");

    CHECK_RESULT(gusuku_weather_from_open_meteo("{\"current\": {\"time\": \"2026-12-07T13:15\", \"cloud_cover\": 140}}",
                                                kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_open_meteo: Open-Meteo answer: /current/cloud_cover: 140 is outside [0, 100] %");
    CHECK(memcmp(&reading, &marked, sizeof reading) == 0);

    CHECK_RESULT(gusuku_weather_from_open_meteo("<html>502 Bad Gateway</html>", kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_open_meteo: Open-Meteo answer: byte 0: not JSON");

    CHECK_RESULT(gusuku_weather_from_open_meteo("{\"current\": {\"time\": \"2026-12-07T13:15\"}}", kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_open_meteo: Open-Meteo answer: /current/cloud_cover: missing");

    CHECK_RESULT(gusuku_weather_from_metar(NULL, kFetchedAt, &reading), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_metar: metar: is NULL");
    CHECK_RESULT(gusuku_weather_from_open_meteo(NULL, kFetchedAt, &reading), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_open_meteo: json_text: is NULL");
    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z BKN030", kFetchedAt, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_metar: out_reading: is NULL");
    CHECK(memcmp(&reading, &marked, sizeof reading) == 0);

    reading.struct_size = 0; /* an unset size */
    CHECK_RESULT(gusuku_weather_from_metar("METAR EDDB 071220Z BKN030", kFetchedAt, &reading),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_weather_from_metar: out_reading.struct_size: 0 is not");
}

static void sunFilterKeepsAVeiledSunAndHidesItOnEvidence(void) {
    gusuku_sun_filter* filter = NULL;
    gusuku_sun_state state;
    gusuku_sun_evidence no_shadow = {0.02f, 1.0f, -1.0f};
    int frame, hidden_at = -1, dark_at = -1;
    CHECK_RESULT(gusuku_sun_filter_create(&filter), GUSUKU_OK);
    CHECK_RESULT(gusuku_sun_filter_update(filter, 0.0, GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST, NULL, &state), GUSUKU_OK);
    CHECK(state.sun_out == 1 && state.sun_visibility == 1.0f && fabsf(state.sun_strength - 0.6f) < 1e-6f);
    CHECK(state.decided_by_frame == 0);
    for (frame = 1; frame <= 40; ++frame) {
        CHECK_RESULT(gusuku_sun_filter_update(filter, frame * 0.1, GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST, &no_shadow,
                                              &state),
                     GUSUKU_OK);
        if (!state.sun_out && hidden_at < 0) hidden_at = frame;
        if (state.sun_visibility == 0.0f && dark_at < 0) dark_at = frame;
    }
    CHECK(state.decided_by_frame == 1);
    CHECK(hidden_at == 6);     /* crossed at frame 1, held 0.5 s */
    CHECK(dark_at == 6 + 15);  /* 1.5 s of 0.1 s frames */
    CHECK(state.changes == 1u);
    CHECK_RESULT(gusuku_sun_filter_update(NULL, 0.0, GUSUKU_SKY_REGIME_CLEAR, NULL, &state),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_sun_filter_update: filter: is NULL");
    CHECK_RESULT(gusuku_sun_filter_update(filter, 0.0, (gusuku_sky_regime)9, NULL, &state),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_STARTS("gusuku_sun_filter_update: regime: not a gusuku_sky_regime");
    CHECK_RESULT(gusuku_sun_filter_create(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    gusuku_sun_filter_free(filter);
    gusuku_sun_filter_free(NULL);
}

int main(void) {
    metarBrokenIsSixOktas();
    sunFilterKeepsAVeiledSunAndHidesItOnEvidence();
    openMeteoCurrentAndHourly();
    badInputNamesTheField();
    if (g_failures != 0) {
        fprintf(stderr, "test_c_weather: %d check(s) failed\n", g_failures);
        return 1;
    }
    printf("test_c_weather: all checks passed\n");
    return 0;
}

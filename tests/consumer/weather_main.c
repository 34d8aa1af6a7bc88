/* The installed weather readers (gusuku::weather, in the runtime component) from C99: a METAR's BKN layer is
 * 6 oktas (cover 0.75), and a report with no sky group is refused with the C API's code and a message naming it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gusuku/weather/gusuku_weather.h>

int main(void) {
    gusuku_weather_reading reading;
    memset(&reading, 0, sizeof reading);
    reading.struct_size = sizeof reading;
    const double fetched_at = 1796646600.0; /* 2026-12-07T12:30:00Z */
    const gusuku_result read =
        gusuku_weather_from_metar("METAR EDDB 071220Z 24008KT 9999 BKN030 05/01 Q1012", fetched_at, &reading);
    printf("consumer weather: %s: cover %.3f from %s\n", gusuku_result_name(read), reading.weather.cloud_cover,
           reading.read_from);
    const gusuku_result refused = gusuku_weather_from_metar("METAR EDDB 071220Z NIL", fetched_at, &reading);
    printf("consumer weather: %s: %s\n", gusuku_result_name(refused), gusuku_last_error_message());
    return read == GUSUKU_OK && fabsf(reading.weather.cloud_cover - 0.75f) < 1e-6f &&
                   refused == GUSUKU_ERROR_INVALID_ARGUMENT && strstr(gusuku_last_error_message(), "sky cover") != NULL
               ? 0
               : 1;
}

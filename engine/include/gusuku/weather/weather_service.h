#pragma once
// Weather from a weather service's answer: the text an app fetched (this library makes no network call) turned
// into the runtime's gusuku::Weather (gusuku/runtime/runtime.h: cloud_cover in [0, 1]). Library gusuku_weather
// (CMake gusuku::weather): the C++ standard library only, so a phone (runtime-only) build has it; the C entry
// points are gusuku/weather/gusuku_weather.h. How often to ask, and what to do when nothing answers:
// docs/platform-light.md.
//
// Two services:
//   - Open-Meteo's /v1/forecast (open-meteo.com/en/docs), asked with &current=cloud_cover,is_day (a "current"
//     block: its "time", "interval" 900 s, "cloud_cover" in percent and "is_day" 0 or 1) or &hourly=cloud_cover
//     ("hourly": "time" and "cloud_cover" arrays of equal length). Times are the answer's local clock
//     ("YYYY-MM-DDThh:mm", utc_offset_seconds east of UTC; 0, GMT, when the answer has none) or, with
//     &timeformat=unixtime, UTC seconds. "current_units"/"hourly_units", when present, must give cloud_cover
//     in "%".
//   - A METAR (WMO FM 15; the US Federal Meteorological Handbook No. 1): "METAR EGLL 021150Z 24012KT 9999 FEW020
//     BKN035 12/08 Q1012". Its sky-cover groups give oktas (eighths of the sky). Layer amounts are summation
//     amounts (each layer's includes those below it), so the cover is the largest layer's. The reports give
//     classes, not oktas; each class is read as the middle of its range, which halves the worst error a class
//     can hide (and the runtime's blend is linear in cover, so a midpoint is also the least mean error):
//       SKC, CLR, NSC, NCD, CAVOK   0 oktas       FEW (1 to 2)  1.5       SCT (3 to 4)  3.5
//       BKN (5 to 7)                6              OVC           8         VV (sky obscured, vertical
//                                                                           visibility) 8
//     A cloud type suffix (CB, TCU, ///) and an unknown height (///) are ignored; "//////" (cover not
//     observed) is skipped. Reading stops at RMK and at a trend (TEMPO, BECMG, NOSIG, FMhhmm, PROBnn): those
//     describe later or remarked weather, not the observation.
//
// Errors: gusuku::InputError "NAME: FIELD: PROBLEM" (NAME the caller's name for the text, FIELD a JSON pointer
// such as /current/cloud_cover, or the METAR group) for text that is not JSON, a missing or non-numeric cover, a
// cover outside [0, 100] %, an instant no hour is near, a METAR with no station, time or sky group, or a group
// that is not one. Never a crash on any bytes (tests/fuzz/fuzz_weather_service.cpp). Pure functions of their
// text; they allocate (parsing) and take microseconds: call them when an answer arrives, not per frame.

#include <optional>
#include <string>

#include "gusuku/maths/sun_visibility.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {

enum class WeatherSource {
    kOpenMeteoCurrent,  ///< Open-Meteo's "current" block
    kOpenMeteoHourly,   ///< the hour of Open-Meteo's "hourly" arrays nearest the asked instant
    kMetar,             ///< a METAR's sky-cover groups
};

/// The okta values chosen for the METAR classes (see above).
inline constexpr float kMetarClearOktas = 0.0f;
inline constexpr float kMetarFewOktas = 1.5f;
inline constexpr float kMetarScatteredOktas = 3.5f;
inline constexpr float kMetarBrokenOktas = 6.0f;
inline constexpr float kMetarOvercastOktas = 8.0f;
inline constexpr float kMetarVerticalVisibilityOktas = 8.0f;

/// A service's answer as the runtime takes it, and what it was read from.
struct WeatherReading {
    Weather weather;                ///< cloud_cover in [0, 1]: percent / 100, or oktas / 8
    /// When the answer holds, UTC seconds: Open-Meteo's time (the start of its interval or hour), the METAR's
    /// observation.
    double utc_unix_seconds = 0.0;
    WeatherSource source = WeatherSource::kOpenMeteoCurrent;
    /// What gave the cover: a JSON pointer ("/current/cloud_cover", "/hourly/cloud_cover/13") or the METAR group
    /// ("BKN035", "CAVOK").
    std::string read_from;
    std::optional<bool> is_day;  ///< Open-Meteo's is_day, when the answer has it (METAR: nothing)
    /// METAR: the base of the group that gave the cover, feet above the station; -1 not known (no base in the
    /// group, ///, or Open-Meteo). skyRegimeOf reads a high overcast (cirrostratus) from it.
    float cover_base_feet = -1.0f;
    std::string station;         ///< METAR: the ICAO station ("EGLL"); Open-Meteo: empty
};

/// What the report says of the sun, as the prior of SunVisibilityFilter (gusuku/maths/sun_visibility.h): clear,
/// broken, overcast, or a high overcast that keeps the sun (a METAR's OVC or BKN-to-OVC at 16,500 ft or more).
SkyRegime skyRegimeOf(const WeatherReading& reading);

/// The "current" block of an Open-Meteo answer. name: how messages call the text (a URL, a file name).
WeatherReading weatherFromOpenMeteoCurrent(const std::string& json_text,
                                           const std::string& name = "Open-Meteo answer");

/// The hour of the "hourly" arrays nearest utc_unix_seconds (ties: the earlier), which must lie within one hour of
/// the arrays' span; the hour's cover must be a number (Open-Meteo writes null where it has none).
WeatherReading weatherFromOpenMeteoHourly(const std::string& json_text, double utc_unix_seconds,
                                          const std::string& name = "Open-Meteo answer");

/// "current" when the answer has it, else the hour nearest utc_unix_seconds.
WeatherReading weatherFromOpenMeteo(const std::string& json_text, double utc_unix_seconds,
                                    const std::string& name = "Open-Meteo answer");

/// A METAR or SPECI report (an optional "METAR"/"SPECI" and "COR", the station, DDhhmmZ, ...; a trailing '='
/// is allowed). The DDhhmmZ group names a day of the month only: it is taken as the latest such instant not
/// more than an hour after reference_utc_unix_seconds (the time the app fetched it; UTC seconds in [0, 1e11]):
/// a report observes the past, so day 31 23:50 fetched on 1 April at 00:10 is 31 March, and day 30 fetched on
/// 1 March is 30 January (an old report: its utc_unix_seconds says how old).
WeatherReading weatherFromMetar(const std::string& metar, double reference_utc_unix_seconds,
                                const std::string& name = "METAR");

}  // namespace gusuku

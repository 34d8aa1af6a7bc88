// libFuzzer target: the weather adapters (gusuku/weather/weather_service.h) on arbitrary bytes, read both as an
// Open-Meteo answer (current, then the hour nearest an instant) and as a METAR: the text an app fetched from a
// network it does not control. Bad input must end in gusuku::InputError; any other exception, a crash, a
// sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gusuku/weather/weather_service.h"
#include "gusuku/formats/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const double instant = 1782005400.0;  // 2026-06-21T01:30:00Z, inside the seeds' hours
    try {
        gusuku::weatherFromOpenMeteo(text, instant);
    } catch (const gusuku::InputError&) {
    }
    try {
        gusuku::weatherFromOpenMeteoHourly(text, instant);
    } catch (const gusuku::InputError&) {
    }
    try {
        gusuku::weatherFromMetar(text, instant);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

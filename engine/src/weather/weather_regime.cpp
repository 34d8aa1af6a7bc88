// A weather reading's regime: the prior SunVisibilityFilter starts from (gusuku/maths/sun_visibility.h).

#include "gusuku/weather/weather_service.h"

namespace gusuku {

SkyRegime skyRegimeOf(const WeatherReading& reading) {
    return skyRegimeFromCover(reading.weather.cloud_cover, reading.cover_base_feet);
}

}  // namespace gusuku

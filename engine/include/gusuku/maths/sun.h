#pragma once
// Sun position: NREL's Solar Position Algorithm (Reda and Andreas 2004, NREL/TP-560-34302), double precision.
// Accuracy +-0.0003 deg over years -2000..6000. Azimuth is measured east of north (0 = north, 90 = east).

#include <glm/vec3.hpp>

namespace gusuku {

/// Where and under which air the sun is observed. Defaults are documented per field.
struct SunObserver {
    double latitude_deg = 0.0;    ///< geodetic latitude, north positive, [-90, 90]
    double longitude_deg = 0.0;   ///< east positive, [-180, 180]
    double height_m = 0.0;        ///< height above the WGS84 ellipsoid, metres
    /// Annual mean local pressure, mbar; used only by the refraction correction. Default: the standard
    /// atmosphere at height_m (1013.25 * (1 - 2.25577e-5 h)^5.25588), computed when left negative.
    double pressure_mbar = -1.0;
    double temperature_c = 15.0;  ///< annual mean local temperature, Celsius; refraction only
    /// Delta T = TT - UT1 in seconds. Default 69.2 s, the IERS value for the mid-2020s.
    double delta_t_s = 69.2;
    double delta_ut1_s = 0.0;     ///< UT1 - UTC, seconds, |x| < 0.9
    /// Atmospheric refraction at sunrise and sunset, degrees (SPA's 0.5667 default).
    double atmospheric_refraction_deg = 0.5667;
};

struct SunPosition {
    double julian_day = 0.0;              ///< UT Julian day of the instant
    double topocentric_zenith_deg = 0.0;  ///< without refraction
    double apparent_zenith_deg = 0.0;     ///< with refraction (what shadows use)
    double apparent_elevation_deg = 0.0;  ///< 90 - apparent_zenith_deg
    double azimuth_deg = 0.0;             ///< east of north, [0, 360)
    /// Unit vector towards the sun in the site's east-north-up frame:
    /// (cos e sin A, cos e cos A, sin e) with e the apparent elevation and A the azimuth.
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};
    /// True when the apparent elevation is above 0 (the sun's centre is above the mathematical horizon).
    bool above_horizon = false;
};

/// Computes the sun's position for an instant (UTC seconds since the Unix epoch). Throws
/// std::invalid_argument when an observer field is out of range (latitude 200, say): the message names it.
/// A sun below the horizon is a valid result (above_horizon = false), not an error.
SunPosition computeSunPosition(const SunObserver& observer, double utc_seconds);

/// Pressure of the standard atmosphere at a height (m), mbar: 1013.25 * (1 - 2.25577e-5 h)^5.25588, the default
/// for SunObserver::pressure_mbar. 0 above ~44 km, where the formula's base turns negative (no refraction).
double standardAtmospherePressureMbar(double height_m);

}  // namespace gusuku

// NREL's Solar Position Algorithm (Reda and Andreas 2004, NREL/TP-560-34302), double precision, written from
// the paper's steps 3.1 to 3.15 (numbers in comments are the paper's sections). The periodic-term tables are
// in sun_spa_terms.cpp. Only the sun's position is computed: no sunrise/sunset, no surface incidence.
#include "gusuku/maths/sun.h"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gusuku/maths/time_utc.h"
#include "sun_spa_terms.h"

namespace gusuku {

namespace {

constexpr double kJ2000JulianDay = 2451545.0;
constexpr double kDaysPerJulianCentury = 36525.0;
constexpr double kSunRadiusDeg = 0.26667;         // SPA's apparent solar radius, for the refraction cut-off
constexpr double kEarthEquatorialRadiusM = 6378140.0;
constexpr double kEarthPolarAxisRatio = 0.99664719;  // b/a of the SPA's Earth ellipsoid

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }
double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// Wraps an angle into [0, 360).
double wrapDegrees360(double angle_deg) {
    double wrapped = std::fmod(angle_deg, 360.0);
    if (wrapped < 0.0) wrapped += 360.0;
    return wrapped >= 360.0 ? 0.0 : wrapped;  // fmod of a tiny negative can round up to exactly 360
}

std::string formatNumber(double value) {
    std::ostringstream stream;
    stream.precision(10);
    stream << value;
    return stream.str();
}

[[noreturn]] void throwOutOfRange(const char* field, double value, const std::string& range) {
    throw std::invalid_argument(std::string(field) + " " + formatNumber(value) + " is outside " + range);
}

void requireFinite(const char* field, double value) {
    if (!std::isfinite(value)) throw std::invalid_argument(std::string(field) + " is not a finite number");
}

void requireWithin(const char* field, double value, double low, double high) {
    requireFinite(field, value);
    if (value < low || value > high)
        throwOutOfRange(field, value, "[" + formatNumber(low) + ", " + formatNumber(high) + "]");
}

// Checks every observer field the algorithm uses, with the bounds of NREL's reference implementation where
// the paper gives them, so a wrong field is named here rather than producing a silent NaN later.
void validateObserver(const SunObserver& observer, double utc_seconds) {
    requireWithin("latitude_deg", observer.latitude_deg, -90.0, 90.0);
    requireWithin("longitude_deg", observer.longitude_deg, -180.0, 180.0);
    requireFinite("height_m", observer.height_m);
    if (observer.height_m < -6500000.0) throwOutOfRange("height_m", observer.height_m, "[-6500000, inf)");
    requireFinite("pressure_mbar", observer.pressure_mbar);
    if (observer.pressure_mbar >= 0.0 && (observer.pressure_mbar == 0.0 || observer.pressure_mbar > 5000.0))
        throwOutOfRange("pressure_mbar", observer.pressure_mbar, "(0, 5000] (negative selects the default)");
    requireFinite("temperature_c", observer.temperature_c);
    if (observer.temperature_c <= -273.0 || observer.temperature_c >= 6000.0)
        throwOutOfRange("temperature_c", observer.temperature_c, "(-273, 6000)");
    requireWithin("delta_t_s", observer.delta_t_s, -8000.0, 8000.0);
    requireFinite("delta_ut1_s", observer.delta_ut1_s);
    if (std::fabs(observer.delta_ut1_s) >= 1.0) throwOutOfRange("delta_ut1_s", observer.delta_ut1_s, "(-1, 1)");
    requireWithin("atmospheric_refraction_deg", observer.atmospheric_refraction_deg, -5.0, 5.0);
    requireFinite("utc_seconds", utc_seconds);
    // The periodic terms are fitted for the years -2000..6000 (the paper's stated validity).
    const double earliest = -125687260800.0;  // -2000-01-01T00:00:00Z
    const double latest = 127155427200.0;     // 6001-01-01T00:00:00Z
    if (utc_seconds < earliest || utc_seconds >= latest)
        throw std::invalid_argument("utc_seconds " + formatNumber(utc_seconds) +
                                    " is outside the years -2000..6000 that SPA covers");
}

// 3.2: sum over one Earth series of A cos(B + C * JME).
double sumSeries(const spa_terms::EarthSeries& series, double jme) {
    double sum = 0.0;
    for (std::size_t i = 0; i < series.count; ++i) {
        const spa_terms::EarthTerm& term = series.terms[i];
        sum += term.amplitude * std::cos(term.phase_rad + term.frequency_rad_per_millennium * jme);
    }
    return sum;
}

// 3.2: (X0 + X1 JME + X2 JME^2 + ...) / 1e8 with Xi the sum of series i (Horner's scheme).
template <std::size_t N>
double earthPolynomial(const spa_terms::EarthSeries (&series)[N], double jme) {
    double value = 0.0;
    for (std::size_t i = N; i-- > 0;) value = value * jme + sumSeries(series[i], jme);
    return value / 1.0e8;
}

struct Nutation {
    double longitude_deg;  // delta psi
    double obliquity_deg;  // delta epsilon
};

// 3.4: nutation in longitude and obliquity from the five lunisolar fundamental arguments.
Nutation computeNutation(double jce) {
    const double jce2 = jce * jce;
    const double jce3 = jce2 * jce;
    const double arguments_deg[5] = {
        297.85036 + 445267.111480 * jce - 0.0019142 * jce2 + jce3 / 189474.0,  // mean elongation Moon-Sun
        357.52772 + 35999.050340 * jce - 0.0001603 * jce2 - jce3 / 300000.0,   // mean anomaly of the Sun
        134.96298 + 477198.867398 * jce + 0.0086972 * jce2 + jce3 / 56250.0,   // mean anomaly of the Moon
        93.27191 + 483202.017538 * jce - 0.0036825 * jce2 + jce3 / 327270.0,   // Moon's argument of latitude
        125.04452 - 1934.136261 * jce + 0.0020708 * jce2 + jce3 / 450000.0,    // Moon's ascending node
    };
    double longitude_sum = 0.0;
    double obliquity_sum = 0.0;
    for (const spa_terms::NutationTerm& term : spa_terms::kNutationTerms) {
        double argument_deg = 0.0;
        for (int j = 0; j < 5; ++j) argument_deg += arguments_deg[j] * term.argument_multipliers[j];
        const double argument = radians(argument_deg);
        longitude_sum += (term.longitude_a + term.longitude_b * jce) * std::sin(argument);
        obliquity_sum += (term.obliquity_c + term.obliquity_d * jce) * std::cos(argument);
    }
    // The coefficients are in units of 0.0001 arcsecond.
    return {longitude_sum / 36000000.0, obliquity_sum / 36000000.0};
}

// 3.5: mean obliquity of the ecliptic, arcseconds, U = JME / 10 (Laskar's polynomial).
double meanObliquityArcsec(double jme) {
    static constexpr double kCoefficients[11] = {84381.448, -4680.93, -1.55,  1999.25, -51.38, -249.67,
                                                 -39.05,    7.12,     27.87,  5.79,    2.45};
    const double u = jme / 10.0;
    double value = 0.0;
    for (int i = 10; i >= 0; --i) value = value * u + kCoefficients[i];
    return value;
}

// 3.14: atmospheric refraction correction, degrees, for a true topocentric elevation (Bennett's formula
// scaled by pressure and temperature).
double refractionCorrectionDeg(double elevation_deg, double pressure_mbar, double temperature_c) {
    return (pressure_mbar / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02 /
           (60.0 * std::tan(radians(elevation_deg + 10.3 / (elevation_deg + 5.11))));
}

}  // namespace

double standardAtmospherePressureMbar(double height_m) {
    // Above ~44 km the base goes negative; the air is then negligible, so refraction is off.
    const double base = 1.0 - 2.25577e-5 * height_m;
    return base > 0.0 ? 1013.25 * std::pow(base, 5.25588) : 0.0;
}

SunPosition computeSunPosition(const SunObserver& observer, double utc_seconds) {
    validateObserver(observer, utc_seconds);
    const double pressure_mbar = observer.pressure_mbar < 0.0
                                     ? standardAtmospherePressureMbar(observer.height_m)
                                     : observer.pressure_mbar;

    // 3.1: time scales. JD is in UT1 (UTC + delta UT1); JDE is in terrestrial time (+ delta T).
    const double jd = julianDayFromUtcSeconds(utc_seconds + observer.delta_ut1_s);
    const double jde = jd + observer.delta_t_s / 86400.0;
    const double jc = (jd - kJ2000JulianDay) / kDaysPerJulianCentury;
    const double jce = (jde - kJ2000JulianDay) / kDaysPerJulianCentury;
    const double jme = jce / 10.0;

    // 3.2: Earth heliocentric longitude, latitude (degrees) and radius vector (AU).
    const double earth_longitude_deg = wrapDegrees360(degrees(earthPolynomial(spa_terms::kLongitudeSeries, jme)));
    const double earth_latitude_deg = degrees(earthPolynomial(spa_terms::kLatitudeSeries, jme));
    const double earth_sun_distance_au = earthPolynomial(spa_terms::kRadiusSeries, jme);

    // 3.3: geocentric longitude and latitude of the sun (the opposite direction).
    const double geocentric_longitude_deg = wrapDegrees360(earth_longitude_deg + 180.0);
    const double geocentric_latitude_deg = -earth_latitude_deg;

    // 3.4 - 3.5: nutation and the true obliquity of the ecliptic.
    const Nutation nutation = computeNutation(jce);
    const double obliquity_deg = meanObliquityArcsec(jme) / 3600.0 + nutation.obliquity_deg;

    // 3.6 - 3.7: aberration correction and the apparent sun longitude.
    const double aberration_deg = -20.4898 / (3600.0 * earth_sun_distance_au);
    const double apparent_longitude_deg = geocentric_longitude_deg + nutation.longitude_deg + aberration_deg;

    // 3.8: apparent sidereal time at Greenwich.
    const double mean_sidereal_deg = wrapDegrees360(280.46061837 + 360.98564736629 * (jd - kJ2000JulianDay) +
                                                    jc * jc * (0.000387933 - jc / 38710000.0));
    const double sidereal_deg = mean_sidereal_deg + nutation.longitude_deg * std::cos(radians(obliquity_deg));

    // 3.9 - 3.10: geocentric right ascension and declination.
    const double lambda = radians(apparent_longitude_deg);
    const double epsilon = radians(obliquity_deg);
    const double beta = radians(geocentric_latitude_deg);
    const double right_ascension_deg = wrapDegrees360(degrees(
        std::atan2(std::sin(lambda) * std::cos(epsilon) - std::tan(beta) * std::sin(epsilon), std::cos(lambda))));
    const double declination = std::asin(std::sin(beta) * std::cos(epsilon) +
                                         std::cos(beta) * std::sin(epsilon) * std::sin(lambda));

    // 3.11: observer local hour angle.
    const double hour_angle = radians(wrapDegrees360(sidereal_deg + observer.longitude_deg - right_ascension_deg));

    // 3.12: parallax moves the sun from the Earth's centre to the observer (topocentric coordinates).
    const double latitude = radians(observer.latitude_deg);
    const double equatorial_parallax = radians(8.794 / (3600.0 * earth_sun_distance_au));
    const double reduced_latitude = std::atan(kEarthPolarAxisRatio * std::tan(latitude));
    const double height_ratio = observer.height_m / kEarthEquatorialRadiusM;
    const double x = std::cos(reduced_latitude) + height_ratio * std::cos(latitude);
    const double y = kEarthPolarAxisRatio * std::sin(reduced_latitude) + height_ratio * std::sin(latitude);
    const double parallax_denominator =
        std::cos(declination) - x * std::sin(equatorial_parallax) * std::cos(hour_angle);
    const double parallax_in_right_ascension =
        std::atan2(-x * std::sin(equatorial_parallax) * std::sin(hour_angle), parallax_denominator);
    const double topocentric_declination =
        std::atan2((std::sin(declination) - y * std::sin(equatorial_parallax)) * std::cos(parallax_in_right_ascension),
                   parallax_denominator);
    const double topocentric_hour_angle = hour_angle - parallax_in_right_ascension;

    // 3.13: topocentric elevation without refraction.
    const double true_elevation_deg =
        degrees(std::asin(std::sin(latitude) * std::sin(topocentric_declination) +
                          std::cos(latitude) * std::cos(topocentric_declination) * std::cos(topocentric_hour_angle)));

    // 3.14: refraction, applied only while any part of the refracted disc can be above the horizon, as NREL's
    // reference implementation does (below that the formula is meaningless).
    double refraction_deg = 0.0;
    if (true_elevation_deg >= -(kSunRadiusDeg + observer.atmospheric_refraction_deg))
        refraction_deg = refractionCorrectionDeg(true_elevation_deg, pressure_mbar, observer.temperature_c);
    const double apparent_elevation_deg = true_elevation_deg + refraction_deg;

    // 3.15: azimuth, measured from south westwards by astronomers, then turned to east of north.
    const double astronomers_azimuth_deg =
        degrees(std::atan2(std::sin(topocentric_hour_angle),
                           std::cos(topocentric_hour_angle) * std::sin(latitude) -
                               std::tan(topocentric_declination) * std::cos(latitude)));
    const double azimuth_deg = wrapDegrees360(astronomers_azimuth_deg + 180.0);

    SunPosition position;
    position.julian_day = jd;
    position.topocentric_zenith_deg = 90.0 - true_elevation_deg;
    position.apparent_zenith_deg = 90.0 - apparent_elevation_deg;
    position.apparent_elevation_deg = apparent_elevation_deg;
    position.azimuth_deg = azimuth_deg;
    const double elevation = radians(apparent_elevation_deg);
    const double azimuth = radians(azimuth_deg);
    position.direction_enu = {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                              std::sin(elevation)};
    position.above_horizon = apparent_elevation_deg > 0.0;
    return position;
}

}  // namespace gusuku

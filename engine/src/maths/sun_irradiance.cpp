// Clear-sky direct sun (gusuku/maths/sun_irradiance.h): ESRA beam model with Kasten-Young air mass and a per-channel
// reddening. The baker's E_sun for every slot goes through these lines, so a change here changes bake sets:
// keep the arithmetic as it is unless the bake is meant to change.

#include "gusuku/maths/sun_irradiance.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gusuku {

namespace {

constexpr double kSolarConstantWm2 = 1367.0;  // ESRA's I0 (no Sun-Earth distance correction: bake-date agnostic)
// Effective wavelengths of the Rec.709 primaries' channels, nm, and the spectral exponent of the optical depth.
constexpr double kChannelWavelengthNm[3] = {610.0, 550.0, 465.0};
constexpr double kReferenceWavelengthNm = 550.0;
constexpr double kOpticalDepthSpectralExponent = 2.0;

/// Rayleigh optical thickness at air mass m, Kasten (1996) as fitted in ESRA.
double rayleighOpticalThickness(double air_mass) {
    const double m = air_mass;
    if (m <= 20.0)
        return 1.0 / (6.6296 + m * (1.7513 + m * (-0.1202 + m * (0.0065 - m * 0.00013))));
    return 1.0 / (10.4 + 0.718 * m);
}

/// ESRA's broadband beam optical depth: 0.8662 T_L m dR(m).
double beamOpticalDepth(double air_mass, double linke_turbidity) {
    return 0.8662 * linke_turbidity * air_mass * rayleighOpticalThickness(air_mass);
}

void checkArguments(double elevation_deg, double linke_turbidity) {
    if (std::isnan(elevation_deg)) throw std::invalid_argument("clear-sky sun: elevation_deg is NaN");
    if (!std::isfinite(linke_turbidity) || !(linke_turbidity > 0.0))
        throw std::invalid_argument("clear-sky sun: linke_turbidity must be finite and > 0");
}

}  // namespace

double kastenYoungAirMass(double elevation_deg) {
    if (std::isnan(elevation_deg)) throw std::invalid_argument("kastenYoungAirMass: elevation_deg is NaN");
    if (elevation_deg < 0.0) return INFINITY;
    const double h = std::fmin(elevation_deg, 90.0);
    return 1.0 / (std::sin(h * std::numbers::pi / 180.0) + 0.50572 * std::pow(h + 6.07995, -1.6364));
}

glm::dvec3 clearSkySunIrradianceRgb(double elevation_deg, double linke_turbidity) {
    checkArguments(elevation_deg, linke_turbidity);
    if (elevation_deg <= 0.0) return glm::dvec3(0.0);
    const double air_mass = kastenYoungAirMass(elevation_deg);
    const double optical_depth = beamOpticalDepth(air_mass, linke_turbidity);
    const double zenith_optical_depth = beamOpticalDepth(kastenYoungAirMass(90.0), linke_turbidity);
    const double broadband = kSolarConstantWm2 * std::exp(-optical_depth);
    glm::dvec3 irradiance;
    for (int c = 0; c < 3; ++c) {
        const double k = std::pow(kChannelWavelengthNm[c] / kReferenceWavelengthNm, -kOpticalDepthSpectralExponent);
        // Neutral at the zenith; each channel's extra (or missing) depth grows with the path beyond it.
        irradiance[c] = broadband * std::exp(-(k - 1.0) * (optical_depth - zenith_optical_depth));
    }
    return irradiance;
}

double clearSkyDiffuseHorizontalIrradiance(double elevation_deg, double linke_turbidity) {
    checkArguments(elevation_deg, linke_turbidity);
    if (elevation_deg <= 0.0) return 0.0;
    const double t = linke_turbidity;
    const double transmission = -1.5843e-2 + t * (3.0543e-2 + t * 3.797e-4);
    double a0 = 2.6463e-1 + t * (-6.1581e-2 + t * 3.1408e-3);
    if (a0 * transmission < 2e-3) a0 = 2e-3 / transmission;
    const double a1 = 2.0402 + t * (1.8945e-2 - t * 1.1161e-2);
    const double a2 = -1.3025 + t * (3.9231e-2 + t * 8.5079e-3);
    const double s = std::sin(std::fmin(elevation_deg, 90.0) * std::numbers::pi / 180.0);
    return kSolarConstantWm2 * transmission * (a0 + s * (a1 + s * a2));
}

double clearSkyDirectToDiffuseRatio(double elevation_deg, double linke_turbidity) {
    const double diffuse = clearSkyDiffuseHorizontalIrradiance(elevation_deg, linke_turbidity);
    return diffuse > 0.0 ? clearSkySunIrradianceRgb(elevation_deg, linke_turbidity).y / diffuse : 0.0;
}

glm::dvec3 sunElevationScaleRgb(double from_elevation_deg, double to_elevation_deg, double linke_turbidity) {
    const glm::dvec3 from = clearSkySunIrradianceRgb(from_elevation_deg, linke_turbidity);
    const glm::dvec3 to = clearSkySunIrradianceRgb(to_elevation_deg, linke_turbidity);
    glm::dvec3 scale(0.0);
    for (int c = 0; c < 3; ++c) scale[c] = (from[c] > 0.0 && to[c] > 0.0) ? to[c] / from[c] : 0.0;
    return scale;
}

glm::dvec3 carrySunIrradianceRgb(const glm::dvec3& irradiance_rgb, double from_elevation_deg, double to_elevation_deg,
                                 double linke_turbidity) {
    return irradiance_rgb * sunElevationScaleRgb(from_elevation_deg, to_elevation_deg, linke_turbidity);
}

}  // namespace gusuku

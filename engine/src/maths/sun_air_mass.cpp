// The sun's colour by air mass (gusuku/maths/sun_air_mass.h): Rayleigh plus Angstrom aerosol per Rec.709 channel, the
// closed-form aerosol fit to a measured sun, and the carry between elevations.

#include "gusuku/maths/sun_air_mass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gusuku/maths/sun_irradiance.h"

namespace gusuku {

namespace {

constexpr double kChannelWavelengthUm[3] = {0.610, 0.550, 0.465};
// Leckner (1978) Rayleigh optical depth, sea level: 0.008735 lambda^-4.08.
constexpr double kRayleighCoefficient = 0.008735;
constexpr double kRayleighExponent = 4.08;

// 5772 K black body, x 0.3265, y 0.3359 (Kim et al. 2002), through the Rec.709 XYZ-to-RGB matrix, luminance 1.
constexpr double kSunChromaticityX = 0.3265;
constexpr double kSunChromaticityY = 0.3359;

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

double rayleighDepth(int channel) { return kRayleighCoefficient * std::pow(kChannelWavelengthUm[channel], -kRayleighExponent); }
double aerosolDepthPerBeta(int channel) { return std::pow(kChannelWavelengthUm[channel], -kAngstromExponent); }

void checkArguments(double elevation_deg, double angstrom_beta) {
    if (std::isnan(elevation_deg)) throw std::invalid_argument("sun air mass: elevation_deg is NaN");
    if (!std::isfinite(angstrom_beta) || angstrom_beta < 0.0)
        throw std::invalid_argument("sun air mass: angstrom_beta must be finite and >= 0");
}

}  // namespace

glm::dvec3 extraterrestrialSunColourRgb() {
    const double X = kSunChromaticityX / kSunChromaticityY, Y = 1.0;
    const double Z = (1.0 - kSunChromaticityX - kSunChromaticityY) / kSunChromaticityY;
    return {3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
            0.0557 * X - 0.2040 * Y + 1.0570 * Z};
}

glm::dvec3 zenithOpticalDepthRgb(double angstrom_beta) {
    checkArguments(0.0, angstrom_beta);
    glm::dvec3 depth;
    for (int c = 0; c < 3; ++c) depth[c] = rayleighDepth(c) + angstrom_beta * aerosolDepthPerBeta(c);
    return depth;
}

glm::dvec3 sunTransmittanceRgb(double elevation_deg, double angstrom_beta) {
    checkArguments(elevation_deg, angstrom_beta);
    if (elevation_deg <= 0.0) return glm::dvec3(0.0);
    const double air_mass = kastenYoungAirMass(elevation_deg);
    const glm::dvec3 depth = zenithOpticalDepthRgb(angstrom_beta);
    return {std::exp(-depth.r * air_mass), std::exp(-depth.g * air_mass), std::exp(-depth.b * air_mass)};
}

MeasuredSunFit fitAerosolToMeasuredSun(const glm::dvec3& measured_rgb, double elevation_deg) {
    if (std::isnan(elevation_deg)) throw std::invalid_argument("sun air mass: elevation_deg is NaN");
    MeasuredSunFit fit;
    const bool usable = elevation_deg > 0.0 && std::isfinite(measured_rgb.r) && std::isfinite(measured_rgb.b) &&
                        measured_rgb.r > 0.0 && measured_rgb.b > 0.0;
    if (!usable) return fit;  // no colour to fit: luminance only
    const glm::dvec3 sun = extraterrestrialSunColourRgb();
    // Any sign: a sun less red than clean air allows (even bluer than the sun above the air) clamps to beta = 0,
    // which keeps composition exact (a luminance-only rule would flip between the baker's and the runtime's
    // carry when the clamped carry takes a sun across the extraterrestrial colour).
    const double reddening = std::log((measured_rgb.r / measured_rgb.b) / (sun.r / sun.b));
    // ln(R/B over ET's) = (tau_B - tau_R) m = ((R_B - R_R) + beta (A_B - A_R)) m, with A = lambda^-alpha.
    const double air_mass = kastenYoungAirMass(elevation_deg);
    const double rayleigh_spread = rayleighDepth(2) - rayleighDepth(0);
    const double aerosol_spread = aerosolDepthPerBeta(2) - aerosolDepthPerBeta(0);
    fit.unclamped_beta = (reddening / air_mass - rayleigh_spread) / aerosol_spread;
    fit.angstrom_beta = std::clamp(fit.unclamped_beta, kMinAngstromBeta, kMaxAngstromBeta);
    fit.colour_fitted = true;
    return fit;
}

glm::dvec3 carryMeasuredSunRgb(const glm::dvec3& measured_rgb, double from_elevation_deg, double to_elevation_deg) {
    checkArguments(from_elevation_deg, 0.0);
    checkArguments(to_elevation_deg, 0.0);
    if (from_elevation_deg <= 0.0 || to_elevation_deg <= 0.0) return glm::dvec3(0.0);
    const MeasuredSunFit fit = fitAerosolToMeasuredSun(measured_rgb, from_elevation_deg);
    const glm::dvec3 from = sunTransmittanceRgb(from_elevation_deg, fit.angstrom_beta);
    const glm::dvec3 to = sunTransmittanceRgb(to_elevation_deg, fit.angstrom_beta);
    if (fit.colour_fitted) return measured_rgb * (to / from);
    // Luminance only (no usable colour): the colour is kept, scaled as the extraterrestrial sun's transmitted
    // luminance changes.
    const glm::dvec3 sun = extraterrestrialSunColourRgb();
    return measured_rgb * (luminance(sun * to) / luminance(sun * from));
}

double aerosolFromDiffuseColour(const glm::dvec3& diffuse_horizontal_rgb, double sun_elevation_deg) {
    if (std::isnan(sun_elevation_deg)) throw std::invalid_argument("sun air mass: elevation_deg is NaN");
    const glm::dvec3& d = diffuse_horizontal_rgb;
    if (!(sun_elevation_deg > 0.0) || !std::isfinite(d.r) || !std::isfinite(d.b) || !(d.r > 0.0) || !(d.b > 0.0))
        return kDefaultAngstromBeta;
    const double target = d.r / d.b;
    const glm::dvec3 sun = extraterrestrialSunColourRgb();
    // R/B of the scattered light rises with beta (grey aerosol depth adds more to R's small share): bisection.
    auto scatteredRedOverBlue = [&](double beta) {
        const glm::dvec3 t = sunTransmittanceRgb(sun_elevation_deg, beta);
        return sun.r * (1.0 - t.r) / (sun.b * (1.0 - t.b));
    };
    double low = kMinAngstromBeta, high = kMaxAngstromBeta;
    if (target <= scatteredRedOverBlue(low)) return low;
    if (target >= scatteredRedOverBlue(high)) return high;
    for (int step = 0; step < 60; ++step) {
        const double middle = 0.5 * (low + high);
        (scatteredRedOverBlue(middle) < target ? low : high) = middle;
    }
    return 0.5 * (low + high);
}

glm::dvec3 calibratedClearSkySunRgb(const glm::dvec3& diffuse_horizontal_rgb, double photo_sun_elevation_deg,
                                    double to_elevation_deg) {
    checkArguments(photo_sun_elevation_deg, 0.0);
    checkArguments(to_elevation_deg, 0.0);
    const double diffuse_luminance = luminance(diffuse_horizontal_rgb);
    if (photo_sun_elevation_deg <= 0.0 || to_elevation_deg <= 0.0 || !(diffuse_luminance > 0.0) ||
        !std::isfinite(diffuse_luminance))
        return glm::dvec3(0.0);
    const double beta = aerosolFromDiffuseColour(diffuse_horizontal_rgb, photo_sun_elevation_deg);
    const glm::dvec3 sun = extraterrestrialSunColourRgb();
    const glm::dvec3 at_photo = sun * sunTransmittanceRgb(photo_sun_elevation_deg, beta);
    const double direct_luminance_at_photo = clearSkyDirectToDiffuseRatio(photo_sun_elevation_deg) * diffuse_luminance;
    const glm::dvec3 at_target = sun * sunTransmittanceRgb(to_elevation_deg, beta);
    return at_target * (direct_luminance_at_photo / luminance(at_photo));
}

}  // namespace gusuku

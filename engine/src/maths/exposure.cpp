#include "gusuku/maths/exposure.h"

#include <cmath>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun_irradiance.h"

namespace gusuku {

namespace {

std::string numberText(double value) {
    std::ostringstream text;
    text.precision(10);
    text << value;
    return text.str();
}

// A finite value > 0, else InputError "FUNCTION: ARGUMENT: must be finite and > 0, got VALUE".
double requirePositive(const char* function, const char* argument, double value) {
    if (!std::isfinite(value) || !(value > 0.0))
        throw InputError(function, argument, "must be finite and > 0, got " + numberText(value));
    return value;
}

double requireFinite(const char* function, const char* argument, double value) {
    if (!std::isfinite(value)) throw InputError(function, argument, "must be finite, got " + numberText(value));
    return value;
}

// The luminance (cd m^-2) shown at display-linear 1 at EV100 = 0, per model (see the header).
double whiteLuminanceAtEv0(CameraSpeedModel model) {
    if (model == CameraSpeedModel::kStandardOutputSensitivity)
        return kStandardOutputSensitivityConstant / (kLensFactor * 100.0 * kMiddleGreyDisplayLinear);
    return kSaturationSpeedConstant / (kLensFactor * 100.0);
}

// ARCore's linearisation of its gamma-space values (its colour correction's documented power).
constexpr double kArcoreGamma = 2.2;

constexpr double kPlanckianLowestKelvin = 1667.0;
constexpr double kPlanckianHighestKelvin = 25000.0;
// Below this the Planckian white's linear Rec.709 blue is negative (1667 K: -0.04; 2000 K: +0.02).
constexpr double kGainsLowestKelvin = 2000.0;

// Linear Rec.709 of the Planckian white at T with luminance Y = 1.
glm::dvec3 planckianRec709(double temperature_kelvin) {
    const glm::dvec2 xy = planckianChromaticity(temperature_kelvin);
    const glm::dvec3 xyz(xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y);
    return linearRec709FromXyz(xyz);
}

}  // namespace

double ev100FromCamera(double f_number, double exposure_time_s, double iso_speed) {
    requirePositive("ev100FromCamera", "f_number", f_number);
    requirePositive("ev100FromCamera", "exposure_time_s", exposure_time_s);
    requirePositive("ev100FromCamera", "iso_speed", iso_speed);
    return std::log2(f_number * f_number / exposure_time_s * 100.0 / iso_speed);
}

double whiteLuminanceFromEv100(double ev100, CameraSpeedModel model) {
    requireFinite("whiteLuminanceFromEv100", "ev100", ev100);
    return whiteLuminanceAtEv0(model) * std::exp2(ev100);
}

double ev100FromWhiteLuminance(double white_luminance_cd_m2, CameraSpeedModel model) {
    requirePositive("ev100FromWhiteLuminance", "white_luminance_cd_m2", white_luminance_cd_m2);
    return std::log2(white_luminance_cd_m2 / whiteLuminanceAtEv0(model));
}

double ev100FromAverageLuminance(double average_luminance_cd_m2) {
    requirePositive("ev100FromAverageLuminance", "average_luminance_cd_m2", average_luminance_cd_m2);
    return std::log2(average_luminance_cd_m2 * 100.0 / kReflectedLightMeterConstant);
}

double exposureFromEv100(double ev100, double luminance_per_unit, CameraSpeedModel model) {
    requireFinite("exposureFromEv100", "ev100", ev100);
    requirePositive("exposureFromEv100", "luminance_per_unit", luminance_per_unit);
    return luminance_per_unit / whiteLuminanceFromEv100(ev100, model);
}

double ev100FromExposure(double exposure, double luminance_per_unit, CameraSpeedModel model) {
    requirePositive("ev100FromExposure", "exposure", exposure);
    requirePositive("ev100FromExposure", "luminance_per_unit", luminance_per_unit);
    return ev100FromWhiteLuminance(luminance_per_unit / exposure, model);
}

double luminancePerUnitFromClearSun(const glm::dvec3& sun_irradiance_rgb, double apparent_elevation_deg) {
    const char* function = "luminancePerUnitFromClearSun";
    requireFinite(function, "apparent_elevation_deg", apparent_elevation_deg);
    if (!(apparent_elevation_deg > 0.0 && apparent_elevation_deg <= 90.0))
        throw InputError(function, "apparent_elevation_deg",
                         "must be in (0, 90], got " + numberText(apparent_elevation_deg));
    const double sun_luminance = luminanceRec709(sun_irradiance_rgb);
    requirePositive(function, "sun_irradiance_rgb (its luminance)", sun_luminance);
    // Green is the model's broadband value (sun_irradiance.h), the channel nearest the eye's peak.
    const double beam_w_m2 = clearSkySunIrradianceRgb(apparent_elevation_deg).g;
    return kSunLuminousEfficacy * beam_w_m2 / sun_luminance;
}

double neutralExposure(double reference_luminance) {
    requirePositive("neutralExposure", "reference_luminance", reference_luminance);
    return kMiddleGreyDisplayLinear / reference_luminance;
}

double exposureFromArcorePixelIntensity(double pixel_intensity, double reference_luminance) {
    const char* function = "exposureFromArcorePixelIntensity";
    requirePositive(function, "pixel_intensity", pixel_intensity);
    if (pixel_intensity > 1.0)
        throw InputError(function, "pixel_intensity", "must be in (0, 1], got " + numberText(pixel_intensity));
    requirePositive(function, "reference_luminance", reference_luminance);
    return std::pow(pixel_intensity, kArcoreGamma) / reference_luminance;
}

glm::dvec3 whiteBalanceGainsFromArcoreColorCorrection(const glm::dvec3& color_correction_rgb) {
    const char* function = "whiteBalanceGainsFromArcoreColorCorrection";
    requirePositive(function, "color_correction_rgb[0]", color_correction_rgb.r);
    requirePositive(function, "color_correction_rgb[1]", color_correction_rgb.g);
    requirePositive(function, "color_correction_rgb[2]", color_correction_rgb.b);
    // ARCore's green is 1 by definition; dividing by it keeps that true for a caller who scaled all three.
    const glm::dvec3 relative = color_correction_rgb / color_correction_rgb.g;
    return {std::pow(relative.r, kArcoreGamma), 1.0, std::pow(relative.b, kArcoreGamma)};
}

double exposureFromArkitAmbientIntensity(double ambient_intensity_lumens, double reference_luminance) {
    const char* function = "exposureFromArkitAmbientIntensity";
    requirePositive(function, "ambient_intensity_lumens", ambient_intensity_lumens);
    requirePositive(function, "reference_luminance", reference_luminance);
    return kMiddleGreyDisplayLinear / reference_luminance * ambient_intensity_lumens / kArkitNeutralAmbientLumens;
}

glm::dvec2 planckianChromaticity(double temperature_kelvin) {
    const double t = temperature_kelvin;
    if (!std::isfinite(t) || t < kPlanckianLowestKelvin || t > kPlanckianHighestKelvin)
        throw InputError("planckianChromaticity", "temperature_kelvin",
                         "must be in [1667, 25000] K (the Planckian locus fit's range), got " + numberText(t));
    // Kim et al. (2002): x as a cubic in 1/T, y as a cubic in x, each on two or three ranges.
    const double x = t <= 4000.0
                         ? -0.2661239e9 / (t * t * t) - 0.2343589e6 / (t * t) + 0.8776956e3 / t + 0.179910
                         : -3.0258469e9 / (t * t * t) + 2.1070379e6 / (t * t) + 0.2226347e3 / t + 0.240390;
    double y;
    if (t <= 2222.0)
        y = -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683;
    else if (t <= 4000.0)
        y = -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867;
    else
        y = 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    return {x, y};
}

glm::dvec3 whiteBalanceGainsFromColourTemperature(double temperature_kelvin) {
    if (!std::isfinite(temperature_kelvin) || temperature_kelvin < kGainsLowestKelvin ||
        temperature_kelvin > kPlanckianHighestKelvin)
        throw InputError("whiteBalanceGainsFromColourTemperature", "temperature_kelvin",
                         "must be in [2000, 25000] K (below 2000 K the light is outside Rec.709's gamut), got " +
                             numberText(temperature_kelvin));
    const glm::dvec3 light = planckianRec709(temperature_kelvin);
    const glm::dvec3 neutral = planckianRec709(kArkitNeutralTemperatureKelvin);
    const glm::dvec3 gains = light / neutral;
    return gains / luminanceRec709(gains);
}

}  // namespace gusuku

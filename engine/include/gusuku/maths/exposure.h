#pragma once
// The runtime's exposure stated physically (gusuku_maths: glm and the standard library; C++17).
//
// What the runtime does with FrameInput::exposure (gusuku/runtime/runtime.h): the building's display-linear value
// is clamp(radiance x exposure, 0, 1) per linear Rec.709 channel, radiance in the bake set's units. Those units
// are the sky maps' linear radiance units (docs/bakeset.md: irradiance is "sky units x sr", radiance = rho / pi x
// irradiance): whatever scale the sky photo was stored at. A bake set records no absolute scale, so a photometric
// statement needs one number more, the luminance of one bake set unit:
//
//     L_v = k x Y(radiance),   Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec.709's luminance weights, D65 white),
//     k   = luminance_per_unit, cd m^-2 per bake set radiance unit.
//
// Two ways to know k:
//   - the sky maps were stored calibrated in Radiance's convention (W sr^-1 m^-2 per channel, luminance =
//     179 lm/W x Y: Radiance's white efficacy, the efficacy of equal-energy white over the visible band, as
//     Radiance's own tools and HDR captures calibrated for them use): k = kRadianceWhiteEfficacy;
//   - otherwise the bake set's own sun sets it: its E_sun (sky units x sr) at the slot's elevation against the
//     clear-sky beam the baker's model gives there in W m^-2 (gusuku/maths/sun_irradiance.h) times the luminous
//     efficacy of sunlight (luminancePerUnitFromClearSun below; right on a clear day's slot, to some 10 %).
//
// The camera model (ISO 12232, as the photometric exposure of Lagarde and de Rousiers' "Moving Frostbite to PBR",
// 2014, and Filament's camera): a lens at f-number N, exposure time t and ISO speed S puts the focal-plane
// exposure H = q L t / N^2 (lx s) on the sensor for scene luminance L, q = 0.65 (ISO 12232's lens factor: about
// 90 % transmission, vignetting and the cos^4 fall-off of a typical lens). EV100 = log2(N^2 / t) at S = 100, so
// N^2 / t = 2^EV100 S / 100 for any S. The luminance that reaches display-linear 1 is:
//   - saturation-based speed (S = 78 / H_sat, the sensor clips at H_sat): L_white = 78 / (q 100) 2^EV100
//     = 1.2 2^EV100 cd m^-2;
//   - standard output sensitivity (S = 10 / H_sos, H_sos giving sRGB 118/255, display-linear 0.18):
//     L_white = 10 / (q 100 0.18) 2^EV100 = 0.855 2^EV100 cd m^-2.
// So the runtime's exposure for a camera at EV100 is
//
//     exposure = k / L_white(EV100),     e.g. saturation: exposure = k / (1.2 2^EV100).
//
// A reflected-light meter (ISO 2720, K = 12.5) reads EV100 = log2(L_avg 100 / 12.5) for a scene of mean
// luminance L_avg, which then shows at display-linear 12.5 / 120 = 0.104 (saturation) or 12.5 / 85.5 = 0.146
// (SOS): middle grey with the headroom for highlights the standards leave.
//
// The platforms' light estimates are relative (how bright this frame is against a neutral one), so their
// conversions need a reference the bake set gives: reference_luminance, the luminance Y (bake set units) of the
// radiance the bake set predicts for what the camera mostly sees, the ground in view (its cells' albedo / pi x
// (E_without + E_sun cos), gusuku/maths/colour_match.h's groundMatchPredictedRadiance at exposure 1, averaged
// over the frame's ground). "Neutral" is the exposure that shows it at middle grey, display-linear 0.18:
// neutralExposure = 0.18 / reference_luminance. ColourMatch::kGround measures the same ratio from the frame itself
// (observed / predicted on the ground), the fallback when no estimate is given.
//
// White balance: the runtime takes one scalar exposure today; the gains below (vec3, linear Rec.709, relative to
// D65) are for an app that tints the composite or its own content: the runtime does not apply them.
//
// Errors: every function throws gusuku::InputError (gusuku/formats/input_error.h) naming the argument for NaN,
// infinite, zero or negative intensities and out-of-range values. Pure functions, no state.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace gusuku {

/// ISO 12232's lens factor q in H = q L t / N^2.
inline constexpr double kLensFactor = 0.65;
/// ISO 12232 saturation-based speed: S = 78 / H_sat (lx s).
inline constexpr double kSaturationSpeedConstant = 78.0;
/// ISO 12232 standard output sensitivity: S = 10 / H_sos.
inline constexpr double kStandardOutputSensitivityConstant = 10.0;
/// ISO 2720 reflected-light meter calibration constant K (cd m^-2 s).
inline constexpr double kReflectedLightMeterConstant = 12.5;
/// Middle grey, display-linear (sRGB 118/255: what SOS and the platforms' "neutral" put the scene's mean at).
inline constexpr double kMiddleGreyDisplayLinear = 0.18;
/// Radiance's white efficacy, lm/W: luminance = 179 x Y of a map stored in W sr^-1 m^-2 per channel.
inline constexpr double kRadianceWhiteEfficacy = 179.0;
/// Luminous efficacy of the direct sun, lm/W: the luminous solar constant 133.8 klx (Darula, Kittler and Gueymard
/// 2005) over the 1367 W m^-2 of the clear-sky model (gusuku/maths/sun_irradiance.h). Clear-sky beam efficacies
/// measured at the ground lie around 90 to 105 lm/W for mid and high suns and fall for low ones (the atmosphere
/// takes blue and infrared alike, then more of the visible): expect some 10 % from it above 30 degrees, more below.
inline constexpr double kSunLuminousEfficacy = 133800.0 / 1367.0;

/// How the camera's speed is defined (see the header comment).
enum class CameraSpeedModel {
    kSaturation,                  ///< ISO 12232 saturation-based: display-linear 1 at 1.2 x 2^EV100 cd m^-2
    kStandardOutputSensitivity,   ///< ISO 12232 SOS: display-linear 0.18 at 0.154 x 2^EV100 cd m^-2
};

/// EV100 of a camera setting: log2(N^2 / t x 100 / S). ISO 100, f/16, 1/100 s: 14.64 (sunny 16).
double ev100FromCamera(double f_number, double exposure_time_s, double iso_speed);

/// The scene luminance (cd m^-2) shown at display-linear 1 at this EV100: 1.2 x 2^EV100 (saturation) or
/// 0.855 x 2^EV100 (SOS).
double whiteLuminanceFromEv100(double ev100, CameraSpeedModel model = CameraSpeedModel::kSaturation);

/// The inverse of whiteLuminanceFromEv100.
double ev100FromWhiteLuminance(double white_luminance_cd_m2,
                               CameraSpeedModel model = CameraSpeedModel::kSaturation);

/// EV100 a reflected-light meter reads for a scene of mean luminance average_luminance_cd_m2:
/// log2(L 100 / 12.5).
double ev100FromAverageLuminance(double average_luminance_cd_m2);

/// The runtime's exposure (FrameInput::exposure) for a camera at EV100 and a bake set whose radiance unit has
/// luminance_per_unit cd m^-2: luminance_per_unit / whiteLuminanceFromEv100(ev100, model).
double exposureFromEv100(double ev100, double luminance_per_unit,
                         CameraSpeedModel model = CameraSpeedModel::kSaturation);

/// The inverse of exposureFromEv100.
double ev100FromExposure(double exposure, double luminance_per_unit,
                         CameraSpeedModel model = CameraSpeedModel::kSaturation);

/// k (cd m^-2 per bake set radiance unit) from a sunny slot's E_sun (manifest slots[].sun.irradiance_rgb, sky
/// units x sr) at its apparent elevation: kSunLuminousEfficacy x the clear-sky beam (W m^-2, green channel:
/// the broadband value) / Y(E_sun). Assumes the slot's sky was clear (the baker's clear-sky model, Linke
/// turbidity 3); a sun dimmed by thin cloud in the photo gives a k too large by the dimming. The elevation must
/// be in (0, 90]; E_sun's luminance must be finite and positive.
double luminancePerUnitFromClearSun(const glm::dvec3& sun_irradiance_rgb, double apparent_elevation_deg);

/// The exposure that shows reference_luminance (Y, bake set units; see the header comment) at middle grey:
/// 0.18 / reference_luminance.
double neutralExposure(double reference_luminance);

/// ARCore: LightEstimate.getPixelIntensity(), "the pixel intensity of the current camera view in gamma color
/// space", [0, 1] with 0 black and 1 white (developers.google.com/ar/reference/java/com/google/ar/core/
/// LightEstimate); linear by the power 2.2 ARCore gives for its colour correction. The frame's mean display-linear
/// value is then pixel_intensity^2.2, and the exposure that shows the predicted scene so is
///     exposure = pixel_intensity^2.2 / reference_luminance
/// (neutralExposure at pixel_intensity = 0.18^(1/2.2) = 0.459). The mean of gamma values is not the gamma of
/// the mean: a frame of high contrast reads low (half its pixels at linear 0.05 and half at 0.8 give 0.30 for a
/// mean of 0.425, 29 % low); the ground match measures better. pixel_intensity in (0, 1]; 0 (a black frame)
/// is refused: no exposure follows from it.
double exposureFromArcorePixelIntensity(double pixel_intensity, double reference_luminance);

/// ARCore: LightEstimate.getColorCorrection()'s first three values, "RGB scaling factors to be applied to the
/// final color computed in the fragment shader", in gamma space, green "always 1.0 as the green channel is the
/// reference baseline" (same page): linear gains by the power 2.2, so (r^2.2, 1, b^2.2). ARCore's own baseline is
/// the camera's white, taken as D65. Each value finite and > 0.
glm::dvec3 whiteBalanceGainsFromArcoreColorCorrection(const glm::dvec3& color_correction_rgb);

/// The neutral ARKit ambient intensity: "A value of 1000 represents neutral lighting"
/// (developer.apple.com/documentation/arkit/arlightestimate/ambientintensity).
inline constexpr double kArkitNeutralAmbientLumens = 1000.0;
/// The neutral ARKit colour temperature: "A value of 6500 represents neutral (pure white) lighting"
/// (developer.apple.com/documentation/arkit/arlightestimate/ambientcolortemperature).
inline constexpr double kArkitNeutralTemperatureKelvin = 6500.0;

/// ARKit: ARLightEstimate.ambientIntensity, lumens, "based on the internal exposure compensation of the camera"
/// and meant to scale the virtual scene's lights (1000 neutral). Read as this frame's brightness against a
/// neutral one: exposure = neutralExposure(reference_luminance) x ambient_intensity / 1000. ambient_intensity
/// finite and > 0 (ARKit reports 0 to about 2000; 0, a dark frame, is refused).
double exposureFromArkitAmbientIntensity(double ambient_intensity_lumens, double reference_luminance);

/// Chromaticity (CIE 1931 x, y) of a Planckian radiator at temperature_kelvin, Kim et al.'s cubic spline
/// (2002), [1667, 25000] K, for the radiation constant c2 = 1.4388e-2 m K: CIE illuminant A (2856 K at the older
/// c2 = 1.435e-2, so 2848 K here) gives (0.4476, 0.4075), 6500 K (0.3135, 0.3237). Outside the range:
/// InputError.
glm::dvec2 planckianChromaticity(double temperature_kelvin);

/// ARKit: ARLightEstimate.ambientColorTemperature, kelvin (6500 neutral, lower warmer) as per-channel linear
/// Rec.709 gains relative to D65, to tint content as if lit by that light. Convention: the gains are the light's
/// colour, so a warm light gives red > 1 > blue: the linear Rec.709 of the Planckian white at T divided
/// channelwise by that at 6500 K (ARKit's neutral, within 0.003 in u'v' of D65, so 6500 K gives exactly
/// (1, 1, 1)), scaled to luminance Y = 1 (a tint, not a brightness). 3000 K: about (1.70, 0.86, 0.27); 10000 K
/// (0.84, 1.01, 1.38). [2000, 25000] K (below 2000 K the Planckian white leaves Rec.709's gamut: its blue goes
/// negative); outside it, NaN or infinite: InputError.
glm::dvec3 whiteBalanceGainsFromColourTemperature(double temperature_kelvin);

}  // namespace gusuku

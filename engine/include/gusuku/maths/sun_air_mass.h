#pragma once
// The sun's colour against its elevation, per Rec.709 channel, from the air mass it shines through: what the
// baker uses to carry a sun MEASURED in a sky photo (the disc, at the elevation the photo was taken) to each
// slot's elevation, and what the runtime uses to carry a slot's E_sun to the current sun (frame_lighting.h).
//
// Model (Beer-Lambert per channel, single effective wavelength lambda_c per channel):
//   T_c(h, beta) = exp(-(tau_R(lambda_c) + tau_A(lambda_c, beta)) m(h))
//   tau_R(lambda) = 0.008735 lambda^-4.08      Rayleigh, sea level, lambda in micrometres: Leckner (1978), as
//                                              given in Iqbal (1983), "An Introduction to Solar Radiation"; within
//                                              3 % of Bodhaine et al. (1999) over 450-650 nm
//   tau_A(lambda) = beta lambda^-alpha         aerosol, Angstrom (1929): turbidity coefficient beta (the aerosol
//                                              depth at 1 um), exponent alpha = kAngstromExponent = 1.3
//   m(h)                                       relative air mass, Kasten and Young (1989): kastenYoungAirMass in
//                                              gusuku/maths/sun_irradiance.h (m(90) = 1, m(10) = 5.6, m(0) = 37.9)
//   lambda_c = 0.610, 0.550, 0.465 um          the dominant wavelengths of the Rec.709 primaries (ITU-R BT.709
//                                              chromaticities against D65; Bruneton's 2017 three-wavelength
//                                              atmosphere uses 680/550/440 nm, which reddens the low sun about
//                                              1.5x faster: 610/465 is the closer one for a channel's mean)
// Extraterrestrial sun colour (what T multiplies): a 5772 K black body (the IAU 2015 nominal solar effective
// temperature), chromaticity x 0.3265, y 0.3359 on Kim et al.'s (2002) Planckian-locus fit, in linear Rec.709
// normalised to luminance 1: (1.1116, 0.9757, 0.9125), R/B 1.218.
//
// Carrying a measured sun (the baker's disc, or a slot's E_sun at the runtime): one aerosol scalar beta is fitted
// in closed form so that ET_c T_c(h_measured, beta) has the measured R/B:
//   ln((R/B)_measured / (R/B)_ET) = (tau_B - tau_R) m(h_measured), linear in beta
// clamped to [kMinAngstromBeta, kMaxAngstromBeta]; then E(h) = E_measured * T(h, beta) / T(h_measured, beta)
// per channel. That is E(h) = s_c ET_c T_c(h, beta) with s_c fixed at the measured elevation: the measured
// luminance over the extraterrestrial sun's transmitted luminance is the overall scale (a sun dimmed by thin
// cloud in the photo stays dimmed by the same factor at every elevation) and the measured G (which one scalar
// cannot fit) keeps its offset. At the measured elevation the carry is the identity; carrying twice equals
// carrying once, also when the fit is clamped (a fit beyond a bound refitted at another elevation is beyond it
// again: beta' = bound + (beta - bound) m_measured / m_other), so the runtime refitting a slot's E_sun recovers
// the baker's beta and carries it on exactly.
// When the fit fails:
//   - the measured sun is less red than clean air would make it, or even bluer than the extraterrestrial sun
//     ((R/B)_measured < 1.218: a warm white balance, a red channel clipped in the photo's core): beta clamps to
//     0; its colour offset is kept as a per-channel factor and only clean air's reddening is applied on top.
//     (Carrying such a sun's luminance alone, its colour frozen, is NOT done: the clamped carry can take a sun
//     across the extraterrestrial colour, and a rule switching on that colour would make the runtime's second
//     carry disagree with the baker's; the shared low-sun photo does exactly that between 10.5 and 31 deg.)
//   - the measured sun has no usable colour (a channel <= 0 or not finite): its colour is kept and only the
//     luminance is carried, by the luminance of ET T(h, kDefaultAngstromBeta).
//
// Units: elevations are APPARENT elevations in degrees; irradiances are on a plane facing the sun, in any units
// (the functions are ratios), except extraterrestrialSunColourRgb (luminance 1). Pure functions, glm only.

#include <glm/vec3.hpp>

namespace gusuku {

/// Angstrom exponent alpha of the aerosol optical depth (continental aerosol, Angstrom's own 1.3).
inline constexpr double kAngstromExponent = 1.3;
/// Physical range of Angstrom's beta (aerosol depth at 1 um): 0 (pure Rayleigh air) to 0.5 (very hazy; aerosol
/// depth 1.2 at 500 nm). A measured sun redder or less red than this range allows keeps its own colour offset.
inline constexpr double kMinAngstromBeta = 0.0;
inline constexpr double kMaxAngstromBeta = 0.5;
/// A clear sky's beta (aerosol depth 0.25 at 500 nm), used where the colour cannot tell: luminance-only carry.
inline constexpr double kDefaultAngstromBeta = 0.1;

/// Extraterrestrial sun colour in linear Rec.709, luminance 1 (see above).
glm::dvec3 extraterrestrialSunColourRgb();

/// Zenith optical depth per channel, Rayleigh plus aerosol (beta >= 0).
glm::dvec3 zenithOpticalDepthRgb(double angstrom_beta);

/// Direct-beam transmittance per channel at an apparent elevation: exp(-tau_c m(h)); (0, 0, 0) at h <= 0.
/// Throws std::invalid_argument when elevation is NaN or beta is not finite and >= 0.
glm::dvec3 sunTransmittanceRgb(double elevation_deg, double angstrom_beta);

/// The beta fitted to a measured sun (see above).
struct MeasuredSunFit {
    double angstrom_beta = kDefaultAngstromBeta;  ///< the fitted beta, clamped; kDefaultAngstromBeta if !colour_fitted
    double unclamped_beta = 0.0;                  ///< the closed-form value before clamping, any sign
    bool colour_fitted = false;                   ///< false: R or B <= 0 or not finite: luminance only
};

/// Fits beta to a sun of irradiance `measured_rgb` at `elevation_deg` (> 0). Throws std::invalid_argument on a
/// NaN elevation; an elevation <= 0 or a non-finite measurement gives colour_fitted = false.
MeasuredSunFit fitAerosolToMeasuredSun(const glm::dvec3& measured_rgb, double elevation_deg);

/// The measured sun carried from its elevation to another (see above). (0, 0, 0) when either elevation is <= 0.
/// Same throws as sunTransmittanceRgb.
glm::dvec3 carryMeasuredSunRgb(const glm::dvec3& measured_rgb, double from_elevation_deg, double to_elevation_deg);

// ------------------------------------------------------------------------------------------------------------
// The clear-sky fallback (no usable disc in the photo), calibrated on the map's own diffuse light.
//   Colour: beta such that the diffuse light's R/B matches single scattering's energy balance, the light taken
//     out of the beam reappearing as sky light: D_c proportional to ET_c (1 - T_c(h_photo, beta)). Hazier air
//     whitens the sky and reddens the low sun together; one scalar ties them. Bisection over the physical
//     range; a sky bluer than clean air allows gets kMinAngstromBeta, one whiter than the haziest gets
//     kMaxAngstromBeta (an overcast map: its "sun" is a guess either way).
//   Luminance: at the photo's sun elevation the direct normal luminance is ESRA's clear-sky direct/diffuse
//     ratio (clearSkyDirectToDiffuseRatio, T_L = kDefaultLinkeTurbidity) times the map's diffuse horizontal
//     luminance: the ratio of a clear sky at that elevation calibrates the photo's unknown exposure.
//   At other elevations: ET T(h, beta), carried like a measured sun from the photo's elevation.
// h_photo: the direction of a clipped disc where the map shows one, else the slot's own elevation (the photo
// taken about when the slot lights).
// ------------------------------------------------------------------------------------------------------------

/// beta whose single-scattering diffuse colour ET (1 - T(h, beta)) has the R/B of diffuse_horizontal_rgb, at
/// sun elevation h (> 0), clamped to [kMinAngstromBeta, kMaxAngstromBeta]. kDefaultAngstromBeta when the
/// diffuse light has a channel <= 0 or is not finite, or h <= 0.
double aerosolFromDiffuseColour(const glm::dvec3& diffuse_horizontal_rgb, double sun_elevation_deg);

/// E_sun of the fallback at to_elevation_deg (see above), in the map's units (radiance units x sr), given the
/// map's diffuse horizontal irradiance per channel (upper hemisphere, sun removed). (0, 0, 0) when either
/// elevation is <= 0 or the diffuse light is not positive.
glm::dvec3 calibratedClearSkySunRgb(const glm::dvec3& diffuse_horizontal_rgb, double photo_sun_elevation_deg,
                                    double to_elevation_deg);

}  // namespace gusuku

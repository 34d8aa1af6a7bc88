#pragma once
// The sun's direct irradiance against its elevation (docs/design.md 3 and 8): what the baker uses to carry an E_sun
// measured from a sky photo's sun disc to a slot's sun elevation (or to give E_sun outright when the photo cannot
// say), and what the runtime uses once per frame, on the CPU, to carry a slot's E_sun to the current sun.
//
// Model: the ESRA clear-sky beam model (Rigollier, Bauer and Wald 2000, Solar Energy 68(1)) with Kasten and
// Young's (1989) relative air mass, plus a mild per-channel reddening of our own (documented below).
//
// Units and frame: elevations are the sun's APPARENT (refraction-corrected) elevation in degrees, as
// SunPosition::apparent_elevation_deg gives it; irradiance is on a plane facing the sun (direct normal
// irradiance), per linear Rec.709 channel. clearSkySunIrradianceRgb is in W m^-2; the carrying functions are
// ratios, so a measured E_sun keeps whatever units it came in (a bake set's: the sky maps' radiance units times
// steradians). Pure functions, double precision, no state: the same inputs give the same bits on any thread.

#include <glm/vec3.hpp>

namespace gusuku {

/// The Linke turbidity of the clear-sky model the baker uses (a clear, rural-to-urban summer sky). A runtime that
/// carries a bake set's E_sun must use the same value as the baker did, or the carried E_sun jumps at a slot.
inline constexpr double kDefaultLinkeTurbidity = 3.0;

/// Relative optical air mass, Kasten and Young (1989): m = 1 / (sin h + 0.50572 (h + 6.07995)^-1.6364), h the
/// apparent sun elevation in degrees (clamped to 90). m(90) = 0.9997 (about 1), m(30) = 1.9943, m(0) = 37.92.
/// Elevation below 0 -> +infinity (no direct beam). Throws std::invalid_argument on NaN.
double kastenYoungAirMass(double elevation_deg);

/// Direct normal irradiance of a clear sky, W m^-2, per Rec.709 channel, at sea level.
/// Broadband: ESRA beam model: B_n = I0 exp(-0.8662 T_L m dR(m)) with I0 = 1367 W m^-2 (no Sun-Earth distance
/// correction: a bake is date-agnostic in this respect), m Kasten-Young, dR the Rayleigh optical thickness of
/// Kasten (1996) as fitted in ESRA:
///   1/dR = 6.6296 + 1.7513 m - 0.1202 m^2 + 0.0065 m^3 - 0.00013 m^4 (m <= 20), 10.4 + 0.718 m (m > 20).
/// Colour: each channel's optical depth is tau_c = k_c tau with k_c = (lambda_c / 550 nm)^-2 (lambda 610, 550,
/// 465 nm; exponent 2 between aerosol's ~1.3 and Rayleigh's 4), normalised so that the sun at the zenith is
/// neutral: E_c = B_n(m) exp(-(k_c - 1)(tau(m) - tau(1))). So G is the broadband value, R rises and B falls
/// as the sun gets lower (with T_L = 3: R/G 1.04, B/G 0.92 at 30 deg; R/G 1.25, B/G 0.62 at 5 deg; G at the
/// zenith 998 W m^-2). Elevation <= 0 -> (0, 0, 0).
/// Throws std::invalid_argument when elevation is NaN or linke_turbidity is not finite and > 0.
glm::dvec3 clearSkySunIrradianceRgb(double elevation_deg, double linke_turbidity = kDefaultLinkeTurbidity);

/// Diffuse horizontal irradiance of a clear sky, W m^-2 (broadband), ESRA (Rigollier et al. 2000):
///   D_h = I0 Trd(T_L) Fd(h), Trd = -1.5843e-2 + 3.0543e-2 T_L + 3.797e-4 T_L^2,
///   Fd = A0 + A1 sin h + A2 sin^2 h, A0 = 2.6463e-1 - 6.1581e-2 T_L + 3.1408e-3 T_L^2 (raised to 2e-3 / Trd
///   when A0 Trd < 2e-3), A1 = 2.0402 + 1.8945e-2 T_L - 1.1161e-2 T_L^2, A2 = -1.3025 + 3.9231e-2 T_L +
///   8.5079e-3 T_L^2. Elevation <= 0 -> 0. Same throws as clearSkySunIrradianceRgb.
double clearSkyDiffuseHorizontalIrradiance(double elevation_deg, double linke_turbidity = kDefaultLinkeTurbidity);

/// ESRA's clear-sky direct normal over diffuse horizontal irradiance at an elevation (> 0): the broadband (G)
/// value of clearSkySunIrradianceRgb over clearSkyDiffuseHorizontalIrradiance. With T_L = 3: 9.1 at 60 deg,
/// 10.4 at 10 deg (the diffuse light falls with the sun as the beam does). 0 at elevation <= 0.
double clearSkyDirectToDiffuseRatio(double elevation_deg, double linke_turbidity = kDefaultLinkeTurbidity);

/// Per channel, the model's irradiance at to_elevation_deg divided by that at from_elevation_deg: the factor that
/// carries an E_sun known at one sun elevation to another (the colour shift included). 0 in a channel when either
/// elevation is <= 0 (no direct beam to carry from or to). Same throws as clearSkySunIrradianceRgb.
glm::dvec3 sunElevationScaleRgb(double from_elevation_deg, double to_elevation_deg,
                                double linke_turbidity = kDefaultLinkeTurbidity);

/// E_sun carried from the elevation it was measured (or baked) at to another: irradiance_rgb times
/// sunElevationScaleRgb(from, to), per channel. The baker carries the photo's measured disc to each slot with it;
/// the runtime carries a slot's manifest irradiance_rgb (at the slot's apparent_elevation_deg) to the current
/// sun. Carrying is exact under composition up to rounding: carry(carry(E, a, b), b, c) = carry(E, a, c) for
/// a, b, c > 0. A sun at or below the horizon at either end gives (0, 0, 0).
glm::dvec3 carrySunIrradianceRgb(const glm::dvec3& irradiance_rgb, double from_elevation_deg, double to_elevation_deg,
                                 double linke_turbidity = kDefaultLinkeTurbidity);

}  // namespace gusuku

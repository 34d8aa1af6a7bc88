#pragma once
// Analytic skies for the sample site: the CIE standard general sky (Darula and Kittler; ISO 15469:2004 /
// CIE S 011/E:2003) for a clear day, with a sun disc, and the CIE standard overcast sky (Moon and Spencer
// 1942). They stand in for the 360 sky photos a real capture provides, so a fresh clone can bake without
// external assets, and they are known in closed form, so tests can check the images against the formulas.
//
// Units: radiance in relative linear Rec.709 RGB, as a camera HDR exposed for the sky would hold; the
// luminance of a colour is Y = 0.2126 R + 0.7152 G + 0.0722 B. Every colour below is normalised to Y = 1, so
// "luminance" and "radiance" scale the same way. Directions are unit ENU vectors (x east, y north, z up).

#include <glm/vec3.hpp>

#include "gusuku/assets/image.h"

namespace gusuku::bake {

/// Angular radius of the sun's disc seen from the Earth (mean), degrees.
inline constexpr double kSunAngularRadiusDeg = 0.2675;

/// Parameters of the CIE general sky's gradation phi(Z) = 1 + a exp(b / cos Z) and indicatrix
/// f(chi) = 1 + c (exp(d chi) - exp(d pi / 2)) + e cos^2 chi functions.
struct CieSkyCoefficients {
    double a = 0.0, b = 0.0, c = 0.0, d = 0.0, e = 0.0;
};

/// The published coefficients of CIE general sky type 1..15 (12: standard clear sky, low turbidity; 13: clear,
/// polluted). Throws std::invalid_argument for any other type.
CieSkyCoefficients cieSkyCoefficients(int sky_type);

/// Sky luminance relative to the zenith's, L / Lz = f(chi) phi(Z) / (f(Zs) phi(0)), for a direction above
/// the horizon (0 at or below it). chi is the angle between direction and sun, Z the direction's zenith
/// angle, Zs the sun's. sun_direction must be above the horizon or on it.
double cieRelativeLuminance(const glm::dvec3& direction, const glm::dvec3& sun_direction, int sky_type);

/// CIE standard overcast sky, L / Lz = (1 + 2 cos Z) / 3 above the horizon, 0 below.
double overcastRelativeLuminance(const glm::dvec3& direction);

/// Horizontal irradiance per unit zenith luminance, the integral over the upper hemisphere of (L / Lz) cos Z,
/// by midpoint quadrature in (Z, azimuth) with `zenith_steps` x 2 zenith_steps cells. For the overcast sky
/// this is 7 pi / 9 analytically.
double cieDiffuseHorizontalPerZenith(const glm::dvec3& sun_direction, int sky_type, int zenith_steps = 256);
double overcastDiffuseHorizontalPerZenith(int zenith_steps = 256);

/// A clear sky with the sun. Defaults give a clear summer day in relative units (see the file comment).
struct ClearSkySpec {
    glm::dvec3 sun_direction{0.0, 0.0, 1.0};  ///< unit ENU, towards the sun, above the horizon
    int cie_sky_type = 12;
    double diffuse_horizontal_irradiance = 2.0;  ///< DHI of the sky without the sun (luminance units)
    /// Direct normal irradiance over DHI; about 6 on a clear day, so DNI = 12 here.
    double direct_normal_to_diffuse_horizontal = 6.0;
    glm::dvec3 zenith_colour{0.56, 0.74, 1.30};   ///< deep blue overhead (normalised to Y = 1 on use)
    glm::dvec3 horizon_colour{0.92, 0.97, 1.10};  ///< paler towards the horizon (normalised on use)
    glm::dvec3 sun_colour{1.00, 0.97, 0.90};      ///< a slightly warm white (normalised on use)
    double ground_albedo = 0.2;                   ///< of the ground shown below the horizon
    glm::dvec3 ground_colour{1.10, 1.00, 0.78};   ///< an earthy tint (normalised on use)
};

struct OvercastSkySpec {
    double diffuse_horizontal_irradiance = 2.5;  ///< luminance units
    double ground_albedo = 0.2;
    glm::dvec3 ground_colour{1.10, 1.00, 0.78};
};

/// The clear sky as a function of direction, without the sun disc (the "smooth sky").
class ClearSkyModel {
public:
    explicit ClearSkyModel(const ClearSkySpec& spec);

    const ClearSkySpec& spec() const { return spec_; }
    double zenithLuminance() const { return zenith_luminance_; }
    double directNormalIrradiance() const;
    /// Radiance of the disc, DNI / (disc solid angle), luminance units.
    double sunDiscLuminance() const;
    /// Global horizontal irradiance, DHI + DNI sin(sun elevation).
    double globalHorizontalIrradiance() const;
    /// Radiance of the ground below the horizon: albedo * GHI / pi (a Lambertian ground lit by sun and sky).
    double groundLuminance() const;
    /// RGB radiance of the smooth sky (above the horizon) or the ground (below), no sun disc.
    glm::dvec3 radiance(const glm::dvec3& direction) const;

private:
    ClearSkySpec spec_;
    double zenith_luminance_ = 0.0;
};

/// Renders the clear sky into an equirect map (equirect.h convention) of the given size, plus the sun disc:
/// each texel the disc overlaps gets extra radiance in proportion to the solid angle of the disc inside it
/// (found with sun_subsamples x sun_subsamples points per texel), scaled so that the sum of extra radiance
/// times texel solid angle (equirectTexelSolidAngle) equals the direct normal irradiance exactly.
ImageRGBA renderClearSky(const ClearSkySpec& spec, int width, int height, double north_azimuth_in_image_deg,
                         int sun_subsamples = 8);

/// The overcast sky's zenith luminance for a spec: DHI / (7 pi / 9).
double overcastZenithLuminance(const OvercastSkySpec& spec);

/// Renders the grey CIE overcast sky; below the horizon the ground at albedo * DHI / pi.
ImageRGBA renderOvercastSky(const OvercastSkySpec& spec, int width, int height,
                            double north_azimuth_in_image_deg);

}  // namespace gusuku::bake

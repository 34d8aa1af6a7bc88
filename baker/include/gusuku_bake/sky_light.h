#pragma once
// Sky light for the bake (docs/design.md 3): the baked E_ind sees the 360 sky photo WITH ITS SUN DISC REMOVED, and the
// direct sun is added in real time with an irradiance E_sun measured from the removed disc (HDR maps) or taken
// from a clear-sky model of the sun's elevation (clipped or sunless maps). This header holds two CPU parts:
//   - sun disc extraction            (sun_disc.cpp)
//   - sky importance-sampling tables (sky_importance.cpp), and their CPU twins of shaders/include/sky_sampling.glsl
// The clear-sky sun model, shared with the runtime, is gusuku/maths/sun_irradiance.h (engine/src/maths).
// (the GPU probe of that GLSL lives with the tests: tests/support/sky_probe.h).
//
// Conventions: equirect maps as in gusuku/maths/equirect.h (row 0 zenith, azimuth = 360 u - north_azimuth_in_image_deg),
// directions are unit vectors in the site's east-north-up frame, radiance in the map's linear Rec.709 units,
// irradiance = radiance units * sr. Luminance is Rec.709 Y = 0.2126 R + 0.7152 G + 0.0722 B.

#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/assets/image.h"

namespace gusuku {
class VulkanContext;
}

namespace gusuku::bake {

// ------------------------------------------------------------------------------------------------------------
// Sun disc extraction (sun_disc.cpp)
// ------------------------------------------------------------------------------------------------------------

/// Solid angle of the mean solar disc (angular radius 0.2675 deg): 2 pi (1 - cos r), about 6.8e-5 sr.
inline constexpr double kSunDiscAngularRadiusDeg = 0.2675;
double sunDiscSolidAngleSr();

/// What extractSunDisc found and removed.
struct SunDiscEstimate {
    bool found = false;  ///< false: no sun in the map (overcast, sun behind cloud); the map is unchanged
    /// Unit ENU direction of the luminance-weighted centroid of (L - L_fill) over the removed texels.
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};
    /// Irradiance of the removed light on a plane facing direction_enu: sum over removed texels of
    /// (L - L_fill) * texel solid angle * cos(angle to direction_enu), per channel, clamped to >= 0.
    /// Meaningful as E_sun only when clipped is false.
    glm::dvec3 irradiance_rgb{0.0};
    /// True when the map cannot hold the sun's true radiance, so irradiance_rgb underestimates E_sun and the
    /// clear-sky model must be used instead. Either rule makes it true:
    ///  (a) flat top: the texels connected to the peak whose luminance is within 1e-6 (relative) of the peak
    ///      number 3 or more AND cover more solid angle than the whole sun disc (sunDiscSolidAngleSr()); an
    ///      unclipped disc can only be flat over at most its own solid angle (a real one is limb-darkened), and
    ///      two equal texels are what a disc centred on a texel edge gives. (A disc centred exactly on a texel
    ///      corner at the horizon of a low-resolution map can still light 4 texels equally: a false positive
    ///      that only costs using the clear-sky model.)
    ///  (b) too faint: the removed luminance irradiance is below 1% of pi * ring median luminance; a real clear
    ///      sun's direct normal irradiance is of the order of (or above) the circumsolar sky's pi * L, so a disc
    ///      100x fainter than that is a capped one.
    bool clipped = false;
    int texel_count = 0;                  ///< texels replaced in the map
    double angular_radius_deg = 0.0;      ///< largest angle from direction_enu to a replaced texel centre
    double peak_luminance = 0.0;          ///< brightest texel's luminance (before removal)
    double ring_median_luminance = 0.0;   ///< median luminance of the ring around the bright core
    glm::dvec3 fill_radiance_rgb{0.0};    ///< the value written into the replaced texels (the ring's mean)
};

/// Finds the sun in an equirect sky map and removes it, in place.
/// Rule: take the brightest texel (luminance); its bright core is the connected set (8-neighbours, columns
/// wrap) with luminance >= half the peak; if that core reaches beyond 10 deg it is not a disc (bright cloud,
/// clipped overcast) -> not found. A ring of angular radii [r_core + g, r_core + g + w], g = w = max(2 deg,
/// 3 texels), gives the background: its median luminance m and mean RGB (the fill). The sun is found when
/// peak > 50 m (an HDR sun), or when the top is flat (rule (a) of `clipped`) and peak > 1.25 m (a clipped sun
/// in an LDR-range map). The removed region is the connected set from the peak with luminance > m + min(m,
/// (peak - m) / 2), kept inside the ring's inner radius, dilated by 2 texels; each of its texels becomes the
/// fill. A sunless map (no texel standing out like that) -> found = false and the map is untouched.
/// Callers should still compare direction_enu with the sun position from the date (a clipped white cloud can
/// pass the flat-top rule). Known limit: an LDR-range clipped sun (peak < 50 m) covering fewer than 3 texels
/// (maps of 512 x 256 and less) is not found and stays in the map. Throws InputError when the map is empty or its texel vector has the wrong size.
/// Cost: O(texels) for the peak search, plus O(texels in the band of rows around the sun).
SunDiscEstimate extractSunDisc(ImageRGBA& sky_in_out, double north_azimuth_in_image_deg);

// ------------------------------------------------------------------------------------------------------------
// Sky importance sampling (sky_importance.cpp); GPU twin: shaders/include/sky_sampling.glsl
// ------------------------------------------------------------------------------------------------------------

/// Floats before the CDFs in SkySamplingTables::table.
inline constexpr size_t kSkyTableHeaderFloats = 4;

/// Cells of a guide table for a CDF of `intervals` intervals: the smallest power of two >= intervals (1 for 1).
/// Twin of skyGuideCells() in sky_sampling.glsl.
int skyGuideCells(int intervals);

/// Everything the GPU needs to evaluate and importance-sample the sky; upload radiance_rgba and table as two
/// uniform texel buffers (bindings SKY_RADIANCE_BINDING and SKY_TABLE_BINDING of set 0, views of format
/// R32G32B32A32_SFLOAT and R32_SFLOAT: one texel per radiance vec4, one per table float). lavapipe's
/// maxTexelBufferElements (128 Mi) is far above what its 128 MiB storage-buffer cap, which the preflight checks
/// every buffer against, lets through (8 Mi radiance texels, 32 Mi table floats).
///
/// radiance_rgba: width * height * 4 floats, the sky map (sun removed), row 0 the zenith; a non-finite or
///   negative channel is stored as 0. The fourth float of each texel is not the map's alpha but the texel's
///   sampling density over the unit square, p(u, v) below, in float exactly as the GPU would compute it from the
///   CDFs: ((M[y+1] - M[y]) * height * (C_y[x+1] - C_y[x])) * width. So one load gives a direction's radiance and
///   density (the cosine-sampled miss in the tracer needs both).
/// table (all float32):
///   [0] width  [1] height  [2] north_azimuth_in_image_deg
///   [3] integral = sum over texels of luminance * texel solid angle (the sky's luminance integrated over the
///       sphere; 0 for a black map)
///   [4 .. 4 + height]                    marginal CDF over rows, height + 1 entries, first 0, last exactly 1
///   [4 + (height + 1) + y (width + 1) + x], x = 0..width: row y's conditional CDF over columns, first 0,
///                                        last exactly 1
///   then the guide tables (Chen and Asau's cut points), which make each CDF search a short one without
///   changing its answer: with G = skyGuideCells(n) (a power of two) for a CDF of n intervals, G + 1 entries
///   g[k] = the largest i in [0, n-1] with cdf[i] <= k / G (stored as float, exact below 2^24). A search for
///   xi in [0, 1) then looks only in [g[k], g[k+1]], k = floor(xi G) (exact: G is a power of two), and finds
///   the same interval as a search of the whole CDF. First the marginal's guide (skyGuideCells(height) + 1
///   floats), then each row's (skyGuideCells(width) + 1 floats per row, row 0 first).
/// The sampled density over the unit square (u, v) is piecewise constant: f(x, y) = luminance(x, y) sin(theta_y)
/// (theta_y the polar angle of row y's centre), normalised. Its value is read back from the CDFs alone:
///   p(u, v) = (M[y+1] - M[y]) * height * (C_y[x+1] - C_y[x]) * width
/// and over solid angle: pdf = p(u, v) / (2 pi^2 sin theta), sin theta of the direction itself (so pdf
/// integrates to 1 over the sphere exactly when summed as pdf(texel centre) * texel solid angle).
/// Guards: a row whose luminance sums to 0 gets a uniform conditional CDF (never chosen by the marginal); a map
/// whose luminance is 0 everywhere (or non-finite / negative texels, which count as 0) falls back to f = sin
/// theta, i.e. uniform over the sphere. Nothing is ever NaN.
struct SkySamplingTables {
    int width = 0;
    int height = 0;
    float north_azimuth_in_image_deg = 0.0f;
    std::vector<float> radiance_rgba;
    std::vector<float> table;
    /// How uneven the sky is for a cosine-sampled estimate: see skyCosineRelativeVariance.
    double cosine_relative_variance = 0.0;
};

/// Builds the tables from a sky map with the sun already removed (extractSunDisc). Throws InputError when the
/// map is empty, its texel vector has the wrong size, or it has more than 2^24 texels per side (the table
/// stores sizes as float). Cost: O(texels), double-precision sums.
SkySamplingTables buildSkySamplingTables(const ImageRGBA& sky_without_sun, double north_azimuth_in_image_deg);

/// Relative variance Var / E^2 of a one-sample, cosine-sampled estimate of the irradiance from the map (sun
/// removed) on an unoccluded plane, E = integral of L cos: pi * integral(L^2 cos) / integral(L cos)^2 - 1, in
/// luminance, the largest over five planes (facing up, north, east, south, west). 0 for a uniform sky, 1 for a
/// sky lit only above the horizon (on a wall); the sample's CIE overcast map gives 0.46, photographs 2.6 to 4.9,
/// a small bright patch far more. 0 for a black map.
double skyCosineRelativeVariance(const ImageRGBA& sky_without_sun, double north_azimuth_in_image_deg);

/// Above this cosine relative variance the tracer also samples the sky map by importance at every path
/// vertex (one more shadow ray each, weighted against the cosine lobe by MIS); at or below it the cosine
/// lobe alone gathers the sky. Set between the skies measured as error^2 x trace time on the sample house
/// (gusuku-bake converge --sky-sampling): the sample's analytic skies, below it, do better with the cosine lobe
/// alone; the shared photographed skies, above it, do better with the map sampled too.
inline constexpr double kSkyNextEventRelativeVarianceThreshold = 1.0;

/// A direction drawn from the sky's tables with its density.
struct SkySample {
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};
    double pdf_solid_angle = 0.0;  ///< per steradian
};

/// CPU twin of sampleSkyDirection(): xi in [0, 1)^2; xi.x picks the row (marginal), xi.y the column in it,
/// each by a search for the last CDF entry <= xi (compared in float, exactly as on the GPU; the guide table
/// narrows the range, the answer is that of a search of the whole CDF), then the
/// remainder places the point continuously inside the texel. direction = equirectDirection(u, v, north).
/// pdf as documented on SkySamplingTables with sin theta = sin(pi v) (v measured from the nearer pole's side
/// of the row, for precision), floored at 1e-7.
SkySample sampleSkyCpu(const SkySamplingTables& tables, float xi1, float xi2);

/// CPU twin of skyPdf(): density per steradian of sampleSkyCpu at a direction (need not be unit; a zero
/// vector reads as the zenith). The texel is the one containing the direction (nearest-texel lookup, as
/// skyRadianceCpu); sin theta = |xy| / |direction|, floored at 1e-7.
double skyPdfCpu(const SkySamplingTables& tables, const glm::dvec3& direction_enu);

/// Rows [first, last] of a sky map, both included; empty when first > last.
struct SkyRows {
    int first = 0;
    int last = -1;
};

/// CPU twin of skyRowsFacing(): the rows that hold every direction of the open hemisphere dot(normal, d) > 0,
/// those whose polar angles come within 90 deg of the unit normal's, widened by one row at each end (so that
/// float rounding on the GPU never leaves such a direction out), clamped to the map. Why: the tracer draws the
/// map's next-event direction in those rows only, as a direction below a surface's plane brings it no light
/// and leaves its SIMD lane idle while the others trace. Computed in double; the GLSL, in float, may differ by
/// a row where the normal's band edge falls on a row boundary.
SkyRows skyRowsFacingCpu(const SkySamplingTables& tables, const glm::dvec3& unit_normal);

/// CPU twin of skyRowsProbability(): the chance sampleSkyCpu lands in the rows, M[last + 1] - M[first] of the
/// marginal CDF in float; 0 for empty rows.
float skyRowsProbabilityCpu(const SkySamplingTables& tables, SkyRows rows);

/// CPU twin of sampleSkyDirectionInRows(): sampleSkyCpu conditioned on the rows. xi1 is mapped into the rows' part
/// of the marginal CDF, M[first] + xi1 * probability (in float), kept one float below M[last + 1], so the density
/// is skyPdfCpu / skyRowsProbabilityCpu inside them and 0 outside. When the rows hold no light: pdf 0, the zenith.
SkySample sampleSkyInRowsCpu(const SkySamplingTables& tables, SkyRows rows, float xi1, float xi2);

/// CPU twin of skyRadiance(): the texel containing the direction, no filtering. u from the azimuth as in
/// equirect.h (azimuth 0 where x = y = 0), v = theta / pi with theta = atan2(|xy|, z); x = min(int(u w), w-1),
/// y = min(int(v h), h-1).
glm::dvec3 skyRadianceCpu(const SkySamplingTables& tables, const glm::dvec3& direction_enu);

}  // namespace gusuku::bake

#pragma once
// The building's sun horizons (docs/bakeset.md, "Sun horizons"): per lightmap texel, the elevation above which the
// sky is open within kSunHorizonRadiusM, in eight world azimuths. The shadow map fitted over the whole building
// (1024^2 over tens of metres: a few centimetres a texel, plus its biases) cannot resolve a round tile's shadow
// in the groove beside it; the lightmap's texels lie on the surface and can. The runtime evaluates the horizon
// against the sun's direction and multiplies the shadow map's visibility by it (shaders/include/sun_horizon.glsl
// is this file's GLSL twin). Header only and glm only, so the formats, the baker, the runtime and the tests share
// one encoding.
//
// Layout: two lightmap-sized layers of RGBA8 UNORM (format_table.h's "rgba8 data" row), layer 0 the azimuths 0-3,
// layer 1 the azimuths 4-7, channel c of layer l is azimuth 4 l + c, azimuth k at k x 45 degrees east of north
// (0 north, 2 east). A code c is the elevation c x 90 / 255 degrees (0.35 degrees a step). A code of 0 in every
// channel is an open horizon: visibility 1 whatever the sun (what a bake set without horizons reads).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace gusuku {

inline constexpr int kSunHorizonAzimuths = 8;
inline constexpr int kSunHorizonLayers = 2;
inline constexpr double kSunHorizonAzimuthStepDeg = 360.0 / kSunHorizonAzimuths;
/// What one code step is in degrees of elevation.
inline constexpr double kSunHorizonDegPerCode = 90.0 / 255.0;
/// How far the baker looks for a horizon: the features the runtime's shadow map misses (its texels a few
/// centimetres over a building, its biases a few texels), and no further, so what the shadow map does resolve is
/// counted once.
inline constexpr double kSunHorizonRadiusM = 0.5;
/// The width of the runtime's transition from shaded to lit around the horizon: the sun's disc (0.53 degrees)
/// and a code step, so that the horizon's bilinear interpolation between texels makes a smooth edge, not a stair.
inline constexpr double kSunHorizonTransitionDeg = 1.0;
inline constexpr double kSunHorizonDegPerRadian = 57.29577951308232;

/// A bake set's horizons: width = height = the lightmap's resolution, rgba8 holding layer 0 then layer 1
/// (kSunHorizonLayers x width x height x 4 bytes, rows from the top as the lightmaps). Empty: none (visibility 1).
struct BakeSetSunHorizon {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba8;
    bool empty() const { return rgba8.empty(); }
};

/// The code nearest `elevation_deg` (clamped to [0, 90] degrees).
inline uint8_t encodeSunHorizonDeg(double elevation_deg) {
    return uint8_t(std::lround(std::clamp(elevation_deg, 0.0, 90.0) / kSunHorizonDegPerCode));
}
inline double decodeSunHorizonDeg(uint8_t code) { return code * kSunHorizonDegPerCode; }

/// The unit ENU direction at `azimuth_deg` east of north and `elevation_deg` above the horizontal.
inline glm::dvec3 sunHorizonDirection(double azimuth_deg, double elevation_deg) {
    const double a = azimuth_deg / kSunHorizonDegPerRadian, e = elevation_deg / kSunHorizonDegPerRadian;
    return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

/// The sun's visibility over a point's eight horizons (degrees, azimuth 0 first) for the unit direction towards
/// the sun: the horizon interpolated linearly between the two stored azimuths either side of the sun's, then
/// 0.5 with the sun's centre on it and a linear ramp of kSunHorizonTransitionDeg across it. An open horizon
/// (interpolated to 0) is 1. The GLSL twin computes the same.
inline double sunHorizonVisibility(const double (&horizon_deg)[kSunHorizonAzimuths], const glm::dvec3& sun_direction) {
    double azimuth_deg = std::atan2(sun_direction.x, sun_direction.y) * kSunHorizonDegPerRadian;
    if (azimuth_deg < 0.0) azimuth_deg += 360.0;
    const double elevation_deg = std::asin(std::clamp(sun_direction.z, -1.0, 1.0)) * kSunHorizonDegPerRadian;
    const double position = azimuth_deg / kSunHorizonAzimuthStepDeg;
    const int below = int(std::floor(position)) % kSunHorizonAzimuths;
    const double t = position - std::floor(position);
    const double horizon = (1.0 - t) * horizon_deg[below] + t * horizon_deg[(below + 1) % kSunHorizonAzimuths];
    if (horizon <= 0.0) return 1.0;
    return std::clamp((elevation_deg - horizon) / kSunHorizonTransitionDeg + 0.5, 0.0, 1.0);
}

}  // namespace gusuku

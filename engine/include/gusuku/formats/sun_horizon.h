#pragma once
// The building's sun horizons (docs/bakeset.md, "Sun horizons"): per lightmap texel, the elevation above which the
// sky is open within kSunHorizonRadiusM, in eight world azimuths. The shadow map fitted over the whole building
// (1024^2 over tens of metres: a few centimetres a texel, plus its biases) cannot resolve a round tile's shadow
// in the groove beside it; the lightmap's texels lie on the surface and can. The runtime evaluates the horizon
// against the sun's direction and multiplies the shadow map's visibility by it (shaders/include/sun_horizon.glsl
// is this file's GLSL twin). Header only and glm only, so the formats, the baker, the runtime and the tests share
// one encoding.
//
// Layout: two square layers of RGBA8 UNORM (format_table.h's "rgba8 data" row) over the lightmap's coordinates
// (uv1), at a resolution of their own (the lightmap's or finer: a texel a few centimetres, so that a tile row spans
// several); layer 0 the azimuths 0-3, layer 1 the azimuths 4-7, channel c of layer l is azimuth 4 l + c, azimuth k
// at k x 45 degrees east of north (0 north, 2 east). A code c is the elevation c x 90 / 255 degrees (0.35 degrees
// a step). A code of 0 in every channel is an open horizon: visibility 1 whatever the sun (what a bake set without
// horizons reads).

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
/// centimetres over a building, its biases a few texels). The runtime's building map then tests each point moved
/// this far towards the sun, so that a blocker nearer along the sun's ray is the horizons' alone and none counts
/// twice (building.frag).
inline constexpr double kSunHorizonRadiusM = 0.5;
/// The width of the runtime's transition from shaded to lit around the horizon: the sun's disc (0.53 degrees)
/// and a code step, so that the horizon's bilinear interpolation between texels makes a smooth edge, not a stair.
inline constexpr double kSunHorizonTransitionDeg = 1.0;
inline constexpr double kSunHorizonDegPerRadian = 57.29577951308232;

/// The manifest's building.sun_horizon_layout, which a reader requires as written (another layout is another file).
inline constexpr const char* kSunHorizonLayout =
    "RGBA8 UNORM, layer 1 below layer 0; channel c of layer l: azimuth (4 l + c) x 45 deg east of north; "
    "code x 90 / 255 deg; within 0.5 m";
/// The bake set's and the pack's file name.
inline constexpr const char* kSunHorizonFile = "building_sun_horizon.ktx2";

/// The sides a horizon image may have (the runtime takes a 1 x 1 image for none).
inline constexpr int kMinSunHorizonResolution = 2, kMaxSunHorizonResolution = 8192;

/// A bake set's horizons: width = height (any resolution over uv1, its own), rgba8 holding layer 0 then layer 1
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

/// The sun's azimuth (degrees east of north, [0, 360)) and elevation (degrees) from its unit ENU direction.
inline void sunHorizonAngles(const glm::dvec3& sun_direction, double& azimuth_deg, double& elevation_deg) {
    azimuth_deg = std::atan2(sun_direction.x, sun_direction.y) * kSunHorizonDegPerRadian;
    if (azimuth_deg < 0.0) azimuth_deg += 360.0;
    elevation_deg = std::asin(std::clamp(sun_direction.z, -1.0, 1.0)) * kSunHorizonDegPerRadian;
}

/// The elevation (degrees, in [0, 90]) at which the plane through a surface of unit normal `normal` cuts the vertical
/// half-plane at `azimuth_deg` east of north: directions at that azimuth below it are behind the surface (90 for
/// every azimuth behind a wall, the pitch behind a roof, 0 in front of either). d(e) = cos e h + sin e up meets the
/// plane where cos e (h . n) + sin e n_z = 0; clamping atan2(-(h . n), n_z) to [0, 90] covers walls (n_z = 0) and
/// faces turned down (n_z < 0) alike.
inline double surfaceHorizonDeg(const glm::dvec3& normal, double azimuth_deg) {
    const double azimuth = azimuth_deg / kSunHorizonDegPerRadian;
    const double across = std::sin(azimuth) * normal.x + std::cos(azimuth) * normal.y;
    return std::clamp(std::atan2(-across, normal.z) * kSunHorizonDegPerRadian, 0.0, 90.0);
}

/// The visibility of a sun `elevation_deg` high over a horizon `horizon_deg` high: 0.5 with the sun's centre on it,
/// a linear ramp kSunHorizonTransitionDeg wide across it; 1 over an open horizon (0 or below).
inline double sunVisibilityOverHorizon(double horizon_deg, double elevation_deg) {
    if (horizon_deg <= 0.0) return 1.0;
    return std::clamp((elevation_deg - horizon_deg) / kSunHorizonTransitionDeg + 0.5, 0.0, 1.0);
}

/// The sun's visibility over a point's eight horizons (degrees, azimuth 0 first) for the unit direction towards
/// the sun and the unit normal of the surface drawn there: what rises above the surface's own horizon at the two
/// stored azimuths either side of the sun's, interpolated linearly, the surface's own horizon at the sun's azimuth
/// added back, then sunVisibilityOverHorizon (1 where nothing rises above the surface: the cosine settles the rest).
/// The surface's own part is taken out before interpolating because it jumps: a wall's horizon is 0 on its sunny
/// side and 90 degrees behind it, and interpolated between stored azimuths 45 degrees apart it hid a sun grazing the
/// wall from in front (a wall facing between two stored azimuths read up to 45 degrees there). At a stored azimuth
/// this is the stored horizon itself wherever the sun is in front of the surface; with the normal straight up, the
/// stored horizons interpolated.
inline double sunHorizonVisibility(const double (&horizon_deg)[kSunHorizonAzimuths], const glm::dvec3& sun_direction,
                                   const glm::dvec3& normal = glm::dvec3(0.0, 0.0, 1.0)) {
    double azimuth_deg = 0.0, elevation_deg = 0.0;
    sunHorizonAngles(sun_direction, azimuth_deg, elevation_deg);
    const double position = azimuth_deg / kSunHorizonAzimuthStepDeg;
    const int below = int(std::floor(position)) % kSunHorizonAzimuths, above_index = (below + 1) % kSunHorizonAzimuths;
    const double t = position - std::floor(position);
    auto aboveSurface = [&](int k) {
        return std::max(0.0, horizon_deg[k] - surfaceHorizonDeg(normal, k * kSunHorizonAzimuthStepDeg));
    };
    const double above = (1.0 - t) * aboveSurface(below) + t * aboveSurface(above_index);
    if (above <= 0.0) return 1.0;
    // The sun overhead has no azimuth, and nothing rises above it (the GLSL twin's rule too).
    const bool overhead = std::hypot(sun_direction.x, sun_direction.y) < 1e-6;
    return sunVisibilityOverHorizon((overhead ? 0.0 : surfaceHorizonDeg(normal, azimuth_deg)) + above, elevation_deg);
}

/// What the runtime draws at lightmap coordinates `uv` (shaders/include/sun_horizon.glsl, its twin): each of the
/// four texels about uv gives its visibility (sunHorizonVisibility of its decoded horizons), and those are
/// interpolated bilinearly, clamped to the edge. The visibility is filtered, not the horizon: a crest's
/// horizon jumps from open to its own slope, and a horizon interpolated across that jump would put the groove's
/// shadow edge where the sun's elevation crosses it (too far towards the lit side under a low sun, too far
/// towards the groove under a high one) rather than between the texels. An empty horizon: 1.
inline double sunHorizonVisibilityAt(const BakeSetSunHorizon& horizon, double u, double v,
                                     const glm::dvec3& sun_direction,
                                     const glm::dvec3& normal = glm::dvec3(0.0, 0.0, 1.0)) {
    if (horizon.empty()) return 1.0;
    const double x = u * horizon.width - 0.5, y = v * horizon.height - 0.5;
    const double fx = x - std::floor(x), fy = y - std::floor(y);
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const size_t layer_bytes = size_t(horizon.width) * size_t(horizon.height) * 4;
    auto visibility = [&](int tx, int ty) {
        tx = std::clamp(tx, 0, horizon.width - 1);
        ty = std::clamp(ty, 0, horizon.height - 1);
        const size_t texel = (size_t(ty) * size_t(horizon.width) + size_t(tx)) * 4;
        double horizons[kSunHorizonAzimuths];
        for (int k = 0; k < kSunHorizonAzimuths; ++k)
            horizons[k] = decodeSunHorizonDeg(horizon.rgba8[size_t(k / 4) * layer_bytes + texel + size_t(k % 4)]);
        return sunHorizonVisibility(horizons, sun_direction, normal);
    };
    return (1.0 - fy) * ((1.0 - fx) * visibility(x0, y0) + fx * visibility(x0 + 1, y0)) +
           fy * ((1.0 - fx) * visibility(x0, y0 + 1) + fx * visibility(x0 + 1, y0 + 1));
}

}  // namespace gusuku

// The building's sun horizons at run time: the GLSL twin of gusuku/formats/sun_horizon.h's sunHorizonVisibility
// (docs/bakeset.md, "Sun horizons"). Layer 0 holds azimuths 0-3, layer 1 azimuths 4-7 (45 degrees apart, east of
// north), each texel value v the elevation v x 90 degrees; read at the lightmap's coordinates, each of the four
// texels about the point gives its visibility and those are interpolated (sun_horizon.h says why). Needs the including
// shader to declare `sun_horizons` (sampler2DArray, RUNTIME_SUN_HORIZON_BINDING).
#ifndef GUSUKU_SUN_HORIZON_GLSL
#define GUSUKU_SUN_HORIZON_GLSL

#define SUN_HORIZON_FULL_SCALE_DEG 90.0   // a texel value of 1 (code 255)
#define SUN_HORIZON_TRANSITION_DEG 1.0    // kSunHorizonTransitionDeg: the sun's disc and a code step
#define SUN_HORIZON_REACH_M 0.5           // kSunHorizonRadiusM: how far the baker looked

// Whether the bake set has horizons: one without has a 1 x 1 image of open horizons (runtime_scene.cpp).
bool hasSunHorizons() { return textureSize(sun_horizons, 0).x > 1; }

// The four texels about `lightmap_uv` (textureGather's order) at one stored azimuth, as texel values.
vec4 gatherSunHorizons(vec2 lightmap_uv, int azimuth) {
    vec3 coordinates = vec3(lightmap_uv, float(azimuth >> 2));
    int channel = azimuth & 3;
    if (channel == 0) return textureGather(sun_horizons, coordinates, 0);
    if (channel == 1) return textureGather(sun_horizons, coordinates, 1);
    if (channel == 2) return textureGather(sun_horizons, coordinates, 2);
    return textureGather(sun_horizons, coordinates, 3);
}

// The elevation (degrees, [0, 90]) at which the plane of a surface of unit normal `normal` cuts the vertical
// half-plane towards the horizontal unit direction `towards` (surfaceHorizonDeg's twin).
float surfaceHorizonDeg(vec3 normal, vec2 towards) {
    return clamp(degrees(atan(-dot(towards, normal.xy), normal.z)), 0.0, 90.0);
}

// The horizontal unit direction of stored azimuth k (k x 45 degrees east of north).
vec2 storedAzimuthDirection(int k) {
    float azimuth = radians(45.0 * float(k));
    return vec2(sin(azimuth), cos(azimuth));
}

// The sun's visibility over the small features within SUN_HORIZON_REACH_M of the point (sunHorizonVisibilityAt's twin):
// at each of the four texels about it, what rises above the surface's own horizon (from the fragment's normal)
// interpolated linearly between the stored azimuths either side of the sun's, the surface's own horizon at the sun's
// azimuth added back, 0.5 with the sun's centre on it and 1 where nothing rises above the surface (every value 0: a
// bake set without horizons); then those four visibilities interpolated bilinearly. The sun's direction is the frame's,
// so every fragment takes the same branches in gatherSunHorizons: two gathers a fragment.
float sunHorizonVisibility(vec2 lightmap_uv, vec3 sun_direction, vec3 normal) {
    float azimuth_deg = degrees(atan(sun_direction.x, sun_direction.y));
    if (azimuth_deg < 0.0) azimuth_deg += 360.0;
    float elevation_deg = degrees(asin(clamp(sun_direction.z, -1.0, 1.0)));
    float position = azimuth_deg / 45.0;
    int below = int(floor(position)) & 7;
    float t = position - floor(position);
    // What rises above the surface's own horizon at each stored azimuth, interpolated; the surface's own horizon at
    // the sun's azimuth added back (sunHorizonVisibility in the header says why).
    int next = (below + 1) & 7;
    vec4 above_below = max(gatherSunHorizons(lightmap_uv, below) * SUN_HORIZON_FULL_SCALE_DEG -
                           surfaceHorizonDeg(normal, storedAzimuthDirection(below)), vec4(0.0));
    vec4 above_next = max(gatherSunHorizons(lightmap_uv, next) * SUN_HORIZON_FULL_SCALE_DEG -
                          surfaceHorizonDeg(normal, storedAzimuthDirection(next)), vec4(0.0));
    vec4 above_deg = mix(above_below, above_next, t);
    float length_xy = length(sun_direction.xy);  // the sun overhead has no azimuth, and nothing rises above it
    float own_deg = length_xy < 1e-6 ? 0.0 : surfaceHorizonDeg(normal, sun_direction.xy / length_xy);
    vec4 horizon_deg = above_deg + own_deg;
    vec4 visibility = clamp((elevation_deg - horizon_deg) / SUN_HORIZON_TRANSITION_DEG + 0.5, 0.0, 1.0);
    visibility = mix(visibility, vec4(1.0), lessThanEqual(above_deg, vec4(0.0)));
    // textureGather's texels: (i0, j1), (i1, j1), (i1, j0), (i0, j0), at the bilinear weights texture() would use.
    vec2 weight = fract(lightmap_uv * vec2(textureSize(sun_horizons, 0).xy) - 0.5);
    return mix(mix(visibility.w, visibility.z, weight.x), mix(visibility.x, visibility.y, weight.x), weight.y);
}

#endif

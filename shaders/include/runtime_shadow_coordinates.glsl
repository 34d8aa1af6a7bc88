// Where a point lands in the sun's shadow maps, with nothing sampled: runtime_shadow.glsl's lookups build on it,
// and the ground's vertex shader uses it alone (the maps are orthographic, so the coordinates are affine in the
// point and interpolate exactly between cell centres; only the bias's normal is the vertex's). Needs
// FrameUniforms; the constants are runtime_shadow.glsl's contract (see there).
#ifndef GUSUKU_RUNTIME_SHADOW_COORDINATES_GLSL
#define GUSUKU_RUNTIME_SHADOW_COORDINATES_GLSL

// The slope-scaled bias grows with tan(angle between the normal and the sun), which is unbounded at grazing
// light: the cosine is held at or above this (about 87 degrees) so the tangent stays finite...
const float kShadowMinCosine = 0.05;
// ... and the tangent's share of the bias is capped at this (about 84 degrees): a larger bias would detach the
// shadow from the contact line of the surfaces that cast it, for a gain only on surfaces nearly edge-on to the sun.
const float kShadowMaxBiasTangent = 10.0;

// The point's shadow-map uv (x, y) and its depth less the site's slope-scaled bias (z), inside the fitted window
// or not.
vec3 siteShadowCoordinates(vec3 position_enu, vec3 normal_enu) {
    vec4 clip = frame.enu_to_shadow_clip * vec4(position_enu, 1.0);
    float cosine = clamp(dot(normal_enu, frame.sun_direction), kShadowMinCosine, 1.0);
    float tangent = sqrt(1.0 - cosine * cosine) / cosine;
    return vec3(clip.xy * 0.5 + 0.5, clip.z - frame.shadow_depth_bias * (1.0 + min(tangent, kShadowMaxBiasTangent)));
}

// Whether uv lies in the maps' fitted window (outside it nothing of the building can shade the point).
bool insideShadowWindow(vec2 uv) { return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))); }

#endif

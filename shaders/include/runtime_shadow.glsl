// The runtime's shadow lookup: V in [0, 1] (1 lit) of an ENU point from one of the sun's depth maps, with a
// slope-scaled depth bias and a (2r+1)^2-tap PCF of the hardware's 2x2 compare filter. Needs FrameUniforms.
#ifndef GUSUKU_RUNTIME_SHADOW_GLSL
#define GUSUKU_RUNTIME_SHADOW_GLSL

// The slope-scaled bias grows with tan(angle between the normal and the sun), which is unbounded at grazing
// light: the cosine is held at or above this (about 87 degrees) so the tangent stays finite...
const float kShadowMinCosine = 0.05;
// ... and the tangent's share of the bias is capped at this (about 84 degrees): a larger bias would detach the
// shadow from the contact line of the surfaces that cast it, for a gain only on surfaces nearly edge-on to the sun.
const float kShadowMaxBiasTangent = 10.0;
// surelyLit's corner taps sit this many texels out at least: with PCF radius 0 the footprint is still the
// hardware's 2x2 compare filter, which reaches half a texel about the centre.
const float kSurelyLitMinReachTexels = 0.5;
// The centre and four corners: all lit means the whole footprint is lit.
const float kSurelyLitTaps = 5.0;

// The point's shadow-map coordinates and biased depth; false outside the fitted window (nothing of the building
// can shade it there).
bool shadowLookup(vec3 position_enu, vec3 normal_enu, out vec2 uv, out float depth) {
    vec4 clip = frame.enu_to_shadow_clip * vec4(position_enu, 1.0);
    uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    float cosine = clamp(dot(normal_enu, frame.sun_direction), kShadowMinCosine, 1.0);
    float tangent = sqrt(1.0 - cosine * cosine) / cosine;
    depth = clip.z - frame.shadow_depth_bias * (1.0 + min(tangent, kShadowMaxBiasTangent));
    return true;
}

// True when the whole PCF footprint is lit, from its centre and four corner taps (5 lookups instead of
// (2r+1)^2): most ground is in no shadow, and this lets the ground pass leave it untouched cheaply.
bool surelyLit(sampler2DShadow shadow_map, vec3 position_enu, vec3 normal_enu) {
    vec2 uv;
    float depth;
    if (!shadowLookup(position_enu, normal_enu, uv, depth)) return true;
    float reach = frame.shadow_texel_uv * max(frame.shadow_pcf_radius, kSurelyLitMinReachTexels);
    float lit = texture(shadow_map, vec3(uv, depth)) + texture(shadow_map, vec3(uv + vec2(reach, reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(-reach, reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(reach, -reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(-reach, -reach), depth));
    return lit >= kSurelyLitTaps;
}

float sunVisibility(sampler2DShadow shadow_map, vec3 position_enu, vec3 normal_enu) {
    vec2 uv;
    float depth;
    if (!shadowLookup(position_enu, normal_enu, uv, depth)) return 1.0;
    int radius = int(frame.shadow_pcf_radius);
    float texel = frame.shadow_texel_uv;
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) lit += texture(shadow_map, vec3(uv + vec2(x, y) * texel, depth));
    float taps = float((2 * radius + 1) * (2 * radius + 1));
    return lit / taps;
}

#endif

// The runtime's shadow lookup: V in [0, 1] (1 lit) of an ENU point from one of the sun's depth maps, with a
// slope-scaled depth bias and a (2r+1)^2-tap PCF of the hardware's 2x2 compare filter. Needs FrameUniforms.
#ifndef GUSUKU_RUNTIME_SHADOW_GLSL
#define GUSUKU_RUNTIME_SHADOW_GLSL

// The point's shadow-map coordinates and biased depth; false outside the fitted window (nothing of the building
// can shade it there).
bool shadowLookup(vec3 position_enu, vec3 normal_enu, out vec2 uv, out float depth) {
    vec4 clip = frame.enu_to_shadow_clip * vec4(position_enu, 1.0);
    uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    float cosine = clamp(dot(normal_enu, frame.sun_direction.xyz), 0.05, 1.0);
    float tangent = sqrt(1.0 - cosine * cosine) / cosine;
    depth = clip.z - frame.shadow_parameters.y * (1.0 + min(tangent, 10.0));
    return true;
}

// True when the whole PCF footprint is lit, from its centre and four corner taps (5 lookups instead of
// (2r+1)^2): most ground is in no shadow, and this lets the ground pass leave it untouched cheaply.
bool surelyLit(sampler2DShadow shadow_map, vec3 position_enu, vec3 normal_enu) {
    vec2 uv;
    float depth;
    if (!shadowLookup(position_enu, normal_enu, uv, depth)) return true;
    float reach = frame.shadow_parameters.x * max(frame.shadow_parameters.z, 0.5);
    float lit = texture(shadow_map, vec3(uv, depth)) + texture(shadow_map, vec3(uv + vec2(reach, reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(-reach, reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(reach, -reach), depth)) +
                texture(shadow_map, vec3(uv + vec2(-reach, -reach), depth));
    return lit >= 5.0;
}

float sunVisibility(sampler2DShadow shadow_map, vec3 position_enu, vec3 normal_enu) {
    vec2 uv;
    float depth;
    if (!shadowLookup(position_enu, normal_enu, uv, depth)) return 1.0;
    int radius = int(frame.shadow_parameters.z);
    float texel = frame.shadow_parameters.x;
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) lit += texture(shadow_map, vec3(uv + vec2(x, y) * texel, depth));
    float taps = float((2 * radius + 1) * (2 * radius + 1));
    return lit / taps;
}

#endif

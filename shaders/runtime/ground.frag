#version 450
// The shadow catcher (DESIGN.md 3 and 8 step 6): the camera pixel of a ground point is multiplied by
//   ratio = (E_with + V_bld E_sun) / (E_without + E_sun),  E_sun = V_scene I_sun max(0, n . s)
// through the blend unit (in linear: the attachment is sRGB). Where the building changes
// the light by less than half an 8-bit step the fragment is discarded, so those camera pixels are never written
// and pass through bit for bit. Direct-only mode: a fixed darkening in the building's shadow, nothing else.
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"
#include "ground_ratio.glsl"

layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_BUILDING_SHADOW_BINDING) uniform sampler2DShadow building_shadow;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_SITE_SHADOW_BINDING) uniform sampler2DShadow site_shadow;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_GROUND_IRRADIANCE_BINDING) uniform sampler2DArray ground_irradiance;

#include "runtime_shadow.glsl"

layout(location = 0) in vec3 position_enu;
layout(location = 1) in vec3 normal_enu;
layout(location = 2) in vec2 ground_uv;
layout(location = 3) in float ground_present;

layout(location = 0) out vec4 out_ratio;

vec3 groundIrradiance(float slot_layer, float weight, bool with_building) {
    if (weight <= 0.0) return vec3(0.0);
    float layer = 2.0 * slot_layer + (with_building ? 0.0 : 1.0);
    return weight * texture(ground_irradiance, vec3(ground_uv, layer)).rgb;
}

void main() {
    // Between a cell with ground and one without, the interpolated presence falls below 1: no ratio there.
    if (ground_present < 0.999) discard;
    vec3 normal = normalize(normal_enu);
    bool sun_shines = frame.sun_direction.w > 0.0 && dot(normal, frame.sun_direction.xyz) > 0.0;
    float building_visibility = sun_shines ? sunVisibility(building_shadow, position_enu, normal) : 1.0;

    vec3 ratio;
    if (frame.slot_layers.w == RUNTIME_MODE_DIRECT_ONLY) {
        ratio = vec3(mix(frame.direct_only.w, 1.0, building_visibility));
    } else {
        vec3 e_with = groundIrradiance(frame.slot_layers.x, frame.slot_weights.x, true) +
                      groundIrradiance(frame.slot_layers.y, frame.slot_weights.y, true) +
                      groundIrradiance(frame.slot_layers.z, frame.slot_weights.z, true);
        vec3 e_without = groundIrradiance(frame.slot_layers.x, frame.slot_weights.x, false) +
                         groundIrradiance(frame.slot_layers.y, frame.slot_weights.y, false) +
                         groundIrradiance(frame.slot_layers.z, frame.slot_weights.z, false);
        // Both sides are stored with the same scale, so it cancels except against E_sun.
        e_with *= frame.colour_match.z;
        e_without *= frame.colour_match.z;
        float scene_visibility = 1.0;
        if (sun_shines && frame.shadow_parameters.w > 0.0)
            scene_visibility = sunVisibility(site_shadow, position_enu, normal);
        vec3 e_sun = sun_shines ? groundSunIrradiance(frame.sun_irradiance.rgb, normal, frame.sun_direction.xyz,
                                                      scene_visibility)
                                : vec3(0.0);
        ratio = groundShadowRatio(e_with, e_without, e_sun, building_visibility);
    }
    if (any(isnan(ratio))) ratio = vec3(1.0);
    // The blend computes destination x source x 2 (source and destination factors DST_COLOR and SRC_COLOR), so
    // a ratio up to 2 (light the building bounces onto the ground) survives the attachment's [0, 1] clamp.
    ratio = clamp(ratio, vec3(0.0), vec3(2.0));
    if (all(lessThan(abs(ratio - 1.0), vec3(frame.ground_parameters.w)))) discard;
    out_ratio = vec4(0.5 * ratio, 1.0);
}

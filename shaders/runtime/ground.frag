#version 450
// The shadow catcher (docs/design.md 3 and 8 step 6): the camera pixel of a ground point is multiplied by
//   ratio = (E_with + V_bld E_sun) / (E_without + E_sun),  E_sun = V_scene I_sun max(0, n . s)
// through the blend unit (in linear: the attachment is sRGB). Where the building changes the light by less than
// half an 8-bit step the fragment writes a ratio of exactly 1: the blend then returns the camera's own value
// (decode, times 1, encode: the same byte, which tests pin), and quads the building cannot change are not drawn
// at all (the CPU chooses them). No `discard`: on llvmpipe a shader that may discard costs more per fragment
// than one that always writes.
// Direct-only mode: a fixed darkening in the building's shadow, nothing else.
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"
#include "ground_ratio.glsl"

layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_BUILDING_SHADOW_BINDING) uniform sampler2DShadow building_shadow;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_BUILDING_SHADOW_DEPTH_BINDING) uniform sampler2D building_shadow_depths;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_SITE_SHADOW_BINDING) uniform sampler2DShadow site_shadow;

#include "runtime_shadow.glsl"

layout(location = 0) in vec3 position_enu;
layout(location = 1) in vec3 normal_enu;
layout(location = 2) in vec3 irradiance_with;
layout(location = 3) in vec3 irradiance_without;
layout(location = 4) in float ground_present;
layout(location = 5) in vec3 sun_irradiance;     // I_sun max(0, n . s), interpolated from the cell centres
layout(location = 6) in float shadow_candidate;  // > 0 where the building's shadow may fall (a shadow map read)
layout(location = 7) in vec3 site_shadow_coordinates;  // the site's map's uv and biased depth (ground.vert)

layout(location = 0) out vec4 out_ratio;

// False in the variant drawn for quads the building's shadow cannot reach this frame: no building shadow-map
// reads at all (llvmpipe would run them masked for every fragment of a SIMD group otherwise).
layout(constant_id = 0) const bool kBuildingShadow = true;
// False in the variant for frames without sun (overcast, night): no shadow-map reads and no sun term.
layout(constant_id = 1) const bool kSunShines = true;

// The presence (ground_irradiance layer 0's alpha: 0 no ground, 1 ground, 2 ground whose baked light the building
// changes) is interpolated between cell centres: within this of 1 counts as ground on every corner (interpolating
// equal values may round by an ulp or so)...
const float kPresentOnEveryCorner = 0.999;
// ... and above 1 by more than the same margin, a corner that is marked 2.
const float kBakedChangeOnACorner = 1.001;

// The ratio through the blend: destination x source x 2 (source and destination factors DST_COLOR and
// SRC_COLOR), so a ratio up to 2 (light the building bounces onto the ground) survives the attachment's [0, 1]
// clamp; within the pass-through threshold of 1 in every channel, exactly 1 (the camera's own byte).
void writeRatio(vec3 ratio) {
    if (any(isnan(ratio))) ratio = vec3(1.0);
    ratio = clamp(ratio, vec3(0.0), vec3(2.0));
    if (all(lessThan(abs(ratio - 1.0), vec3(frame.pass_through_threshold)))) ratio = vec3(1.0);
    out_ratio = vec4(0.5 * ratio, 1.0);
}

void main() {
    const vec4 kUnchanged = vec4(0.5, 0.5, 0.5, 1.0);  // ratio 1 through the blend's factor of 2
    // Between a cell with ground and one without, the interpolated presence falls below 1: no ratio there.
    if (ground_present < kPresentOnEveryCorner) {
        out_ratio = kUnchanged;
        return;
    }
    // Presence above 1 marks cells where the building changes the baked light (runtime_scene.h); elsewhere only
    // its shadow can change the pixel, so a surely lit fragment there is left alone at once.
    bool direct_only = frame.render_mode == RUNTIME_RENDER_MODE_DIRECT_ONLY;
    bool baked_change = ground_present > kBakedChangeOnACorner && !direct_only;
    if (!kBuildingShadow) {
        // The quads only the baked change brings (most of the ratio pass's fragments on a wide view): the light
        // the building changes, under the site's own shadow, with no projection here (the vertices made the map
        // coordinates) and no normal (E_sun is already 0 per vertex where the sun is behind the ground).
        if (!baked_change) {
            out_ratio = kUnchanged;
            return;
        }
        float scene_visibility = 1.0;
        if (kSunShines && frame.sun_shines != 0u && frame.site_shadows != 0u &&
            insideShadowWindow(site_shadow_coordinates.xy))
            scene_visibility = texture(site_shadow, site_shadow_coordinates);
        vec3 e_sun = kSunShines && frame.sun_shines != 0u ? sun_irradiance * scene_visibility : vec3(0.0);
        writeRatio(groundShadowRatio(irradiance_with, irradiance_without, e_sun, 1.0));
        return;
    }
    vec3 normal = normalize(normal_enu);
    bool sun_shines = kSunShines && frame.sun_shines != 0u && dot(normal, frame.sun_direction) > 0.0;
    // Only cells the CPU found in the building's shadow reach read the building's shadow map at all; there the
    // blocker search settles most fragments (lit) before any filter.
    // Both maps share the matrix: the point is projected once.
    vec2 shadow_uv;
    float shadow_depth;
    bool in_shadow_window = sun_shines && shadowLookup(position_enu, normal, shadow_uv, shadow_depth);
    float building_visibility = 1.0;
    if (in_shadow_window && shadow_candidate > 0.0)
        building_visibility = buildingSunVisibility(position_enu, normal, shadow_uv, shadow_depth);
    if (building_visibility >= 1.0 && !baked_change) {
        out_ratio = kUnchanged;
        return;
    }

    vec3 ratio;
    if (direct_only) {
        ratio = vec3(mix(frame.direct_only_shadow_darkening, 1.0, building_visibility));
    } else {
        // The real scene's own shadow only decides whether the sun adds to this point: one bilinear compare tap.
        float scene_visibility = 1.0;
        if (in_shadow_window && frame.site_shadows != 0u)
            scene_visibility = texture(site_shadow, vec3(shadow_uv, shadow_depth));
        vec3 e_sun = sun_shines ? sun_irradiance * scene_visibility : vec3(0.0);
        ratio = groundShadowRatio(irradiance_with, irradiance_without, e_sun, building_visibility);
    }
    writeRatio(ratio);
}

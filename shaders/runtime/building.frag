#version 450
// The building (docs/design.md 3 and 8 step 5): radiance = albedo / pi x (E_ind + V x E_sun x max(0, n . s)), with
// E_ind the slots' baked lightmaps blended by the frame's weights, V the sun's visibility from the building's
// and the site's shadow maps, then the colour match to the camera (colour_match.glsl). Direct-only mode: a
// constant ambient instead of E_ind, no colour match (what AR apps draw today).
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"
#include "runtime_material_push.h"
#include "constants.glsl"

layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_BUILDING_SHADOW_BINDING) uniform sampler2DShadow building_shadow;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_BUILDING_SHADOW_DEPTH_BINDING) uniform sampler2D building_shadow_depths;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_SITE_SHADOW_BINDING) uniform sampler2DShadow site_shadow;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_LIGHTMAP_BINDING) uniform sampler2DArray lightmaps;
layout(set = RUNTIME_MATERIAL_SET, binding = RUNTIME_BASE_COLOUR_BINDING) uniform sampler2D base_colour;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_SUN_HORIZON_BINDING) uniform sampler2DArray sun_horizons;
#include "sun_horizon.glsl"

#include "colour_match.glsl"
layout(std430, set = RUNTIME_FRAME_SET, binding = RUNTIME_COLOUR_MATCH_BINDING) readonly buffer ColourMatchBuffer {
    ColourMatchState colour_state;
};
#include "runtime_shadow.glsl"

// Centroid: with multisampling a pixel on a triangle's edge is shaded once, and at the pixel's centre the
// interpolated values lie outside the triangle: the lightmap would be read past its chart (the gutter, or a
// neighbour's texels) and the shadow maps at a point off the surface. At a covered sample they stay on it. The
// base colour's UV keeps centre interpolation, since its mip level comes from the UV's derivatives.
layout(location = 0) centroid in vec3 position_enu;
layout(location = 1) centroid in vec3 normal_enu;
layout(location = 2) in vec2 base_colour_uv;
layout(location = 3) centroid in vec2 lightmap_uv;

layout(location = 0) out vec4 out_colour;  // linear; the sRGB attachment encodes it

// An alpha-masked material's pipeline (issue 21 item 3) sets this: fragments whose base colour alpha is below
// the cutoff are holes. A specialisation constant, so the opaque materials' pipeline has no discard at all (a
// discard can cost early depth testing on tile-based GPUs).
layout(constant_id = 0) const bool kAlphaMasked = false;
// With multisampling (the pipeline's alpha to coverage on): the mask's edge as a coverage. The alpha's distance
// from the cutoff over its change across the pixel (fwidth) is the share of the pixel on the opaque side, so the
// edge stays as sharp as a discard's where the texture is magnified and becomes a partial coverage where a leaf
// or a gap is smaller than a pixel. The mip chain keeps each level's coverage at the cutoff
// (srgb_mip_chain.h), so that share does not drift with distance.
layout(constant_id = 1) const bool kAlphaToCoverage = false;

void main() {
    vec4 base_colour_texel = texture(base_colour, base_colour_uv);
    float coverage = 1.0;
    if (kAlphaMasked) {
        float alpha = base_colour_texel.a * material.base_colour_factor.a;
        if (kAlphaToCoverage) {
            coverage = clamp((alpha - material.alpha_cutoff) / max(fwidth(alpha), 1.0 / 255.0) + 0.5, 0.0, 1.0);
            if (coverage <= 0.0) discard;
        } else if (alpha < material.alpha_cutoff) {
            discard;
        }
    }
    vec3 albedo = base_colour_texel.rgb * material.base_colour_factor.rgb;
    vec3 normal = normalize(normal_enu);
    // Two-sided: a face seen from behind is lit as its front (thin walls, eaves).
    if (!gl_FrontFacing) normal = -normal;

    bool direct_only = frame.render_mode == RUNTIME_RENDER_MODE_DIRECT_ONLY;
    vec3 indirect_irradiance;
    if (direct_only) {
        indirect_irradiance = frame.direct_only_ambient;
    } else {
        indirect_irradiance = vec3(0.0);
        if (frame.slot_weights.x > 0.0)
            indirect_irradiance += frame.slot_weights.x * texture(lightmaps, vec3(lightmap_uv, frame.slot_layers.x)).rgb;
        if (frame.slot_weights.y > 0.0)
            indirect_irradiance += frame.slot_weights.y * texture(lightmaps, vec3(lightmap_uv, frame.slot_layers.y)).rgb;
        if (frame.slot_weights.z > 0.0)
            indirect_irradiance += frame.slot_weights.z * texture(lightmaps, vec3(lightmap_uv, frame.slot_layers.z)).rgb;
        indirect_irradiance *= frame.irradiance_scale;  // the lightmaps are stored scaled to fit half floats
    }

    vec3 sun_irradiance = vec3(0.0);
    float cosine = dot(normal, frame.sun_direction);
    if (frame.sun_shines != 0u && cosine > 0.0) {
        // Both maps share the matrix: the point is projected once. The blocker search settles most fragments
        // (fully lit); only the rest pay for the penumbra's filter. The real site's shadow on the building: one
        // bilinear compare tap (its edges come from far away and are soft in the camera image anyway).
        // The baked horizons hold the small features (a tile's shadow in its groove) the shadow map is too coarse
        // for; the building's map everything farther along the sun's ray than the horizons reach, so that no
        // blocker counts twice: it tests the point moved that far towards the sun. Direct-only draws what AR apps
        // draw: the shadow map alone.
        bool horizons = !direct_only && hasSunHorizons();
        float visibility = horizons ? sunHorizonVisibility(lightmap_uv, frame.sun_direction, normal) : 1.0;
        vec2 uv;
        float depth;
        if (visibility > 0.0 && shadowLookup(position_enu, normal, uv, depth)) {
            float reach_m = horizons ? SUN_HORIZON_REACH_M : 0.0;
            visibility *= buildingSunVisibility(position_enu + frame.sun_direction * reach_m, normal, uv,
                                                depth - reach_m * frame.shadow_texel_depth / frame.shadow_texel_m);
            if (frame.site_shadows != 0u && visibility > 0.0) visibility *= texture(site_shadow, vec3(uv, depth));
        }
        sun_irradiance = frame.sun_irradiance * (visibility * cosine);
    }
    vec3 radiance = albedo / kPi * (indirect_irradiance + sun_irradiance);
    if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);

    // Without a colour match (off, direct-only, or no camera statistics yet) the camera's exposure maps radiance
    // to display values; the Lab matches map the baked appearance's Lab statistics onto the camera's instead, and
    // the ground match multiplies the exposed radiance by the gain that takes the predicted ground to the camera's.
    vec3 display_linear;
    if (direct_only || !colourMatchActive(colour_state))
        display_linear = clamp(radiance * frame.exposure, vec3(0.0), vec3(1.0));
    else if (colour_state.mode == COLOUR_MATCH_MODE_GROUND)
        display_linear = applyColourMatch(radiance * frame.exposure, colour_state);
    else
        display_linear = applyColourMatch(radiance, colour_state);
    out_colour = vec4(display_linear, coverage);  // alpha: the coverage where alpha to coverage is on, else 1
}

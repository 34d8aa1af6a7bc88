#version 450
// The ground grid drawn from its baked geometry: one vertex per cell centre (gl_VertexIndex = texel index, row 0
// north), its height and normal from ground_geometry; the one vertex stream is this frame's per-cell flag of
// where the building's shadow may fall (chosen on the CPU). The baked terms and the sun's cosine term E_with and E_without are
// blended over the frame's slots here, once per cell, and interpolated to the fragments: vertices sit on the
// cell centres, so the interpolation is the texture's own bilinear one, without a texture read per fragment.
// Pulled a little towards the camera so the occluder mesh it was sampled from does not hide it (docs/design.md 8).
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"
#include "runtime_shadow_coordinates.glsl"

layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_GROUND_GEOMETRY_BINDING) uniform sampler2D ground_geometry;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_GROUND_IRRADIANCE_BINDING) uniform sampler2DArray ground_irradiance;

layout(location = 0) in float shadow_candidate;  // per cell, this frame: the building's shadow may fall here

layout(location = 0) out vec3 out_position_enu;
layout(location = 1) out vec3 out_normal_enu;
layout(location = 2) out vec3 out_irradiance_with;     // E_with blended over the slots, bake set units
layout(location = 3) out vec3 out_irradiance_without;  // E_without, the same
layout(location = 4) out float out_ground_present;     // 0 no ground, 1 ground, 2 ground the building changes
layout(location = 5) out vec3 out_sun_irradiance;      // I_sun max(0, n . s): E_sun before the real scene's shadow
layout(location = 6) out float out_shadow_candidate;
// The site's shadow-map uv and biased depth at the cell centre: the quads the building's shadow cannot reach read
// them interpolated instead of projecting every fragment (the map is orthographic, so uv and depth interpolate
// exactly; the slope bias comes from the cell's normal rather than the fragment's interpolated one, and the sample's
// composites measured, four views and lights, are byte-identical: docs/measurements.md).
layout(location = 7) out vec3 out_site_shadow_coordinates;

vec3 slotIrradiance(ivec2 cell, float slot_layer, float weight, bool with_building) {
    if (weight <= 0.0) return vec3(0.0);
    int layer = 2 * int(slot_layer) + (with_building ? 0 : 1);
    return weight * texelFetch(ground_irradiance, ivec3(cell, layer), 0).rgb;
}

// The pull moves the vertex towards the camera by at most half the distance to it (never past it), and divides by
// that distance no nearer than this (a vertex at the camera stays put instead of becoming NaN).
const float kMinPullDistanceM = 1e-3;
const float kMaxPullFraction = 0.5;

void main() {
    int columns = frame.ground_columns;
    int rows = frame.ground_rows;
    ivec2 cell = ivec2(gl_VertexIndex % columns, gl_VertexIndex / columns);
    vec4 geometry = texelFetch(ground_geometry, cell, 0);
    vec2 centre = vec2(frame.ground_origin_east_m + (float(cell.x) + 0.5) * frame.ground_cell_m,
                       frame.ground_origin_north_m + (float(rows - cell.y) - 0.5) * frame.ground_cell_m);
    vec3 position = vec3(centre, geometry.a);
    out_position_enu = position;
    out_normal_enu = geometry.rgb;
    out_ground_present = texelFetch(ground_irradiance, ivec3(cell, 0), 0).a;
    vec3 with_building = slotIrradiance(cell, frame.slot_layers.x, frame.slot_weights.x, true) +
                         slotIrradiance(cell, frame.slot_layers.y, frame.slot_weights.y, true) +
                         slotIrradiance(cell, frame.slot_layers.z, frame.slot_weights.z, true);
    vec3 without_building = slotIrradiance(cell, frame.slot_layers.x, frame.slot_weights.x, false) +
                            slotIrradiance(cell, frame.slot_layers.y, frame.slot_weights.y, false) +
                            slotIrradiance(cell, frame.slot_layers.z, frame.slot_weights.z, false);
    // Stored scaled to fit half floats: the scale cancels between the two but not against E_sun.
    out_irradiance_with = with_building * frame.irradiance_scale;
    out_irradiance_without = without_building * frame.irradiance_scale;
    out_sun_irradiance = frame.sun_shines != 0u
                             ? frame.sun_irradiance * max(0.0, dot(geometry.rgb, frame.sun_direction))
                             : vec3(0.0);
    out_shadow_candidate = shadow_candidate;
    out_site_shadow_coordinates = siteShadowCoordinates(position, geometry.rgb);
    vec3 towards_camera = frame.camera_position - position;
    float distance_to_camera = length(towards_camera);
    vec3 pulled = position + towards_camera / max(distance_to_camera, kMinPullDistanceM) *
                                 min(frame.ground_pull_m, kMaxPullFraction * distance_to_camera);
    gl_Position = frame.enu_to_clip * vec4(pulled, 1.0);
}

#version 450
// The ground grid drawn from its baked geometry: one vertex per cell centre (gl_VertexIndex = texel index, row 0
// north), its height and normal from ground_geometry; no vertex buffer. Pulled a little towards the camera so the
// occluder mesh it was sampled from does not hide it (DESIGN.md 8 step 6).
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"

layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_GROUND_GEOMETRY_BINDING) uniform sampler2D ground_geometry;
layout(set = RUNTIME_FRAME_SET, binding = RUNTIME_GROUND_IRRADIANCE_BINDING) uniform sampler2DArray ground_irradiance;

layout(location = 0) out vec3 out_position_enu;
layout(location = 1) out vec3 out_normal_enu;
layout(location = 2) out vec2 out_ground_uv;
layout(location = 3) out float out_ground_present;

void main() {
    int columns = int(frame.ground_grid.w);
    int rows = int(frame.ground_parameters.x);
    ivec2 cell = ivec2(gl_VertexIndex % columns, gl_VertexIndex / columns);
    vec4 geometry = texelFetch(ground_geometry, cell, 0);
    vec2 centre = vec2(frame.ground_grid.x + (float(cell.x) + 0.5) * frame.ground_grid.z,
                       frame.ground_grid.y + (float(rows - cell.y) - 0.5) * frame.ground_grid.z);
    vec3 position = vec3(centre, geometry.a);
    out_position_enu = position;
    out_normal_enu = geometry.rgb;
    out_ground_uv = (vec2(cell) + 0.5) / vec2(columns, rows);
    // Ground exists where the bake found it (alpha of the with-building image of layer 0).
    out_ground_present = texelFetch(ground_irradiance, ivec3(cell, 0), 0).a;
    vec3 towards_camera = frame.camera_position.xyz - position;
    float distance_to_camera = length(towards_camera);
    vec3 pulled = position + towards_camera / max(distance_to_camera, 1e-3) *
                                 min(frame.ground_parameters.y, 0.5 * distance_to_camera);
    gl_Position = frame.enu_to_clip * vec4(pulled, 1.0);
}

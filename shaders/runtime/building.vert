#version 450
// The building: ENU position, normal, base colour and lightmap coordinates through to building.frag.
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"

layout(location = 0) in vec3 position_enu;
layout(location = 1) in vec3 normal_enu;
layout(location = 2) in vec2 base_colour_uv;
layout(location = 3) in vec2 lightmap_uv;

layout(location = 0) out vec3 out_position_enu;
layout(location = 1) out vec3 out_normal_enu;
layout(location = 2) out vec2 out_base_colour_uv;
layout(location = 3) out vec2 out_lightmap_uv;

void main() {
    out_position_enu = position_enu;
    out_normal_enu = normal_enu;
    out_base_colour_uv = base_colour_uv;
    out_lightmap_uv = lightmap_uv;
    gl_Position = frame.enu_to_clip * vec4(position_enu, 1.0);
}

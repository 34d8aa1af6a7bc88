#version 450
// An alpha-masked material of the building into the sun's shadow map (issue 21 item 3): depth_only.vert's
// position, plus the base colour's uv for depth_masked.frag's alpha test. Opaque materials keep the vertex-only
// depth_only.vert, so an opaque building's shadow pass costs what it did.
#extension GL_GOOGLE_include_directive : require
#include "runtime_masked_depth_push.h"

layout(location = 0) in vec3 position_enu;
layout(location = 1) in vec2 base_colour_uv_in;
layout(location = 0) out vec2 base_colour_uv;

void main() {
    base_colour_uv = base_colour_uv_in;
    gl_Position = push.enu_to_clip * vec4(position_enu, 1.0);
}

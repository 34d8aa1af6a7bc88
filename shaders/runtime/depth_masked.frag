#version 450
// The alpha test of a masked material in the shadow map: a texel whose base colour alpha (factor times texture)
// is below the cutoff writes no depth, so sunlight passes its holes as the baker's rays do
// (shaders/include/bvh_alpha_mask.glsl) and building.frag discards it in the colour pass.
#extension GL_GOOGLE_include_directive : require
#include "runtime_interface.h"
#include "runtime_masked_depth_push.h"

// The material's own set (the building pass's set RUNTIME_MATERIAL_SET layout), bound here at set 0: this
// pipeline's layout holds it alone.
layout(set = 0, binding = RUNTIME_BASE_COLOUR_BINDING) uniform sampler2D base_colour;
layout(location = 0) in vec2 base_colour_uv;

void main() {
    if (texture(base_colour, base_colour_uv).a * push.base_colour_alpha < push.alpha_cutoff) discard;
}

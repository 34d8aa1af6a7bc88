// Push constants of shaders/runtime/depth_masked.vert and depth_masked.frag (an alpha-masked material into the
// building's shadow map), for GLSL and C++.
#ifndef GUSUKU_RUNTIME_MASKED_DEPTH_PUSH_H
#define GUSUKU_RUNTIME_MASKED_DEPTH_PUSH_H
#include "interface_types.h"
GUSUKU_PUSH_CONSTANTS_BEGIN(MaskedDepthPushConstants)
    mat4 enu_to_clip;          // the sun's view of this frame's shadow fit
    float base_colour_alpha;   // the material's base colour factor's alpha, multiplies the texture's
    float alpha_cutoff;        // fragments whose alpha is below this are holes
GUSUKU_PUSH_CONSTANTS_END(MaskedDepthPushConstants, push)
#endif

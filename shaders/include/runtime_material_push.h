// Push constants of shaders/runtime/building.frag: the material drawn, for GLSL and C++.
#ifndef GUSUKU_RUNTIME_MATERIAL_PUSH_H
#define GUSUKU_RUNTIME_MATERIAL_PUSH_H
#include "interface_types.h"
GUSUKU_PUSH_CONSTANTS_BEGIN(MaterialPushConstants)
    vec4 base_colour_factor;  // linear RGBA, multiplies the texture
    float alpha_cutoff;       // an alpha-masked material's cutoff (read by the masked pipeline only)
GUSUKU_PUSH_CONSTANTS_END(MaterialPushConstants, material)
#endif

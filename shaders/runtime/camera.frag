#version 450
// The camera frame into the composite, sampled in place (docs/design.md 8 step 1): each pixel reads its own
// camera pixel (camera_sample.glsl, any format) and writes it, linear, into the sRGB attachment, whose encoding
// gives back the camera's byte (decode then encode of an 8-bit code is exact). Drawn first, so the building
// and the ground ratio blend over the camera as they did over a copy of it.
#extension GL_GOOGLE_include_directive : require
#include "camera_interface.h"
#include "colour.glsl"

layout(set = 0, binding = CAMERA_PLANE0_BINDING) uniform sampler2D camera_plane0;
#ifndef CAMERA_SAMPLER_YCBCR  // the zero-copy camera's variant has plane 0's binding alone
layout(set = 0, binding = CAMERA_PLANE1_BINDING) uniform sampler2D camera_plane1;
#endif

#include "camera_sample.glsl"

layout(location = 0) out vec4 out_colour;

void main() {
    out_colour = cameraLinearPixel(ivec2(gl_FragCoord.xy));
}

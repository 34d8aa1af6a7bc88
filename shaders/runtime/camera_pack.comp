#version 450
// The camera as packed RGBA8 words (R in the low byte, sRGB, row 0 at the top) for the colour statistics
// kernels, which read the camera that way. Runs only on frames with a colour match on, one invocation per pixel of
// the statistics' sample grid (camera_push.pack_*): only those words are written, each at its pixel's place in the
// frame-sized buffer (the others keep whatever they held; nothing reads them). It reads the camera in place
// through camera_sample.glsl, so the statistics see what the composite shows.
#extension GL_GOOGLE_include_directive : require
#include "camera_interface.h"
#include "colour.glsl"

layout(local_size_x = CAMERA_PACK_WORKGROUP, local_size_y = CAMERA_PACK_WORKGROUP) in;
layout(set = 0, binding = CAMERA_PLANE0_BINDING) uniform sampler2D camera_plane0;
#ifndef CAMERA_SAMPLER_YCBCR  // the zero-copy camera's variant has plane 0's binding alone
layout(set = 0, binding = CAMERA_PLANE1_BINDING) uniform sampler2D camera_plane1;
#endif
layout(std430, set = 1, binding = CAMERA_PACKED_BINDING) writeonly buffer Packed { uint camera_rgba8[]; };

#include "camera_sample.glsl"

void main() {
    const uvec2 sample_index = gl_GlobalInvocationID.xy;
    if (sample_index.x >= camera_push.pack_samples_x || sample_index.y >= camera_push.pack_samples_y) return;
    const ivec2 pixel = ivec2(uvec2(camera_push.pack_offset) + sample_index * camera_push.pack_stride);
    camera_rgba8[pixel.y * int(camera_push.frame_width) + pixel.x] = packUnorm4x8(cameraSrgbPixel(pixel));
}

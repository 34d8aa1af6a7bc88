// The camera-in stage's interface (engine/src/runtime/camera_input.h), shared by GLSL and C++: the camera's
// descriptor set, its specialisation constants and the push constants. A plain C/GLSL header.
#ifndef GUSUKU_CAMERA_INTERFACE_H
#define GUSUKU_CAMERA_INTERFACE_H

#include "interface_types.h"

// The camera's set, for the camera-in draw (set 0 of its own pipeline layout) and the packing kernel.
#define CAMERA_PLANE0_BINDING 0  // sampler2D: RGBA8 / BGRA8 pixels, or the luma (Y') plane
#define CAMERA_PLANE1_BINDING 1  // sampler2D: the interleaved chroma plane at half size (YUV); plane 0 again else
#define CAMERA_BINDING_COUNT 2
// The packing kernel's output (set 1): the camera as packed RGBA8 words, sRGB, for the colour statistics.
#define CAMERA_PACKED_BINDING 0

// Specialisation constants (fixed when the runtime opens: the camera's format does not change per frame).
#define CAMERA_KIND_CONSTANT 0         // 0: one four-byte plane (its view gives RGBA order); 1: two-plane Y'CbCr
#define CAMERA_MATRIX_CONSTANT 1       // Y'CbCr: 0 BT.601, 1 BT.709
#define CAMERA_FULL_RANGE_CONSTANT 2   // Y'CbCr: 0 narrow (studio, Y' 16-235), 1 full (0-255)
#define CAMERA_CHROMA_SWAP_CONSTANT 3  // Y'CbCr: 0 Cb first (NV12), 1 Cr first (NV21)
// The zero-copy camera's variant (compiled with CAMERA_SAMPLER_YCBCR): plane 0's binding is the app's two-plane
// image through an immutable sampler with a sampler Y'CbCr conversion, and plane 1's binding is absent.
#define CAMERA_YCBCR_LINEAR_CONSTANT 4  // 1: the conversion filters linearly, 0: nearest
#define CAMERA_FRAME_HEIGHT_CONSTANT 5  // the frame's height, pixels (normalised coordinates need it)
#define CAMERA_CONSTANT_COUNT 6

#define CAMERA_KIND_FOUR_BYTE 0u
#define CAMERA_KIND_TWO_PLANE_YUV 1u
#define CAMERA_PACK_WORKGROUP 8

// Per frame, both stages.
GUSUKU_PUSH_CONSTANTS_BEGIN(CameraPushConstants)
    uint frame_width;
    uint view_decodes_srgb;  // 1: the view is an _SRGB format, so sampling returns linear values
    // The packing kernel only (the draw leaves them 0): the statistics' sample grid (ColourStatisticsGrid of
    // gusuku/maths/colour_match.h), so that only the pixels they read are packed.
    uint pack_stride;
    uint pack_offset;
    uint pack_samples_x;
    uint pack_samples_y;
GUSUKU_PUSH_CONSTANTS_END(CameraPushConstants, camera_push)

#endif

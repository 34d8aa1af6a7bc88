// shaders/bake/camera_trace.comp as both sides see it: its set-0 bindings (uniform texel buffers for the BVH and
// the scene's shading, bindings 0..4, storage buffers for the rest) and its push-constant block, written once
// for the GLSL and for baker/src/camera_tracer.cpp (which binds the buffers in this order). See
// interface_types.h for the rules. The block fills the 128 bytes every Vulkan device guarantees.
#ifndef GUSUKU_CAMERA_TRACE_INTERFACE_H
#define GUSUKU_CAMERA_TRACE_INTERFACE_H

#include "interface_types.h"

// camera_trace.comp, set 0. Bindings 0-6 are the scene and sky buffers of bake_irradiance.comp, in its order.
#define CAMERA_BVH_NODE_BINDING 0          // Bvh::nodes
#define CAMERA_BVH_TRIANGLE_BINDING 1      // Bvh::triangles
#define CAMERA_SHADING_TRIANGLE_BINDING 2  // PackedSceneShading::triangles
#define CAMERA_MATERIAL_BINDING 3          // PackedSceneShading::materials
#define CAMERA_TEXTURE_BINDING 4           // PackedSceneShading::texture_words
#define CAMERA_SKY_RADIANCE_BINDING 5      // SkySamplingTables::radiance_rgba
#define CAMERA_SKY_TABLE_BINDING 6         // SkySamplingTables::table
#define CAMERA_SAMPLE_ESTIMATE_BINDING 7   // vec4 radiance per (sample in chunk, pixel): bake_accumulate's input
#define CAMERA_GUIDE_BINDING 8             // CAMERA_GUIDE_VEC4S_PER_PIXEL vec4 per pixel (guide pass only)
#define CAMERA_RAY_COUNTER_BINDING 9       // uint rays traced
#define CAMERA_TRACE_BINDING_COUNT 10

// The guide pass writes, per pixel (index y * width + x), from the ray through the pixel centre:
//   [0] first-hit shading normal xyz (ENU, facing the camera), w: hit distance in metres (-1: the ray escaped)
//   [1] albedo rgb, w: 1 on the front of a surface (or either side of a double-sided one), 0 otherwise
//   [2] emitted radiance rgb, w: the direct sun's share, the mean over a 2 x 2 grid of rays in the pixel of
//       max(0, n . s) where the sun's centre is visible from their hit, else 0; 0 without a sun (the denoiser
//       keeps shadow edges by it)
#define CAMERA_GUIDE_VEC4S_PER_PIXEL 3

// Bits of CameraTracePushConstants::flags
#define CAMERA_FLAG_SUN_PRESENT 1u     // the sun lights surfaces (next-event estimation)
#define CAMERA_FLAG_SKY_NEXT_EVENT 2u  // path vertices also sample the sky map (MIS), as the bake decides per sky
#define CAMERA_FLAG_GUIDE_PASS 4u      // write the guides of the pixel-centre ray instead of radiance samples

GUSUKU_PUSH_CONSTANTS_BEGIN(CameraTracePushConstants)
    uint width;         // image size, pixels
    uint height;
    uint first_sample;  // index of this dispatch's first sample in every pixel's stream
    uint sample_count;  // samples per pixel in this dispatch (gl_GlobalInvocationID.y)
    uint max_bounces;   // of the irradiance paths from the first hit, as the bake's
    uint seed;
    uint skip_flags;    // triangles with these flags are invisible (kTriangleFlagBuilding: the site without it)
    uint flags;         // CAMERA_FLAG_*
    vec4 intrinsics;    // fx, fy, cx, cy in pixels (gusuku/runtime/runtime.h's pinhole convention)
    vec4 camera_row0;   // rows of the 3x4 matrix [R | c]: ENU = R * camera + c, R's columns the camera's
    vec4 camera_row1;   //   x (right), y (down), z (forward) axes in ENU, c the camera centre in ENU
    vec4 camera_row2;
    vec4 sun_direction_cos_max;      // xyz unit ENU towards the sun, w cos of the disc's angular radius
    vec4 sun_irradiance_ray_offset;  // xyz E_sun (on a plane facing the sun), w ray offset (metres)
GUSUKU_PUSH_CONSTANTS_END(CameraTracePushConstants, pc)

// local_size_x of camera_trace.comp: the same as bake_accumulate.comp's, whose ordered sums it reuses
#define CAMERA_TRACE_WORKGROUP_SIZE 64

#endif

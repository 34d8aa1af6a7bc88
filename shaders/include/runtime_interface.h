// The runtime's raster passes as both sides see them (shaders/runtime/*.vert, *.frag and
// engine/src/runtime/): descriptor sets, bindings, the per-frame uniform block and the push constants, written
// once for GLSL and C++ (see interface_types.h for the layout rules). Push-constant blocks are in their own
// headers, one per stage that has one (a GLSL stage may declare only one).
#ifndef GUSUKU_RUNTIME_INTERFACE_H
#define GUSUKU_RUNTIME_INTERFACE_H

#include "interface_types.h"

// Set 0: per runtime, the same for every draw of a frame.
#define RUNTIME_FRAME_SET 0
#define RUNTIME_FRAME_UNIFORMS_BINDING 0       // FrameUniforms
#define RUNTIME_BUILDING_SHADOW_BINDING 1      // sampler2DShadow: the building alone, from the sun
#define RUNTIME_SITE_SHADOW_BINDING 2          // sampler2DShadow: the site's occluder mesh, from the sun
#define RUNTIME_LIGHTMAP_BINDING 3             // sampler2DArray: E_ind per slot (layer = slot index)
#define RUNTIME_GROUND_IRRADIANCE_BINDING 4    // sampler2DArray: layer 2 slot = E_with, 2 slot + 1 = E_without
#define RUNTIME_GROUND_GEOMETRY_BINDING 5      // sampler2D: RGB unit normal, A height (ENU z)
#define RUNTIME_COLOUR_MATCH_BINDING 6         // storage buffer: the colour match state (colour_match_interface.h)
#define RUNTIME_FRAME_BINDING_COUNT 7
// Set 1: per material of the building.
#define RUNTIME_MATERIAL_SET 1
#define RUNTIME_BASE_COLOUR_BINDING 0          // sampler2D, sRGB: the material's base colour texture (or white)

// Render modes (FrameUniforms::slot_layers.w)
#define RUNTIME_MODE_PROPOSED 0.0
#define RUNTIME_MODE_DIRECT_ONLY 1.0

GUSUKU_UNIFORM_BLOCK_BEGIN(FrameUniforms, RUNTIME_FRAME_SET, RUNTIME_FRAME_UNIFORMS_BINDING)
    mat4 enu_to_clip;          // the camera: ENU -> Vulkan clip (x right, y down, z in [0, 1])
    mat4 enu_to_shadow_clip;   // the sun's view, fitted to the receivers (shadow_fit.h)
    vec4 camera_position;      // xyz ENU metres
    vec4 sun_direction;        // xyz unit towards the sun (ENU); w 1 when the sun shines this frame, else 0
    vec4 sun_irradiance;       // rgb E_sun this frame (bake set units, after cloud cover); w exposure
    vec4 slot_layers;          // x lightmap layer of slot A, y of slot B, z of the overcast slot; w render mode
    vec4 slot_weights;         // x weight of A, y of B, z of the overcast slot (weights include cloud cover)
    vec4 shadow_parameters;    // x 1 / map size, y depth bias per unit tan(angle), z PCF radius (taps), w 1: site shadows on
    vec4 ground_grid;          // x, y south-west corner (ENU m), z cell size (m), w columns
    vec4 ground_parameters;    // x rows, y pull towards the camera (m), z unused, w pass-through threshold
    vec4 direct_only;          // rgb ambient irradiance (bake set units), w shadow darkening factor
    vec4 irradiance_scale;     // x: stored lightmaps and ground terms times this are the bake set's irradiance
                               // (the colour match's mode and gain live in its own state buffer)
GUSUKU_UNIFORM_BLOCK_END(FrameUniforms, frame)

#endif

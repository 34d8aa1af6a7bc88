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
#define RUNTIME_BUILDING_SHADOW_DEPTH_BINDING 7  // sampler2D, nearest: the building's map as depths (gathers)
#define RUNTIME_SUN_HORIZON_BINDING 8     // sampler2DArray, RGBA8 UNORM: the sun horizons (sun_horizon.glsl)
#define RUNTIME_FRAME_BINDING_COUNT 9
// Set 1: per material of the building.
#define RUNTIME_MATERIAL_SET 1
#define RUNTIME_BASE_COLOUR_BINDING 0          // sampler2D, sRGB: the material's base colour texture (or white)

// FrameUniforms::render_mode (RenderMode kBakedLight, kDirectOnly)
#define RUNTIME_RENDER_MODE_PROPOSED 0u
#define RUNTIME_RENDER_MODE_DIRECT_ONLY 1u

// Each vec3 is followed by the scalar that fills its last 4 bytes (interface_types.h's rules).
GUSUKU_UNIFORM_BLOCK_BEGIN(FrameUniforms, RUNTIME_FRAME_SET, RUNTIME_FRAME_UNIFORMS_BINDING)
    mat4 enu_to_clip;              // the camera: ENU -> Vulkan clip (x right, y down, z in [0, 1])
    mat4 enu_to_shadow_clip;       // the sun's view, fitted to the receivers (shadow_fit.h)
    vec3 camera_position;          // ENU metres
    float exposure;                // linear radiance times this is the display value (FrameInput::exposure)
    vec3 sun_direction;            // unit towards the sun (ENU)
    uint sun_shines;               // 1 when the sun shines this frame, else 0
    vec3 sun_irradiance;           // E_sun this frame (bake set units, after cloud cover)
    uint site_shadows;             // 1: the site's occluder casts the sun's shadow this frame (its map is valid)
    vec3 slot_layers;              // lightmap layer of slot A, of slot B, of the overcast slot
    uint render_mode;              // RUNTIME_RENDER_MODE_*
    vec3 slot_weights;             // weight of A, of B, of the overcast slot (weights include cloud cover)
    float irradiance_scale;        // stored lightmaps and ground terms times this are the bake set's irradiance
    vec3 direct_only_ambient;      // direct-only mode's ambient irradiance (bake set units)
    float direct_only_shadow_darkening;  // direct-only mode: the ground's ratio in the building's full shadow
    // The shadow maps' frame constants (ShadowFit), here so no fragment derives them from enu_to_shadow_clip:
    vec3 shadow_map_x_enu;         // unit ENU vector along the maps' x (texel columns; ShadowFit::right_enu)
    float shadow_texel_m;          // one texel's side, metres (ShadowFit::texel_size_m)
    vec3 shadow_map_y_enu;         // unit ENU vector along the maps' y (texel rows, down: -ShadowFit::up_enu)
    float shadow_texel_depth;      // one texel's side in map depth (texel_size_m / depth_range_m)
    float shadow_texel_uv;         // 1 / shadow map size
    float shadow_depth_bias;       // depth bias per unit tan(angle), in the map's depth units
    float shadow_pcf_radius;       // 0: hard building shadow; r: the sun's penumbra, blocker search 2 + r texels out
    float pass_through_threshold;  // |ratio - 1| below this in every channel: the camera pixel is untouched
    float ground_origin_east_m;    // the ground grid's south-west corner (ENU m)
    float ground_origin_north_m;
    float ground_cell_m;           // the ground grid's cell size (m)
    float ground_pull_m;           // the ground pass moves towards the camera by this (m)
    int ground_columns;            // the ground grid's cells west to east (at least 1)
    int ground_rows;               // cells north to south (at least 1)
                                   // (the colour match's mode and gain live in its own state buffer)
GUSUKU_UNIFORM_BLOCK_END(FrameUniforms, frame)

#endif

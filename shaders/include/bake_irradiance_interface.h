// shaders/bake/bake_irradiance.comp as both sides see it: its set-0 bindings (uniform texel buffers for the BVH
// and the scene's shading, bindings 0..4, storage buffers for the rest) and its push-constant block, written
// once for the GLSL and for baker/src/irradiance_tracer.cpp (which binds the buffers in this order). See
// interface_types.h for the rules. (One header per kernel: a GLSL stage may declare only one push-constant
// block.)
#ifndef GUSUKU_BAKE_IRRADIANCE_INTERFACE_H
#define GUSUKU_BAKE_IRRADIANCE_INTERFACE_H

#include "interface_types.h"

// bake_irradiance.comp, set 0
#define BAKE_BVH_NODE_BINDING 0          // Bvh::nodes
#define BAKE_BVH_TRIANGLE_BINDING 1      // Bvh::triangles
#define BAKE_SHADING_TRIANGLE_BINDING 2  // PackedSceneShading::triangles
#define BAKE_MATERIAL_BINDING 3          // PackedSceneShading::materials
#define BAKE_TEXTURE_BINDING 4           // PackedSceneShading::texture_words
#define BAKE_SKY_RADIANCE_BINDING 5      // SkySamplingTables::radiance_rgba
#define BAKE_SKY_TABLE_BINDING 6         // SkySamplingTables::table
#define BAKE_QUERY_POINT_BINDING 7       // QueryPointGpu per point
#define BAKE_SAMPLE_ESTIMATE_BINDING 8   // vec4 per (sample in chunk, point of the range)
#define BAKE_RAY_COUNTER_BINDING 9       // uint rays traced
#define BAKE_IRRADIANCE_BINDING_COUNT 10

// bake_irradiance.comp's specialisation constants. What a pipeline traces is fixed when it is made, not pushed
// per dispatch: the production kernel (the defaults) has the test paths compiled out, and a test that wants one
// gets a pipeline of its own (IrradianceTracer::pipelineFor).
#define BAKE_SKY_NEXT_EVENT_CONSTANT 1                 // bool: the sky map's next-event block compiled in
#define BAKE_TRACE_MODE_CONSTANT 2                     // uint: BAKE_MODE_* below
#define IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT 3  // uint: irradiance_paths.glsl's kBouncesBeforeRoulette

// bake_irradiance.comp: what a pipeline traces (BAKE_TRACE_MODE_CONSTANT).
#define BAKE_MODE_INDIRECT 0u    // E_ind: everything but the direct sun at the point (every bake)
#define BAKE_MODE_SUN_DIRECT 1u  // the direct sun term alone: tests check the sun's sampling against analytic cases

GUSUKU_PUSH_CONSTANTS_BEGIN(BakeIrradiancePushConstants)
    uint point_count;                // points in this dispatch's range
    uint first_point;                // this dispatch traces points [first_point, first_point + point_count)
    uint first_sample;
    uint sample_count;
    uint max_bounces;
    uint seed;
    uint skip_flags;
    uint sun_present;
    vec4 sun_direction_cos_max;      // xyz unit ENU towards the sun, w cos of the disc's angular radius
    vec4 sun_irradiance_ray_offset;  // xyz E_sun (W/m^2 per channel), w ray offset (metres)
    uint sky_next_event;             // 1: sample the sky map too (MIS), 0: cosine lobe alone
    uint sky_rays_at_point;          // sky next-event rays at the query point itself (irradiance_paths.glsl)
    uint samples_per_lane_group;     // 1, 2, 4 or 8 dividing sample_count: consecutive invocations trace this many
                                     // samples of one point (bake_irradiance.comp says why)
GUSUKU_PUSH_CONSTANTS_END(BakeIrradiancePushConstants, pc)

// local_size_x of bake_irradiance.comp and bake_accumulate.comp
#define BAKE_WORKGROUP_SIZE 64

#endif

// shaders/bake/bake_accumulate.comp as both sides see it: its set-0 bindings and push-constant block, written
// once for the GLSL and for baker/src/irradiance_tracer.cpp. See interface_types.h for the rules.
#ifndef GUSUKU_BAKE_ACCUMULATE_INTERFACE_H
#define GUSUKU_BAKE_ACCUMULATE_INTERFACE_H

#include "interface_types.h"

// bake_accumulate.comp, set 0
#define ACCUMULATE_SAMPLE_ESTIMATE_BINDING 0  // the irradiance kernel's scratch
#define ACCUMULATE_SUM_BINDING 1              // vec4 running sums per point
#define ACCUMULATE_LUMINANCE_SQUARE_BINDING 2  // float running sums of squared luminance per point
#define BAKE_ACCUMULATE_BINDING_COUNT 3

GUSUKU_PUSH_CONSTANTS_BEGIN(BakeAccumulatePushConstants)
    uint point_count;   // points in this dispatch's range
    uint sample_count;
    uint first_point;   // the range is points [first_point, first_point + point_count) of the running sums
GUSUKU_PUSH_CONSTANTS_END(BakeAccumulatePushConstants, pc)

// local_size_x, the same as bake_irradiance.comp's
#define BAKE_ACCUMULATE_WORKGROUP_SIZE 64

#endif

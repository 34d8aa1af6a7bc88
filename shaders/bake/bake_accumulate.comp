#version 450
// Adds a chunk's one-sample estimates (bake_irradiance.comp) onto each point's running sum, one sample at a
// time in sample order, so the floating-point sum is the same however the samples were split into chunks,
// dispatches or runs: a resumed bake matches an uninterrupted one bit for bit.

#extension GL_GOOGLE_include_directive : require

#include "bake_accumulate_interface.h"

layout(local_size_x = BAKE_ACCUMULATE_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ACCUMULATE_SAMPLE_ESTIMATE_BINDING) readonly buffer SampleEstimates {
    vec4 sample_estimates[];
};
// xyz: sum of irradiance estimates; w: number of first rays that hit a back face (texel validity).
layout(std430, set = 0, binding = ACCUMULATE_SUM_BINDING) buffer Accumulation { vec4 accumulated[]; };
// The push-constant block `pc` (BakeAccumulatePushConstants) is declared in bake_accumulate_interface.h.

void main() {
    uint point_index = gl_GlobalInvocationID.x;
    if (point_index >= pc.point_count) return;
    vec4 running_sum = accumulated[point_index];
    for (uint s = 0u; s < pc.sample_count; ++s) running_sum += sample_estimates[s * pc.point_count + point_index];
    accumulated[point_index] = running_sum;
}

#version 450
// Adds a chunk's one-sample estimates (bake_irradiance.comp) onto each point's running sum, one sample at a
// time in sample order, so the floating-point sum is the same however the samples were split into chunks,
// dispatches (of all points or of ranges of them) or runs: a resumed bake matches an uninterrupted one bit for bit. Alongside, the sum of each
// estimate's squared luminance (Rec.709 weights, as gusuku/maths/colour.h's luminanceRec709), from which the lightmap
// filter knows how noisy each texel's mean is (lightmap_denoise.h).

#extension GL_GOOGLE_include_directive : require

#include "bake_accumulate_interface.h"

layout(local_size_x = BAKE_ACCUMULATE_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ACCUMULATE_SAMPLE_ESTIMATE_BINDING) readonly buffer SampleEstimates {
    vec4 sample_estimates[];
};
// xyz: sum of irradiance estimates; w: number of first rays that hit a back face (texel validity).
layout(std430, set = 0, binding = ACCUMULATE_SUM_BINDING) buffer Accumulation { vec4 accumulated[]; };
layout(std430, set = 0, binding = ACCUMULATE_LUMINANCE_SQUARE_BINDING) buffer LuminanceSquares {
    float accumulated_luminance_squares[];
};
// The push-constant block `pc` (BakeAccumulatePushConstants) is declared in bake_accumulate_interface.h.

void main() {
    // The scratch holds the dispatch's range of points; the running sums hold every point of the set.
    uint range_index = gl_GlobalInvocationID.x;
    if (range_index >= pc.point_count) return;
    uint point_index = pc.first_point + range_index;
    vec4 running_sum = accumulated[point_index];
    float running_square_sum = accumulated_luminance_squares[point_index];
    for (uint s = 0u; s < pc.sample_count; ++s) {
        const vec4 estimate = sample_estimates[s * pc.point_count + range_index];
        running_sum += estimate;
        const float luminance = dot(estimate.rgb, vec3(0.2126, 0.7152, 0.0722));
        running_square_sum += luminance * luminance;
    }
    accumulated[point_index] = running_sum;
    accumulated_luminance_squares[point_index] = running_square_sum;
}

#version 450
// Colour statistics of the camera frame, first pass (docs/design.md 4, 5 and 8 pass 7; choices in
// engine/include/gusuku/maths/colour_match.h). One invocation per sampled pixel (every stride-th pixel in x and y):
// decode sRGB, convert to CIE Lab (D65, float), leave out clipped pixels (a channel at 255 or all at 0) and
// count them. Each subgroup then reduces its samples with subgroupAdd (no shared memory, no barrier) to the
// valid samples' count, mean and sum of squared deviations from that mean, and one lane writes them as the
// subgroup's partial. colour_statistics_reduce.comp combines the partials and smooths over frames.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define COLOUR_STATISTICS_KERNEL
#include "colour_match_interface.h"
#include "colour.glsl"

layout(local_size_x = COLOUR_STATISTICS_TILE, local_size_y = COLOUR_STATISTICS_TILE) in;

layout(std430, set = 0, binding = COLOUR_STATISTICS_CAMERA_BINDING) readonly buffer CameraPixels {
    uint camera_rgba8[];
};
layout(std430, set = 0, binding = COLOUR_STATISTICS_PARTIAL_BINDING) writeonly buffer Partials {
    ColourStatisticsPartial partials[];
};

void main() {
    uvec2 sample_index = gl_GlobalInvocationID.xy;
    bool in_grid = sample_index.x < pc.samples_x && sample_index.y < pc.samples_y;
    bool clipped = false;
    bool valid = false;
    vec3 lab = vec3(0.0);
    if (in_grid) {
        uvec2 pixel = uvec2(pc.first_sample_offset) + sample_index * pc.stride;
        uint word = camera_rgba8[pixel.y * pc.frame_width + pixel.x];
        uvec3 bytes = uvec3(word & 0xFFu, (word >> 8u) & 0xFFu, (word >> 16u) & 0xFFu);
        clipped = any(equal(bytes, uvec3(255u))) || all(equal(bytes, uvec3(0u)));
        valid = !clipped;
        if (valid) lab = labFromLinearRec709(srgbDecode(vec3(bytes) / 255.0));
    }
    // Every lane takes part in every subgroupAdd (outside any branch); counts are exact in float (<= 64).
    float count = subgroupAdd(valid ? 1.0 : 0.0);
    vec3 sum = subgroupAdd(lab);
    vec3 mean = count > 0.0 ? sum / count : vec3(0.0);
    vec3 deviation = valid ? lab - mean : vec3(0.0);
    vec3 m2 = subgroupAdd(deviation * deviation);
    float clipped_count = subgroupAdd(clipped ? 1.0 : 0.0);
    if (subgroupElect()) {
        uint workgroup = gl_WorkGroupID.y * pc.workgroups_x + gl_WorkGroupID.x;
        uint partial = workgroup * pc.partials_per_workgroup + gl_SubgroupID;
        // Member by member: one access chain per store, which synchronization validation (layer 1.3.239)
        // follows; a whole-struct store compiles to a chain of chains that it misses.
        partials[partial].lab_mean = mean;
        partials[partial].valid_count = count;
        partials[partial].lab_m2 = m2;
        partials[partial].clipped_count = clipped_count;
    }
}

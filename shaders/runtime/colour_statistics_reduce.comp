#version 450
// Colour statistics of the camera frame, second pass: one workgroup combines the partials of
// colour_statistics.comp into the frame's Lab mean and sigma over the valid samples, then updates the smoothed
// statistics in the ColourMatchState (choices in engine/include/gusuku/maths/colour_match.h, which holds the CPU
// reference of every step). Each invocation folds every 64th partial with Chan, Golub and LeVeque's pairwise
// update; lanes combine with subgroupAdd by the law of total variance (grand mean first, then each lane's M2
// plus its count times its squared offset from the grand mean: no sum(x^2) - n mean^2 cancellation); the few
// subgroup totals meet in shared memory behind one barrier; invocation 0 writes the state.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define COLOUR_REDUCE_KERNEL
#include "colour_match_interface.h"

layout(local_size_x = COLOUR_REDUCE_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = COLOUR_REDUCE_PARTIAL_BINDING) readonly buffer Partials {
    ColourStatisticsPartial partials[];
};
layout(std430, set = 0, binding = COLOUR_REDUCE_STATE_BINDING) buffer State { ColourMatchState state; };

struct Moments {
    float count;
    vec3 mean;
    vec3 m2;  // sum of squared deviations from mean
};

Moments combineMoments(Moments a, Moments b) {
    float count = a.count + b.count;
    if (b.count == 0.0) return a;
    if (a.count == 0.0) return b;
    vec3 delta = b.mean - a.mean;
    float b_share = b.count / count;
    return Moments(count, a.mean + delta * b_share, a.m2 + b.m2 + delta * delta * (a.count * b_share));
}

shared float subgroup_count[COLOUR_REDUCE_WORKGROUP_SIZE];
shared vec3 subgroup_mean[COLOUR_REDUCE_WORKGROUP_SIZE];
shared vec3 subgroup_m2[COLOUR_REDUCE_WORKGROUP_SIZE];
shared float subgroup_clipped[COLOUR_REDUCE_WORKGROUP_SIZE];

void main() {
    uint lane = gl_LocalInvocationIndex;
    Moments own = Moments(0.0, vec3(0.0), vec3(0.0));
    float clipped = 0.0;
    for (uint p = lane; p < pc.partial_count; p += COLOUR_REDUCE_WORKGROUP_SIZE) {
        ColourStatisticsPartial partial = partials[p];
        own = combineMoments(own, Moments(partial.valid_count, partial.lab_mean, partial.lab_m2));
        clipped += partial.clipped_count;
    }
    float count = subgroupAdd(own.count);
    vec3 weighted_mean_sum = subgroupAdd(own.count * own.mean);
    vec3 mean = count > 0.0 ? weighted_mean_sum / count : vec3(0.0);
    vec3 offset = own.mean - mean;
    vec3 m2 = subgroupAdd(own.m2 + own.count * offset * offset);
    float clipped_sum = subgroupAdd(clipped);
    if (subgroupElect()) {
        subgroup_count[gl_SubgroupID] = count;
        subgroup_mean[gl_SubgroupID] = mean;
        subgroup_m2[gl_SubgroupID] = m2;
        subgroup_clipped[gl_SubgroupID] = clipped_sum;
    }
    barrier();
    if (lane != 0u) return;

    Moments frame = Moments(0.0, vec3(0.0), vec3(0.0));
    float frame_clipped = 0.0;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
        frame = combineMoments(frame, Moments(subgroup_count[s], subgroup_mean[s], subgroup_m2[s]));
        frame_clipped += subgroup_clipped[s];
    }
    uint valid_samples = uint(frame.count);
    vec3 frame_variance = frame.count > 0.0 ? max(frame.m2 / frame.count, vec3(0.0)) : vec3(0.0);
    state.frame_lab_mean = vec4(frame.mean, 0.0);
    state.frame_lab_sigma = vec4(sqrt(frame_variance), 0.0);
    state.frame_valid_samples = valid_samples;
    state.frame_clipped_samples = uint(frame_clipped);
    state.frame_total_samples = valid_samples + uint(frame_clipped);

    if (pc.reset != 0u) {
        state.camera_valid = 0u;
        state.frames_accepted = 0u;
        state.camera_lab_mean = vec4(0.0);
        state.camera_lab_variance = vec4(0.0);
        state.ground_valid = 0u;  // one reset for the whole match (the ground mode's gain too)
        state.ground_frames_accepted = 0u;
    }
    bool accepted = valid_samples > 0u && valid_samples >= pc.min_valid_samples;
    state.frame_accepted = accepted ? 1u : 0u;
    if (!accepted) return;  // too few valid samples: the smoothed statistics stay as they were
    if (state.camera_valid == 0u) {
        state.camera_lab_mean = vec4(frame.mean, 0.0);
        state.camera_lab_variance = vec4(frame_variance, 0.0);
    } else {
        float alpha = pc.smoothing_weight;
        state.camera_lab_mean.xyz += alpha * (frame.mean - state.camera_lab_mean.xyz);
        state.camera_lab_variance.xyz += alpha * (frame_variance - state.camera_lab_variance.xyz);
    }
    state.camera_valid = 1u;
    state.frames_accepted += 1u;
}

#version 450
// The ground colour match's second pass, one workgroup of GROUND_MATCH_BINS invocations over the samples of
// colour_statistics_ground.comp (lane l takes samples l, l + 64, ...): each lane counts its samples per log-ratio
// bin in a private array, the counts meet in shared memory (one barrier), invocation 0 finds the median bin (the
// smallest whose cumulative count reaches half the samples); then each lane sums the observed and predicted
// colour of its samples within GROUND_MATCH_WINDOW_BINS of it, the sums meet by subgroupAdd and shared memory,
// and invocation 0 forms the clamped von Kries gain observed / predicted per channel and smooths it into the
// ColourMatchState. Two passes over the samples in all: O(samples), not O(samples x bins). The CPU reference of
// every step is in engine/include/gusuku/maths/colour_match.h (measureGroundColourGain, smoothGroundGain).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define GROUND_REDUCE_KERNEL
#include "colour_match_interface.h"

layout(local_size_x = GROUND_MATCH_BINS) in;

layout(std430, set = 0, binding = GROUND_REDUCE_PARTIAL_BINDING) readonly buffer Samples {
    GroundMatchSample samples[];
};
layout(std430, set = 0, binding = GROUND_REDUCE_STATE_BINDING) buffer State { ColourMatchState state; };

shared uint lane_counts[GROUND_MATCH_BINS][GROUND_MATCH_BINS];  // [lane][bin]
shared int window_first;
shared int window_last;
shared int median_bin;
shared vec3 subgroup_observed[GROUND_MATCH_BINS];
shared vec3 subgroup_predicted[GROUND_MATCH_BINS];
shared float subgroup_kept[GROUND_MATCH_BINS];
shared float subgroup_clipped[GROUND_MATCH_BINS];

void main() {
    uint lane = gl_LocalInvocationIndex;
    uint counts[GROUND_MATCH_BINS];
    for (uint b = 0u; b < GROUND_MATCH_BINS; ++b) counts[b] = 0u;
    float clipped = 0.0;
    for (uint s = lane; s < pc.partial_count; s += GROUND_MATCH_BINS) {
        float bin = samples[s].bin;
        if (bin >= 0.0) counts[uint(bin)] += 1u;
        clipped += samples[s].clipped;
    }
    for (uint b = 0u; b < GROUND_MATCH_BINS; ++b) lane_counts[lane][b] = counts[b];
    barrier();
    if (lane == 0u) {
        uint bin_counts[GROUND_MATCH_BINS];
        uint total = 0u;
        for (uint b = 0u; b < GROUND_MATCH_BINS; ++b) {
            uint count = 0u;
            for (uint l = 0u; l < GROUND_MATCH_BINS; ++l) count += lane_counts[l][b];
            bin_counts[b] = count;
            total += count;
        }
        int median = -1;
        uint cumulative = 0u;
        for (int b = 0; b < GROUND_MATCH_BINS && median < 0; ++b) {
            cumulative += bin_counts[b];
            if (total > 0u && 2u * cumulative >= total) median = b;
        }
        median_bin = median;
        window_first = median < 0 ? 1 : max(0, median - GROUND_MATCH_WINDOW_BINS);
        window_last = median < 0 ? 0 : min(GROUND_MATCH_BINS - 1, median + GROUND_MATCH_WINDOW_BINS);
        state.frame_ground_samples = total;
    }
    barrier();
    float first = float(window_first);
    float last = float(window_last);
    vec3 observed = vec3(0.0);
    vec3 predicted = vec3(0.0);
    float kept = 0.0;
    for (uint s = lane; s < pc.partial_count; s += GROUND_MATCH_BINS) {
        float bin = samples[s].bin;
        if (bin >= first && bin <= last) {
            observed += samples[s].observed;
            predicted += samples[s].predicted;
            kept += 1.0;
        }
    }
    vec3 observed_total = subgroupAdd(observed);
    vec3 predicted_total = subgroupAdd(predicted);
    float kept_total = subgroupAdd(kept);
    float clipped_total = subgroupAdd(clipped);
    if (subgroupElect()) {
        subgroup_observed[gl_SubgroupID] = observed_total;
        subgroup_predicted[gl_SubgroupID] = predicted_total;
        subgroup_kept[gl_SubgroupID] = kept_total;
        subgroup_clipped[gl_SubgroupID] = clipped_total;
    }
    barrier();
    if (lane != 0u) return;

    vec3 observed_sum = vec3(0.0);
    vec3 predicted_sum = vec3(0.0);
    float kept_sum = 0.0;
    float clipped_sum = 0.0;
    for (uint g = 0u; g < gl_NumSubgroups; ++g) {
        observed_sum += subgroup_observed[g];
        predicted_sum += subgroup_predicted[g];
        kept_sum += subgroup_kept[g];
        clipped_sum += subgroup_clipped[g];
    }
    int median = median_bin;
    float limit = max(1.0, state.gain_limit);
    bool accepted = median >= 0 && uint(kept_sum) >= pc.min_valid_samples &&
                    all(greaterThan(predicted_sum, vec3(0.0)));
    vec3 gain = accepted ? clamp(observed_sum / predicted_sum, vec3(1.0 / limit), vec3(limit)) : vec3(1.0);
    state.frame_ground_gain = gain;
    state.frame_ground_median_bin = float(median);
    state.frame_ground_observed = vec4(observed_sum, 0.0);
    state.frame_ground_predicted = vec4(predicted_sum, 0.0);
    state.frame_ground_kept = uint(kept_sum);
    state.frame_ground_clipped = uint(clipped_sum);
    state.frame_ground_accepted = accepted ? 1u : 0u;
    if (pc.reset != 0u) {
        state.ground_valid = 0u;
        state.ground_frames_accepted = 0u;
        state.ground_gain = vec4(1.0, 1.0, 1.0, 0.0);
        // A cut forgets the Lab modes' statistics too (one reset for the whole match).
        state.camera_valid = 0u;
        state.frames_accepted = 0u;
    }
    if (!accepted) return;  // a frame without enough ground keeps the gain as it was
    if (state.ground_valid == 0u) state.ground_gain = vec4(gain, 0.0);
    else state.ground_gain.xyz += pc.smoothing_weight * (gain - state.ground_gain.xyz);
    state.ground_valid = 1u;
    state.ground_frames_accepted += 1u;
}

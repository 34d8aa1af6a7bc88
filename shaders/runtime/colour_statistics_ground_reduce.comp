#version 450
// The ground colour match's second pass: one workgroup, invocation b sums bin b over every workgroup's partial
// of colour_statistics_ground.comp (in workgroup order); invocation 0 then finds the median bin (the smallest
// whose cumulative count reaches half the samples), sums the bins within GROUND_MATCH_WINDOW_BINS of it, forms
// the clamped von Kries gain observed / predicted per channel and smooths it into the ColourMatchState. The CPU
// reference of every step is in engine/include/gusuku/colour_match.h (measureGroundColourGain,
// smoothGroundGain).
#extension GL_GOOGLE_include_directive : require

#define GROUND_REDUCE_KERNEL
#include "colour_match_interface.h"

layout(local_size_x = GROUND_MATCH_BINS) in;

layout(std430, set = 0, binding = GROUND_REDUCE_PARTIAL_BINDING) readonly buffer Partials {
    GroundMatchPartial partials[];
};
layout(std430, set = 0, binding = GROUND_REDUCE_STATE_BINDING) buffer State { ColourMatchState state; };

shared float bin_count[GROUND_MATCH_BINS];
shared vec3 bin_observed[GROUND_MATCH_BINS];
shared vec3 bin_predicted[GROUND_MATCH_BINS];
shared float bin_clipped[GROUND_MATCH_BINS];

void main() {
    uint lane = gl_LocalInvocationIndex;
    float count = 0.0;
    vec3 observed = vec3(0.0);
    vec3 predicted = vec3(0.0);
    float clipped = 0.0;
    for (uint w = 0u; w < pc.partial_count; ++w) {
        GroundMatchPartial partial = partials[w * GROUND_MATCH_BINS + lane];
        observed += partial.observed_count.xyz;
        count += partial.observed_count.w;
        predicted += partial.predicted_clipped.xyz;
        clipped += partial.predicted_clipped.w;
    }
    bin_count[lane] = count;
    bin_observed[lane] = observed;
    bin_predicted[lane] = predicted;
    bin_clipped[lane] = clipped;
    barrier();
    if (lane != 0u) return;

    float total = 0.0;
    float clipped_total = 0.0;
    for (uint b = 0u; b < GROUND_MATCH_BINS; ++b) {
        total += bin_count[b];
        clipped_total += bin_clipped[b];
    }
    int median = -1;
    float cumulative = 0.0;
    for (int b = 0; b < GROUND_MATCH_BINS && median < 0; ++b) {
        cumulative += bin_count[b];
        if (total > 0.0 && 2.0 * cumulative >= total) median = b;
    }
    float kept = 0.0;
    vec3 observed_sum = vec3(0.0);
    vec3 predicted_sum = vec3(0.0);
    if (median >= 0) {
        for (int b = max(0, median - GROUND_MATCH_WINDOW_BINS);
             b <= min(GROUND_MATCH_BINS - 1, median + GROUND_MATCH_WINDOW_BINS); ++b) {
            kept += bin_count[b];
            observed_sum += bin_observed[b];
            predicted_sum += bin_predicted[b];
        }
    }
    float limit = max(1.0, state.gain_limit);
    bool accepted = median >= 0 && uint(kept) >= pc.min_valid_samples && all(greaterThan(predicted_sum, vec3(0.0)));
    vec3 gain = accepted ? clamp(observed_sum / predicted_sum, vec3(1.0 / limit), vec3(limit)) : vec3(1.0);
    state.frame_ground_gain = vec4(gain, float(median));
    state.frame_ground_observed = vec4(observed_sum, 0.0);
    state.frame_ground_predicted = vec4(predicted_sum, 0.0);
    state.frame_ground_samples = uint(total);
    state.frame_ground_kept = uint(kept);
    state.frame_ground_clipped = uint(clipped_total);
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

#version 450
// The sun-evidence estimator's second pass, one workgroup of SUN_EVIDENCE_BINS invocations over sun_evidence.comp's
// samples (lane l takes samples l, l + 64, ...), as colour_statistics_ground_reduce.comp: each lane counts its
// samples per bin in a private array, the counts meet in shared memory (one barrier) and invocation 0 takes the
// quantile. Two passes: the shadowed samples' median log2 ratio (the shade's level, log2 g), then the lit samples'
// strengths s_i = (2^(r_i - log2 g) - 1) / q_i, whose median and quartiles give s, its standard error, the
// probability that the sun is out and the confidence. CPU reference: estimateSunEvidence
// (engine/include/gusuku/maths/sun_evidence.h). Writes the frame slot's SunEvidenceResult, read by the host after
// the slot's fence.
#extension GL_GOOGLE_include_directive : require

#define SUN_EVIDENCE_REDUCE_KERNEL
#include "sun_evidence_interface.h"

layout(local_size_x = SUN_EVIDENCE_BINS) in;

layout(std430, set = 0, binding = SUN_EVIDENCE_REDUCE_SAMPLE_BINDING) readonly buffer Samples {
    SunEvidenceSampleGpu samples[];
};
layout(std430, set = 0, binding = SUN_EVIDENCE_REDUCE_RESULT_BINDING) buffer Results { SunEvidenceResult results[]; };

shared uint lane_counts[SUN_EVIDENCE_BINS][SUN_EVIDENCE_BINS];  // [lane][bin]
shared float lane_sums[SUN_EVIDENCE_BINS];
shared float lane_kept[SUN_EVIDENCE_BINS];
shared uint median_bin;
shared float shade_log2;

uint binOf(float value, float lowest, float span) {
    float index = floor((value - lowest) / span * float(SUN_EVIDENCE_BINS));
    if (!(index >= 0.0)) return 0u;
    return uint(min(index, float(SUN_EVIDENCE_BINS - 1)));
}

bool inWindow(uint bin, uint median) {
    return bin + SUN_EVIDENCE_WINDOW_BINS >= median && bin <= median + SUN_EVIDENCE_WINDOW_BINS;
}

// Invocation 0: the lanes' counts summed per bin.
uint bin_counts[SUN_EVIDENCE_BINS];
float sumCounts() {
    float total = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) {
        uint count = 0u;
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) count += lane_counts[l][b];
        bin_counts[b] = count;
        total += float(count);
    }
    return total;
}

// The median's bin: the first whose cumulative count reaches half the total.
uint medianBinOf(float total) {
    float before = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) {
        float count = float(bin_counts[b]);
        if (count > 0.0 && before + count >= 0.5 * total) return b;
        before += count;
    }
    return 0u;
}

// sunEvidenceQuantile over bin_counts.
float quantile(float total, float q, float lowest, float span) {
    if (!(total > 0.0)) return lowest;
    float target = q * total;
    float before = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) {
        float count = float(bin_counts[b]);
        if (count > 0.0 && before + count >= target) {
            float within = clamp((target - before) / count, 0.0, 1.0);
            return lowest + span * (float(b) + within) / float(SUN_EVIDENCE_BINS);
        }
        before += count;
    }
    return lowest + span;
}

// Invocation 0: the lanes' window sums added in lane order, over their count (0 when none).
float windowMean() {
    float sum = 0.0;
    float kept = 0.0;
    for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) {
        sum += lane_sums[l];
        kept += lane_kept[l];
    }
    return kept > 0.0 ? sum / kept : 0.0;
}

bool isLit(uint s) {
    return samples[s].kind == SUN_EVIDENCE_KIND_LIT && samples[s].sun_share >= SUN_EVIDENCE_MIN_SUN_SHARE;
}

float strengthOf(uint s, float level) { return (exp2(samples[s].log2_ratio - level) - 1.0) / samples[s].sun_share; }

void main() {
    uint lane = gl_LocalInvocationIndex;
    // 1. The shade's histogram and the median's bin.
    uint counts[SUN_EVIDENCE_BINS];
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) counts[b] = 0u;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == SUN_EVIDENCE_KIND_SHADOWED)
            counts[binOf(samples[s].log2_ratio, SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN)] += 1u;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) lane_counts[lane][b] = counts[b];
    barrier();
    float shadowed = 0.0;
    if (lane == 0u) {
        shadowed = sumCounts();
        median_bin = medianBinOf(shadowed);
    }
    barrier();
    // 2. Its trimmed mean: log2 g.
    uint median = median_bin;
    float sum = 0.0;
    float kept = 0.0;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == SUN_EVIDENCE_KIND_SHADOWED &&
            inWindow(binOf(samples[s].log2_ratio, SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN),
                     median)) {
            sum += samples[s].log2_ratio;
            kept += 1.0;
        }
    lane_sums[lane] = sum;
    lane_kept[lane] = kept;
    barrier();
    if (lane == 0u) shade_log2 = windowMean();
    barrier();
    // 3. The lit samples' strengths against it: histogram, median's bin, quartiles.
    float level = shade_log2;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) counts[b] = 0u;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (isLit(s)) counts[binOf(strengthOf(s, level), SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN)] += 1u;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) lane_counts[lane][b] = counts[b];
    barrier();
    float lit = 0.0;
    float interquartile = 0.0;
    if (lane == 0u) {
        lit = sumCounts();
        median_bin = medianBinOf(lit);
        interquartile = quantile(lit, 0.75, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN) -
                        quantile(lit, 0.25, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN);
    }
    barrier();
    // 4. Their trimmed mean: s.
    median = median_bin;
    sum = 0.0;
    kept = 0.0;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (isLit(s)) {
            float strength = strengthOf(s, level);
            if (inWindow(binOf(strength, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN), median)) {
                sum += strength;
                kept += 1.0;
            }
        }
    lane_sums[lane] = sum;
    lane_kept[lane] = kept;
    barrier();
    if (lane != 0u) return;

    SunEvidenceResult result;
    result.sun_out_probability = 0.5;
    result.confidence = 0.0;
    result.sun_strength = -1.0;
    result.cue = 0u;
    result.shadowed_samples = uint(shadowed);
    result.lit_samples = uint(lit);
    result.shade_log2_ratio = 0.0;
    result.strength = 0.0;
    result.strength_standard_error = 0.0;
    result.frame_serial = pc.frame_serial;
    result.result_reserved0 = 0u;
    result.result_reserved1 = 0u;
    float fewest = min(shadowed, lit);
    if (fewest >= float(SUN_EVIDENCE_MIN_SAMPLES)) {
        float strength = windowMean();
        float standard_error = 1.2533 * (interquartile / 1.349) / sqrt(lit);
        float width = max(SUN_EVIDENCE_MIN_WIDTH, standard_error);
        float probability = 1.0 / (1.0 + exp(-(strength - SUN_EVIDENCE_OUT_STRENGTH) / width));
        result.sun_out_probability = probability;
        result.confidence = min(1.0, fewest / float(SUN_EVIDENCE_FULL_SAMPLES)) *
                            clamp(1.0 - standard_error / SUN_EVIDENCE_OUT_STRENGTH, 0.0, 1.0);
        result.sun_strength = probability >= 0.5 ? strength : -1.0;
        result.cue = 1u;
        result.shade_log2_ratio = level;
        result.strength = strength;
        result.strength_standard_error = standard_error;
    }
    results[pc.result_index] = result;
}

#version 450
// The sun-evidence estimator's second pass, one workgroup of SUN_EVIDENCE_BINS invocations over sun_evidence.comp's
// samples (lane l takes samples l, l + 64, ...), as colour_statistics_ground_reduce.comp: each lane counts its
// samples per bin in a private array, the counts meet in shared memory (one barrier) and invocation 0 takes the
// quantile. First the camera response's power from each side's two halves (sun_evidence.h: the response), every
// ratio then linearised through it; then two passes: the shadowed samples' median log2 ratio (the shade's level, log2 g), then the lit samples'
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
shared float lane_fit[SUN_EVIDENCE_BINS][6];  // the response's sums per lane (main's step 0)
shared float split_level;
shared float side_samples[2];  // per side (shadowed, lit): responseSide's reading
shared float side_level_apart[2];
shared float side_ratio_apart[2];
shared uint side_valid[2];
shared uint side_median[2];
shared float response_gamma;

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

// The ratio linearised through the camera response's power (estimateSunEvidence's ratioOf).
float ratioOf(uint s, float gamma) {
    return gamma == 1.0 ? samples[s].log2_ratio
                        : (samples[s].log2_ratio + samples[s].log2_predicted) / gamma - samples[s].log2_predicted;
}

bool isLit(uint s) {
    return samples[s].kind == SUN_EVIDENCE_KIND_LIT && samples[s].sun_share >= SUN_EVIDENCE_MIN_SUN_SHARE;
}

float strengthOf(uint s, float level, float gamma) {
    return (exp2(ratioOf(s, gamma) - level) - 1.0) / samples[s].sun_share;
}

// The shadowed samples' histogram of ratioOf(s, gamma) into lane_counts (each lane its own row).
void shadeHistogram(uint lane, float gamma) {
    uint counts[SUN_EVIDENCE_BINS];
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) counts[b] = 0u;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == SUN_EVIDENCE_KIND_SHADOWED)
            counts[binOf(ratioOf(s, gamma), SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN)] += 1u;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) lane_counts[lane][b] = counts[b];
}

// The raw ratios' histogram of one side's samples in one half (0: predicted level below split, 1: at or above).
void sideHistogram(uint lane, float kind, uint side, float split) {
    uint counts[SUN_EVIDENCE_BINS];
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) counts[b] = 0u;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == kind && (samples[s].log2_predicted >= split) == (side == 1u))
            counts[binOf(samples[s].log2_ratio, SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN)] += 1u;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) lane_counts[lane][b] = counts[b];
}

// One side's reading of the response (responseSide in sun_evidence.cpp) into side_*[slot]; every lane calls it.
void responseSide(uint lane, float kind, uint slot) {
    float count = 0.0;
    float level = 0.0;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == kind) {
            count += 1.0;
            level += samples[s].log2_predicted;
        }
    lane_sums[lane] = level;
    lane_kept[lane] = count;
    barrier();
    if (lane == 0u) {
        float total_n = 0.0;
        float total_x = 0.0;
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) {
            total_n += lane_kept[l];
            total_x += lane_sums[l];
        }
        side_samples[slot] = total_n;
        split_level = total_n > 0.0 ? total_x / total_n : 0.0;
    }
    barrier();
    float split = split_level;
    for (uint side = 0u; side < 2u; ++side) {
        sideHistogram(lane, kind, side, split);
        barrier();
        if (lane == 0u) side_median[side] = medianBinOf(sumCounts());
        barrier();
    }
    float fit[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // kept, ratio, level: darker half, then lighter
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS) {
        if (samples[s].kind != kind) continue;
        uint side = samples[s].log2_predicted >= split ? 1u : 0u;
        if (!inWindow(binOf(samples[s].log2_ratio, SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN),
                      side_median[side]))
            continue;
        fit[3u * side] += 1.0;
        fit[3u * side + 1u] += samples[s].log2_ratio;
        fit[3u * side + 2u] += samples[s].log2_predicted;
    }
    for (uint k = 0u; k < 6u; ++k) lane_fit[lane][k] = fit[k];
    barrier();
    if (lane == 0u) {
        float total[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l)
            for (uint k = 0u; k < 6u; ++k) total[k] += lane_fit[l][k];
        float half_samples = 0.5 * float(SUN_EVIDENCE_MIN_SAMPLES);
        uint valid = 0u;
        side_level_apart[slot] = 0.0;
        side_ratio_apart[slot] = 0.0;
        if (side_samples[slot] >= float(SUN_EVIDENCE_MIN_SAMPLES) && total[0] >= half_samples &&
            total[3] >= half_samples) {
            side_level_apart[slot] = total[5] / total[3] - total[2] / total[0];
            side_ratio_apart[slot] = total[4] / total[3] - total[1] / total[0];
            valid = side_level_apart[slot] >= SUN_EVIDENCE_MIN_RESPONSE_SPREAD_LOG2 ? 1u : 0u;
        }
        side_valid[slot] = valid;
    }
    barrier();
}

void main() {
    uint lane = gl_LocalInvocationIndex;
    // 0. The camera response's power (sun_evidence.h: responseGamma): on each side its samples split at their mean
    //    predicted level, each half's trimmed mean ratio about its median and the mean level of the samples kept;
    //    the sides' slopes pooled by their samples and spread.
    responseSide(lane, SUN_EVIDENCE_KIND_SHADOWED, 0u);
    responseSide(lane, SUN_EVIDENCE_KIND_LIT, 1u);
    if (lane == 0u) {
        float spread = 0.0;
        float moved = 0.0;
        for (uint k = 0u; k < 2u; ++k)
            if (side_valid[k] != 0u) {
                spread += side_samples[k] * side_level_apart[k] * side_level_apart[k];
                moved += side_samples[k] * side_level_apart[k] * side_ratio_apart[k];
            }
        response_gamma = spread > 0.0 ? clamp(1.0 + moved / spread, SUN_EVIDENCE_MIN_RESPONSE_GAMMA,
                                              SUN_EVIDENCE_MAX_RESPONSE_GAMMA)
                                      : 1.0;
    }
    barrier();
    float gamma = response_gamma;
    // 1. The shade's histogram of the linearised ratios and the median's bin.
    shadeHistogram(lane, gamma);
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
            inWindow(binOf(ratioOf(s, gamma), SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN),
                     median)) {
            sum += ratioOf(s, gamma);
            kept += 1.0;
        }
    lane_sums[lane] = sum;
    lane_kept[lane] = kept;
    barrier();
    // Too little shade in view: the lit samples against the app's exposure, g = 1 (the metered ground, cue 2).
    if (lane == 0u) shade_log2 = shadowed >= float(SUN_EVIDENCE_MIN_SAMPLES) ? windowMean() : 0.0;
    barrier();
    // 3. The lit samples' strengths against it: histogram, median's bin, quartiles.
    float level = shade_log2;
    uint counts[SUN_EVIDENCE_BINS];
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) counts[b] = 0u;
    for (uint s = lane; s < pc.sample_count; s += SUN_EVIDENCE_BINS)
        if (isLit(s)) counts[binOf(strengthOf(s, level, gamma), SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN)] += 1u;
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
            float strength = strengthOf(s, level, gamma);
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
    result.response_gamma = gamma;
    result.result_reserved1 = 0u;
    float fewest = min(shadowed, lit);
    bool boundary = shadowed >= float(SUN_EVIDENCE_MIN_SAMPLES);
    if (lit >= float(SUN_EVIDENCE_MIN_SAMPLES)) {
        float strength = windowMean();
        float standard_error = 1.2533 * (interquartile / 1.349) / sqrt(lit);
        float width = max(SUN_EVIDENCE_MIN_WIDTH, standard_error);
        float probability = 1.0 / (1.0 + exp(-(strength - SUN_EVIDENCE_OUT_STRENGTH) / width));
        result.sun_out_probability = probability;
        // The metered ground's confidence stays 0: it holds only where the app's exposure is metered.
        result.confidence = boundary ? min(1.0, fewest / float(SUN_EVIDENCE_FULL_SAMPLES)) *
                                           clamp(1.0 - standard_error / SUN_EVIDENCE_OUT_STRENGTH, 0.0, 1.0)
                                     : 0.0;
        result.sun_strength = probability >= 0.5 ? strength : -1.0;
        result.cue = boundary ? 1u : 2u;
        result.shade_log2_ratio = level;
        result.strength = strength;
        result.strength_standard_error = standard_error;
    }
    results[pc.result_index] = result;
}

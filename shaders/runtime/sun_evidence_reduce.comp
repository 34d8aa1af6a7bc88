#version 450
// The sun-evidence estimator's second pass, one workgroup of SUN_EVIDENCE_BINS invocations over the samples that
// colour_statistics_ground.comp wrote (lane l takes samples l, l + 64, ...), after the frame's site map is drawn.
// First each lane looks its SITE_LOOKUP samples up in the site map and writes their kind (lit, shadowed, or none in
// the penumbra) in place; then the statistics of estimateSunEvidence (engine/include/gusuku/maths/sun_evidence.h,
// the CPU reference): the camera response's power from each side's two halves (the response), every ratio then
// linearised through it; the shadowed samples' trimmed mean log2 ratio about their median (the shade's level, log2
// g; 0 with too little shade, the metered ground's g = 1); then the lit samples' strengths s_i = (2^(r_i - log2 g) -
// 1) / q_i, whose median and quartiles give s, its standard error, the probability that the sun is out and the
// confidence. Writes the frame slot's SunEvidenceResult, read by the host after the slot's fence.
//
// Cheap on llvmpipe, which runs a barrier as a switch between invocations: seven barriers in all, one per pass over
// the samples, and the passes after the first read only the shadowed and lit samples (packed by the first). The histograms are counted by shared-memory atomics (integer counts, so their order does not matter),
// and after each barrier every lane reads the same shared sums in the same lane order, so every lane holds the same
// medians and means without a second barrier to hand them out.
#extension GL_GOOGLE_include_directive : require

#define SUN_EVIDENCE_REDUCE_KERNEL
#include "sun_evidence_interface.h"

layout(local_size_x = SUN_EVIDENCE_BINS) in;

layout(std430, set = 0, binding = SUN_EVIDENCE_REDUCE_SAMPLE_BINDING) buffer Samples {
    SunEvidenceGroundFrame sun_frame;  // the ground kernel's; unread here
    SunEvidenceSampleGpu samples[];
};
layout(std430, set = 0, binding = SUN_EVIDENCE_REDUCE_RESULT_BINDING) buffer Results { SunEvidenceResult results[]; };
layout(set = 0, binding = SUN_EVIDENCE_REDUCE_SITE_SHADOW_BINDING) uniform sampler2DShadow site_shadow;

const uint kShade = 4u;  // histograms[kShade]: the shadowed samples' linearised ratios
const uint kLit = 5u;    // histograms[kLit]: the lit samples' strengths
// 0-3: the response's raw ratios per side (0 shadowed, 1 lit) and half (0 darker, 1 lighter): 2 side + half.
shared uint histograms[6][SUN_EVIDENCE_BINS];
shared float lane_sides[SUN_EVIDENCE_BINS][4];  // per side: samples, sum of log2 predicted
shared float lane_fit[SUN_EVIDENCE_BINS][12];   // per side, per half: kept, sum of ratios, sum of levels
shared float lane_shade[SUN_EVIDENCE_BINS][2];  // the shade's window: sum, kept
shared float lane_lit[SUN_EVIDENCE_BINS][2];    // the strengths' window: sum, kept

uint binOf(float value, float lowest, float span) {
    float index = floor((value - lowest) / span * float(SUN_EVIDENCE_BINS));
    if (!(index >= 0.0)) return 0u;
    return uint(min(index, float(SUN_EVIDENCE_BINS - 1)));
}

uint ratioBin(float log2_ratio) {
    return binOf(log2_ratio, SUN_EVIDENCE_LOWEST_LOG2_RATIO, SUN_EVIDENCE_LOG2_RATIO_SPAN);
}

bool inWindow(uint bin, uint median) {
    return bin + SUN_EVIDENCE_WINDOW_BINS >= median && bin <= median + SUN_EVIDENCE_WINDOW_BINS;
}

// A histogram's count, summed in bin order.
float totalOf(uint h) {
    float total = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) total += float(histograms[h][b]);
    return total;
}

// The median's bin: the first whose cumulative count reaches half the total.
uint medianBinOf(uint h, float total) {
    float before = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) {
        float count = float(histograms[h][b]);
        if (count > 0.0 && before + count >= 0.5 * total) return b;
        before += count;
    }
    return 0u;
}

// sunEvidenceQuantile over histogram h.
float quantile(uint h, float total, float q, float lowest, float span) {
    if (!(total > 0.0)) return lowest;
    float target = q * total;
    float before = 0.0;
    for (uint b = 0u; b < SUN_EVIDENCE_BINS; ++b) {
        float count = float(histograms[h][b]);
        if (count > 0.0 && before + count >= target) {
            float within = clamp((target - before) / count, 0.0, 1.0);
            return lowest + span * (float(b) + within) / float(SUN_EVIDENCE_BINS);
        }
        before += count;
    }
    return lowest + span;
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

// The side of a kind: 0 shadowed, 1 lit, 2 neither.
uint sideOf(float kind) {
    return kind == SUN_EVIDENCE_KIND_SHADOWED ? 0u : kind == SUN_EVIDENCE_KIND_LIT ? 1u : 2u;
}

// 0. The site map's verdict on each SITE_LOOKUP sample (the bilinear compare at its cell's centre); each side's
//    samples and predicted levels (the response's split); and the lane's shadowed and lit samples packed, in their
//    order, into its own slots lane, lane + 64, ... (the k-th at or before where it was read, so nothing unread is
//    overwritten): the later passes read only those, `kept` of them. Returns kept.
uint resolveKinds(uint lane) {
    float sides[4] = float[4](0.0, 0.0, 0.0, 0.0);
    uint kept = 0u;
    for (uint r = lane; r < pc.sample_count; r += SUN_EVIDENCE_BINS) {
        float kind = samples[r].kind;
        if (kind == SUN_EVIDENCE_KIND_SITE_LOOKUP) {
            float visibility = texture(site_shadow, samples[r].site_coordinates);
            kind = visibility <= SUN_EVIDENCE_SHADOWED_VISIBILITY ? SUN_EVIDENCE_KIND_SHADOWED
                   : visibility >= SUN_EVIDENCE_LIT_VISIBILITY    ? SUN_EVIDENCE_KIND_LIT
                                                                  : SUN_EVIDENCE_KIND_NONE;
        }
        uint side = sideOf(kind);
        if (side == 2u) continue;
        float log2_predicted = samples[r].log2_predicted;
        sides[2u * side] += 1.0;
        sides[2u * side + 1u] += log2_predicted;
        uint packed = lane + kept * SUN_EVIDENCE_BINS;  // read back by this same invocation only
        samples[packed].log2_ratio = samples[r].log2_ratio;
        samples[packed].sun_share = samples[r].sun_share;
        samples[packed].kind = kind;
        samples[packed].log2_predicted = log2_predicted;
        ++kept;
    }
    for (uint k = 0u; k < 4u; ++k) lane_sides[lane][k] = sides[k];
    return kept;
}

// The camera response's power (sun_evidence.h: responseGamma) from the fit's shared sums: per side, its halves'
// trimmed means of ratio and level; the sides' slopes pooled by their samples and spread.
float responseGamma(float side_samples[2]) {
    float total[12];
    for (uint k = 0u; k < 12u; ++k) total[k] = 0.0;
    for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l)
        for (uint k = 0u; k < 12u; ++k) total[k] += lane_fit[l][k];
    float spread = 0.0;
    float moved = 0.0;
    float half_samples = 0.5 * float(SUN_EVIDENCE_MIN_SAMPLES);
    for (uint side = 0u; side < 2u; ++side) {
        uint f = 6u * side;
        if (!(side_samples[side] >= float(SUN_EVIDENCE_MIN_SAMPLES) && total[f] >= half_samples &&
              total[f + 3u] >= half_samples))
            continue;
        float level_apart = total[f + 5u] / total[f + 3u] - total[f + 2u] / total[f];
        float ratio_apart = total[f + 4u] / total[f + 3u] - total[f + 1u] / total[f];
        if (!(level_apart >= SUN_EVIDENCE_MIN_RESPONSE_SPREAD_LOG2)) continue;
        spread += side_samples[side] * level_apart * level_apart;
        moved += side_samples[side] * level_apart * ratio_apart;
    }
    return spread > 0.0 ? clamp(1.0 + moved / spread, SUN_EVIDENCE_MIN_RESPONSE_GAMMA, SUN_EVIDENCE_MAX_RESPONSE_GAMMA)
                        : 1.0;
}

void main() {
    uint lane = gl_LocalInvocationIndex;
    for (uint h = 0u; h < 6u; ++h) histograms[h][lane] = 0u;
    uint end = lane + resolveKinds(lane) * SUN_EVIDENCE_BINS;  // past the lane's packed samples
    barrier();
    float side_samples[2];
    float split[2];
    for (uint side = 0u; side < 2u; ++side) {
        float n = 0.0;
        float x = 0.0;
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) {
            n += lane_sides[l][2u * side];
            x += lane_sides[l][2u * side + 1u];
        }
        side_samples[side] = n;
        split[side] = n > 0.0 ? x / n : 0.0;
    }

    // 1. The response: each side's halves (split at the side's mean predicted level), their raw ratios' medians...
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS) {
        uint side = sideOf(samples[s].kind);
        if (side == 2u) continue;
        uint half_index = samples[s].log2_predicted >= split[side] ? 1u : 0u;
        atomicAdd(histograms[2u * side + half_index][ratioBin(samples[s].log2_ratio)], 1u);
    }
    barrier();
    uint half_median[4];
    for (uint h = 0u; h < 4u; ++h) half_median[h] = medianBinOf(h, totalOf(h));
    // ... and the trimmed sums about them, then the power.
    float fit[12];
    for (uint k = 0u; k < 12u; ++k) fit[k] = 0.0;
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS) {
        uint side = sideOf(samples[s].kind);
        if (side == 2u) continue;
        uint half_index = samples[s].log2_predicted >= split[side] ? 1u : 0u;
        if (!inWindow(ratioBin(samples[s].log2_ratio), half_median[2u * side + half_index])) continue;
        uint f = 6u * side + 3u * half_index;
        fit[f] += 1.0;
        fit[f + 1u] += samples[s].log2_ratio;
        fit[f + 2u] += samples[s].log2_predicted;
    }
    for (uint k = 0u; k < 12u; ++k) lane_fit[lane][k] = fit[k];
    barrier();
    float gamma = responseGamma(side_samples);

    // 2. The shade's histogram of the linearised ratios, its median's bin and trimmed mean: log2 g.
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == SUN_EVIDENCE_KIND_SHADOWED) atomicAdd(histograms[kShade][ratioBin(ratioOf(s, gamma))], 1u);
    barrier();
    float shadowed = totalOf(kShade);
    uint median = medianBinOf(kShade, shadowed);
    float sum = 0.0;
    float kept = 0.0;
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS)
        if (samples[s].kind == SUN_EVIDENCE_KIND_SHADOWED && inWindow(ratioBin(ratioOf(s, gamma)), median)) {
            sum += ratioOf(s, gamma);
            kept += 1.0;
        }
    lane_shade[lane][0] = sum;
    lane_shade[lane][1] = kept;
    barrier();
    // Too little shade in view: the lit samples against the app's exposure, g = 1 (the metered ground, cue 2).
    float level = 0.0;
    if (shadowed >= float(SUN_EVIDENCE_MIN_SAMPLES)) {
        sum = 0.0;
        kept = 0.0;
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) {
            sum += lane_shade[l][0];
            kept += lane_shade[l][1];
        }
        level = kept > 0.0 ? sum / kept : 0.0;
    }

    // 3. The lit samples' strengths against it: histogram, median's bin, quartiles, trimmed mean: s.
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS)
        if (isLit(s))
            atomicAdd(histograms[kLit][binOf(strengthOf(s, level, gamma), SUN_EVIDENCE_LOWEST_STRENGTH,
                                             SUN_EVIDENCE_STRENGTH_SPAN)], 1u);
    barrier();
    float lit = totalOf(kLit);
    median = medianBinOf(kLit, lit);
    sum = 0.0;
    kept = 0.0;
    for (uint s = lane; s < end; s += SUN_EVIDENCE_BINS)
        if (isLit(s)) {
            float strength = strengthOf(s, level, gamma);
            if (inWindow(binOf(strength, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN), median)) {
                sum += strength;
                kept += 1.0;
            }
        }
    lane_lit[lane][0] = sum;
    lane_lit[lane][1] = kept;
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
        sum = 0.0;
        kept = 0.0;
        for (uint l = 0u; l < SUN_EVIDENCE_BINS; ++l) {
            sum += lane_lit[l][0];
            kept += lane_lit[l][1];
        }
        float strength = kept > 0.0 ? sum / kept : 0.0;
        float interquartile = quantile(kLit, lit, 0.75, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN) -
                              quantile(kLit, lit, 0.25, SUN_EVIDENCE_LOWEST_STRENGTH, SUN_EVIDENCE_STRENGTH_SPAN);
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

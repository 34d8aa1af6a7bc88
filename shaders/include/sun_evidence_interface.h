// The sun-evidence estimator's GPU layout (issue 41 items 1 and 2), written once for the GLSL
// (shaders/runtime/colour_statistics_ground.comp, which classifies the samples as it measures the ground, and
// sun_evidence_reduce.comp) and for C++ (engine/src/runtime/sun_evidence_pass.cpp and colour_statistics_pass.cpp,
// which pin every offset with static_assert). The CPU reference and the choices: gusuku/maths/sun_evidence.h, whose
// kSunEvidence* constants sun_evidence_pass.cpp holds equal to these. interface_types.h gives the rules.
#ifndef GUSUKU_SUN_EVIDENCE_INTERFACE_H
#define GUSUKU_SUN_EVIDENCE_INTERFACE_H

#include "colour_match_interface.h"  // GroundMatchCellGpu, GroundMatchFrame: the ground kernel's view and cells

#define SUN_EVIDENCE_BINS 64  // also the reduce's workgroup size
#define SUN_EVIDENCE_LOWEST_LOG2_RATIO -6.0
#define SUN_EVIDENCE_LOG2_RATIO_SPAN 12.0
#define SUN_EVIDENCE_LOWEST_STRENGTH -0.5
#define SUN_EVIDENCE_STRENGTH_SPAN 3.2
#define SUN_EVIDENCE_WINDOW_BINS 2u
#define SUN_EVIDENCE_MIN_SUN_SHARE 0.25
#define SUN_EVIDENCE_SHADOWED_VISIBILITY 0.02
#define SUN_EVIDENCE_LIT_VISIBILITY 0.98
#define SUN_EVIDENCE_MIN_SAMPLES 32u
#define SUN_EVIDENCE_FULL_SAMPLES 256u
#define SUN_EVIDENCE_OUT_STRENGTH 0.15
#define SUN_EVIDENCE_MIN_WIDTH 0.03
#define SUN_EVIDENCE_STEP_TOLERANCE_M 0.1
#define SUN_EVIDENCE_MAX_CROSSINGS 128u
#define SUN_EVIDENCE_MIN_RESPONSE_SPREAD_LOG2 0.4
#define SUN_EVIDENCE_MIN_RESPONSE_GAMMA 0.5
#define SUN_EVIDENCE_MAX_RESPONSE_GAMMA 2.0

// SunEvidenceSampleGpu::kind (gusuku::SunEvidenceSampleKind)
#define SUN_EVIDENCE_KIND_NONE 0.0
#define SUN_EVIDENCE_KIND_SHADOWED 1.0
#define SUN_EVIDENCE_KIND_LIT 2.0
// Written by the ground kernel for a sample whose cell faces the sun inside the site map's window: the site map is
// drawn after the ground kernel has run, so the reduce looks it up (site_coordinates) and writes SHADOWED, LIT or NONE.
#define SUN_EVIDENCE_KIND_SITE_LOOKUP 3.0

#ifdef __cplusplus
namespace gusuku::shader_interface {
#endif

// One sample of the ground grid (sample j samples_x + i), written by colour_statistics_ground.comp (kind SITE_LOOKUP
// then resolved in place by sun_evidence_reduce.comp).
struct SunEvidenceSampleGpu {
    float log2_ratio;  // log2(Y observed / Y predicted without the sun)
    float sun_share;   // q = Y(rho E_sun cos) / Y(rho E_without) with the clear sun
    float kind;        // SUN_EVIDENCE_KIND_*
    float log2_predicted;  // x = log2 Y predicted without the sun: the response's fit
    vec3 site_coordinates;  // kind SITE_LOOKUP: the cell centre's site-map uv and biased depth (the compare's)
    float sample_reserved0;
};

// What the ground kernel needs beyond its GroundMatchFrame to classify its samples, at the head of the sun-evidence
// buffer (written in the command buffer by ColourStatisticsPass::recordGround; measure 0 on the frames without).
struct SunEvidenceGroundFrame {
    mat4 enu_to_shadow_clip;    // the site map's projection (FrameUniforms's)
    vec3 clear_sun_irradiance;  // the bake's clear-sky E_sun (sun_scale 1): the share q is against it
    float shadow_depth_bias;    // the site lookup's bias (FrameUniforms's), slope-scaled as the ground pass does
    uint measure;               // 1: classify this frame's samples
    uint sun_up;                // 1: the sun is above the horizon (else every sample is none)
    float ground_top_m;         // the highest ground cell's height: a ray above it meets no step
    uint frame_reserved0;
};

// One frame's reading, written by sun_evidence_reduce.comp into its frame slot's entry (host-visible).
struct SunEvidenceResult {
    float sun_out_probability;
    float confidence;
    float sun_strength;       // s where the sun is out (p >= 0.5), else -1
    uint cue;                 // gusuku::SunEvidenceCue
    uint shadowed_samples;
    uint lit_samples;
    float shade_log2_ratio;   // log2 g (0 with too few samples)
    float strength;           // the median s (0 with too few samples)
    float strength_standard_error;
    uint frame_serial;        // the host's number of the frame measured (SunEvidenceReducePushConstants)
    float response_gamma;     // the camera response's power fitted on the shade (1: none)
    uint result_reserved1;
};

#ifdef __cplusplus
}  // namespace gusuku::shader_interface
#endif

// colour_statistics_ground.comp's one more binding (ColourStatisticsPass: GROUND_MATCH_BINDING_COUNT + 1 in all):
// SunEvidenceGroundFrame, then SunEvidenceSampleGpu[samples_x * samples_y] (at SUN_EVIDENCE_SAMPLES_OFFSET bytes).
#define GROUND_MATCH_SUN_EVIDENCE_BINDING 5
#define SUN_EVIDENCE_SAMPLES_OFFSET 96

// sun_evidence_reduce.comp, set 0 (one workgroup of SUN_EVIDENCE_BINS)
#define SUN_EVIDENCE_REDUCE_SAMPLE_BINDING 0       // the ground kernel's sun-evidence buffer (frame, then samples)
#define SUN_EVIDENCE_REDUCE_RESULT_BINDING 1       // SunEvidenceResult[frames in flight]
#define SUN_EVIDENCE_REDUCE_SITE_SHADOW_BINDING 2  // the site's shadow map (sampler2DShadow, bilinear compare)
#define SUN_EVIDENCE_REDUCE_BINDING_COUNT 3

#if defined(__cplusplus) || defined(SUN_EVIDENCE_REDUCE_KERNEL)
GUSUKU_PUSH_CONSTANTS_BEGIN(SunEvidenceReducePushConstants)
    uint sample_count;
    uint result_index;  // the frame slot's entry
    uint frame_serial;
    uint reduce_reserved0;
GUSUKU_PUSH_CONSTANTS_END(SunEvidenceReducePushConstants, pc)
#endif

#endif

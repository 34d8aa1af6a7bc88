// The sun-evidence estimator's GPU layout (issue 41 items 1 and 2), written once for the GLSL
// (shaders/runtime/sun_evidence.comp, sun_evidence_reduce.comp) and for C++ (engine/src/runtime/sun_evidence_pass.cpp,
// which pins every offset with static_assert). The CPU reference and the choices: gusuku/maths/sun_evidence.h, whose
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

#ifdef __cplusplus
namespace gusuku::shader_interface {
#endif

// One sample of the ground grid (sample j samples_x + i), written by sun_evidence.comp.
struct SunEvidenceSampleGpu {
    float log2_ratio;  // log2(Y observed / Y predicted without the sun)
    float sun_share;   // q = Y(rho E_sun cos) / Y(rho E_without) with the clear sun
    float kind;        // SUN_EVIDENCE_KIND_*
    float log2_predicted;  // x = log2 Y predicted without the sun: the response's fit
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
    uint frame_serial;        // the host's number of the frame measured (SunEvidencePushConstants)
    float response_gamma;     // the camera response's power fitted on the shade (1: none)
    uint result_reserved1;
};

#ifdef __cplusplus
}  // namespace gusuku::shader_interface
#endif

// sun_evidence.comp, set 0 (workgroups: COLOUR_STATISTICS_TILE squared, over the ground match's sample grid)
#define SUN_EVIDENCE_CAMERA_BINDING 0       // uint per pixel: the camera pack's buffer
#define SUN_EVIDENCE_SAMPLE_BINDING 1       // SunEvidenceSampleGpu[samples_x * samples_y]
#define SUN_EVIDENCE_CELL_BINDING 2         // GroundMatchCellGpu[cells]
#define SUN_EVIDENCE_IRRADIANCE_BINDING 3   // vec4[slots * cells]: E_without
#define SUN_EVIDENCE_FRAME_BINDING 4        // GroundMatchFrame: the view, sun_irradiance the clear sun's
#define SUN_EVIDENCE_SITE_SHADOW_BINDING 5  // the site's shadow map (sampler2DShadow, bilinear compare)
#define SUN_EVIDENCE_BINDING_COUNT 6

#if defined(__cplusplus) || defined(SUN_EVIDENCE_KERNEL)
GUSUKU_PUSH_CONSTANTS_BEGIN(SunEvidencePushConstants)
    mat4 enu_to_shadow_clip;   // the site map's projection (FrameUniforms's)
    uint frame_width;          // pixels
    uint stride;               // the ground grid's sample stride
    uint first_sample_offset;  // stride / 2
    uint samples_x;
    uint samples_y;
    float shadow_depth_bias;   // the site lookup's bias (FrameUniforms's), slope-scaled as the ground pass does
    uint sun_up;               // 1: the sun is above the horizon (else every sample is none)
    float ground_top_m;        // the highest ground cell's height: a ray above it meets no step
GUSUKU_PUSH_CONSTANTS_END(SunEvidencePushConstants, pc)
#endif

// sun_evidence_reduce.comp, set 0 (one workgroup of SUN_EVIDENCE_BINS)
#define SUN_EVIDENCE_REDUCE_SAMPLE_BINDING 0  // SunEvidenceSampleGpu[sample_count]
#define SUN_EVIDENCE_REDUCE_RESULT_BINDING 1  // SunEvidenceResult[frames in flight]
#define SUN_EVIDENCE_REDUCE_BINDING_COUNT 2

#if defined(__cplusplus) || defined(SUN_EVIDENCE_REDUCE_KERNEL)
GUSUKU_PUSH_CONSTANTS_BEGIN(SunEvidenceReducePushConstants)
    uint sample_count;
    uint result_index;  // the frame slot's entry
    uint frame_serial;
    uint reduce_reserved0;
GUSUKU_PUSH_CONSTANTS_END(SunEvidenceReducePushConstants, pc)
#endif

#endif

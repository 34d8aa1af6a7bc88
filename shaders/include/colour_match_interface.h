// The colour match's GPU state and the two statistics kernels' bindings and push constants, written once for
// the GLSL (shaders/runtime/colour_statistics.comp, colour_statistics_reduce.comp, include/colour_match.glsl)
// and for C++ (engine/src/runtime/colour_statistics_pass.cpp, engine/include/gusuku/maths/colour_match.h). See
// interface_types.h for the rules; the C++ side pins every offset with static_assert (colour_match.h).
//
// The state lives in one small storage buffer that the runtime keeps for its life:
//   - the first 48 bytes (source statistics, mode, gain limit) are written by the host side each frame through
//     vkCmdUpdateBuffer (ColourStatisticsPass::recordSourceUpdate), in the frame's command buffer;
//   - the rest (the camera's smoothed statistics and the last frame's raw ones) is written only by
//     colour_statistics_reduce.comp, and read by the building's fragment shader of the next frame.
#ifndef GUSUKU_COLOUR_MATCH_INTERFACE_H
#define GUSUKU_COLOUR_MATCH_INTERFACE_H

#include "interface_types.h"

// ColourMatchState::mode (gusuku::ColourMatch kOff, kReinhard, kPreserve in that order)
#define COLOUR_MATCH_MODE_OFF 0u
#define COLOUR_MATCH_MODE_PAPER 1u
#define COLOUR_MATCH_MODE_PRESERVE 2u
#define COLOUR_MATCH_MODE_GROUND 3u

// The transfer's constants, for colour_match.glsl and the runtime's C++; the CPU reference's public
// kColourMatch* (gusuku/maths/colour_match.h, where the choices are explained) are held equal to these by
// static_assert in colour_statistics_pass.cpp.
#define COLOUR_MATCH_MAX_WHITE_BALANCE_SHIFT 15.0  // Lab units: preserve's longest shift of the a, b means
#define COLOUR_MATCH_GAMUT_STEPS 12                // bisection steps of preserve's gamut mapping
#define COLOUR_MATCH_MAX_LINEAR 65504.0            // linear input is clamped to [0, this] before the transfer
#define COLOUR_MATCH_GAMUT_TOLERANCE 1e-5          // linear RGB this far outside [0, 1] still counts as inside

#ifdef __cplusplus
namespace gusuku::shader_interface {
#endif

struct ColourMatchState {
    // ---- written by the host side (bytes 0..47) ----
    vec4 source_lab_mean;   // xyz: mu of the baked appearance (slot statistics blended by the slot weights)
    vec4 source_lab_sigma;  // xyz: sigma of the same
    uint mode;              // COLOUR_MATCH_MODE_*
    float gain_limit;       // g: the transfer's sigma ratio is clamped to [1/g, g]
    uint host_reserved0;
    uint host_reserved1;
    // ---- written by colour_statistics_reduce.comp (bytes 48..143) ----
    vec4 camera_lab_mean;      // xyz: smoothed mu of the camera frame's valid samples
    vec4 camera_lab_variance;  // xyz: smoothed sigma^2 of the same (sigma = sqrt)
    vec4 frame_lab_mean;       // xyz: this frame's mu (valid samples), whether or not it was accepted
    vec4 frame_lab_sigma;      // xyz: this frame's sigma
    uint camera_valid;         // 1 once a frame was accepted since construction or reset; 0: no target yet
    uint frames_accepted;      // frames folded into the smoothed statistics since construction or reset
    uint frame_valid_samples;  // this frame: samples neither clipped nor black
    uint frame_clipped_samples;  // this frame: samples with a channel at 255 or all channels at 0
    uint frame_total_samples;    // this frame: samples taken (valid + clipped)
    uint frame_accepted;         // 1 when this frame had enough valid samples to update the smoothed statistics
    uint gpu_reserved0;
    uint gpu_reserved1;
    // ---- written by colour_statistics_ground_reduce.comp (bytes 144..239), mode GROUND ----
    vec4 ground_gain;             // xyz: smoothed von Kries gain (observed / predicted), valid when ground_valid
    vec3 frame_ground_gain;       // this frame's clamped gain (1 when not accepted)
    float frame_ground_median_bin;  // this frame's median log-ratio bin (-1 none)
    vec4 frame_ground_observed;   // xyz: sum of observed linear RGB over the kept samples
    vec4 frame_ground_predicted;  // xyz: sum of predicted linear RGB over the same
    uint ground_valid;            // 1 once a frame was accepted since construction or reset
    uint ground_frames_accepted;
    uint frame_ground_samples;    // this frame: samples on the ground in the bins
    uint frame_ground_kept;       // this frame: samples in the window about the median
    uint frame_ground_clipped;    // this frame: samples on the ground left out as clipped
    uint frame_ground_accepted;   // 1 when this frame updated the smoothed gain
    uint ground_reserved0;
    uint ground_reserved1;
};

// One sample of the ground kernel's grid, written by colour_statistics_ground.comp (sample j samples_x + i) and
// read by colour_statistics_ground_reduce.comp.
struct GroundMatchSample {
    vec3 observed;   // observed linear RGB
    float bin;       // log-ratio bin, -1 when the sample is not counted
    vec3 predicted;  // predicted linear RGB
    float clipped;   // 1 when a ground sample was left out as clipped, else 0
};

// One ground-grid cell (texel order), uploaded once.
struct GroundMatchCellGpu {
    vec3 albedo;     // linear albedo
    float ground;    // 1: ground with albedo, 0: none
    vec3 normal;     // unit normal (ENU)
    float height_m;  // ENU z
};

// The frame's camera and light for the ground kernel, written by the host before each submission. Each vec3 is
// followed by the scalar that fills its last 4 bytes (interface_types.h's rules).
struct GroundMatchFrame {
    vec3 ray_x;                   // ENU direction of the ray through pixel point (u, v): u ray_x + v ray_y + ray_z
    float first_plane_height_m;   // the height (ENU z) of the first plane a ray meets: the mean ground height
    vec3 ray_y;
    uint sun_shines;              // 1 when the sun shines this frame, else 0
    vec3 ray_z;
    float exposure;               // linear radiance times this is the display value (FrameInput::exposure)
    vec3 camera_position;         // ENU metres
    float ground_origin_east_m;   // the ground grid's south-west corner (ENU m)
    vec3 sun_direction;           // unit towards the sun (ENU)
    float ground_origin_north_m;
    vec3 sun_irradiance;          // E_sun after cloud cover (bake set units)
    float ground_cell_m;          // the ground grid's cell size (m)
    vec3 slot_weights;            // blend weights (0 for a missing slot)
    uint slot_count;              // slots with irradiance in GROUND_MATCH_IRRADIANCE_BINDING
    uint slot_index0;             // slot per blend term (0 when its weight is 0)
    uint slot_index1;
    uint slot_index2;
    uint cell_count;              // columns x rows
    uint columns;
    uint rows;
    uint size_padding0;           // std430 rounds the struct's size up to 16 bytes (its vec3s' alignment):
    uint size_padding1;           //   these two make the C++ struct that size too
};

// One subgroup's share of a frame, written by colour_statistics.comp and read by colour_statistics_reduce.comp:
// the valid samples' count, mean and sum of squared deviations from that mean (M2), so that partials combine
// without the cancellation of sum(x^2) - n mean^2 (Chan, Golub and LeVeque's pairwise update).
struct ColourStatisticsPartial {
    vec3 lab_mean;           // mean of the valid samples (0 when none)
    float valid_count;       // the valid samples
    vec3 lab_m2;             // sum of squared deviations from the mean
    float clipped_count;     // the clipped samples
};

#ifdef __cplusplus
}  // namespace gusuku::shader_interface
#endif

// colour_statistics.comp, set 0
#define COLOUR_STATISTICS_CAMERA_BINDING 0   // uint per pixel: packed RGBA8, R in the low byte, sRGB, row 0 top
#define COLOUR_STATISTICS_PARTIAL_BINDING 1  // ColourStatisticsPartial per (workgroup, subgroup)
#define COLOUR_STATISTICS_BINDING_COUNT 2

// colour_statistics.comp: one invocation per sampled pixel, an 8 x 8 tile of the sample grid per workgroup.
#define COLOUR_STATISTICS_TILE 8

// A GLSL stage may declare one push-constant block: each kernel defines its COLOUR_*_KERNEL before including
// this header and gets its own block; other GLSL (the building's shader) gets none. C++ gets both.
#if defined(__cplusplus) || defined(COLOUR_STATISTICS_KERNEL) || defined(GROUND_MATCH_KERNEL)
GUSUKU_PUSH_CONSTANTS_BEGIN(ColourStatisticsPushConstants)
    uint frame_width;            // pixels
    uint frame_height;
    uint stride;                 // sample every stride-th pixel in x and y
    uint first_sample_offset;    // the first sample is pixel (offset, offset): stride / 2, the middle of its cell
    uint samples_x;              // sampled columns: pixels offset + i * stride, i < samples_x
    uint samples_y;              // sampled rows
    uint workgroups_x;           // ceil(samples_x / COLOUR_STATISTICS_TILE)
    uint partials_per_workgroup;  // subgroups per workgroup: the partial of subgroup s of workgroup w is
                                  // w * partials_per_workgroup + s
GUSUKU_PUSH_CONSTANTS_END(ColourStatisticsPushConstants, pc)
#endif

// colour_statistics_ground.comp, set 0 (push constants: ColourStatisticsPushConstants; workgroups: the tile)
#define GROUND_MATCH_CAMERA_BINDING 0      // as COLOUR_STATISTICS_CAMERA_BINDING
#define GROUND_MATCH_PARTIAL_BINDING 1     // GroundMatchSample[samples_x * samples_y]
#define GROUND_MATCH_CELL_BINDING 2        // GroundMatchCellGpu[cells]
#define GROUND_MATCH_IRRADIANCE_BINDING 3  // vec4[slots * cells]: rgb E_without of slot s, cell c at s * cells + c
#define GROUND_MATCH_FRAME_BINDING 4       // GroundMatchFrame
#define GROUND_MATCH_BINDING_COUNT 5
// Log-ratio bins (colour_match.h: kGroundMatchBins); also the reduce's workgroup size.
#define GROUND_MATCH_BINS 64
#define GROUND_MATCH_BINS_PER_STOP 8.0
#define GROUND_MATCH_LOWEST_LOG2_RATIO -4.0
#define GROUND_MATCH_WINDOW_BINS 4
#define GROUND_MATCH_HEIGHT_ITERATIONS 4
#define GROUND_MATCH_MIN_PREDICTED 1e-6

// colour_statistics_ground_reduce.comp, set 0 (one workgroup of GROUND_MATCH_BINS; push constants:
// ColourReducePushConstants with partial_count = the first kernel's samples)
#define GROUND_REDUCE_PARTIAL_BINDING 0
#define GROUND_REDUCE_STATE_BINDING 1
#define GROUND_REDUCE_BINDING_COUNT 2

// colour_statistics_reduce.comp, set 0 (one workgroup)
#define COLOUR_REDUCE_PARTIAL_BINDING 0  // ColourStatisticsPartial[partial_count]
#define COLOUR_REDUCE_STATE_BINDING 1    // ColourMatchState
#define COLOUR_REDUCE_BINDING_COUNT 2
#define COLOUR_REDUCE_WORKGROUP_SIZE 64

#if defined(__cplusplus) || defined(COLOUR_REDUCE_KERNEL) || defined(GROUND_REDUCE_KERNEL)
GUSUKU_PUSH_CONSTANTS_BEGIN(ColourReducePushConstants)
    uint partial_count;
    uint min_valid_samples;  // fewer valid samples than this: the frame is not accepted (state kept)
    float smoothing_weight;  // alpha of the moving average: new = old + alpha (frame - old), in (0, 1]
    uint reset;              // 1: forget the smoothed statistics; this frame, if accepted, becomes them
GUSUKU_PUSH_CONSTANTS_END(ColourReducePushConstants, pc)
#endif

#endif

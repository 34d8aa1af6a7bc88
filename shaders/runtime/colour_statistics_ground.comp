#version 450
// The ground colour match's first pass (mode GROUND; choices and the CPU reference in
// engine/include/gusuku/maths/colour_match.h). One invocation per sampled pixel: its ray is followed onto the ground
// grid's height field, the cell's predicted radiance (exposure albedo / pi (E_without blended + E_sun cos)) is set
// against the camera's sRGB-decoded pixel, and the sample is written with its log2 luminance-ratio bin (-1 when
// it does not count). No shared memory, no barrier, no subgroup operation: llvmpipe runs a barrier as a switch
// between invocations, so a per-workgroup histogram costs many times the Lab statistics;
// colour_statistics_ground_reduce.comp bins the samples in one pass. On the frames the sun-evidence estimator measures
// (sun_frame.measure), each invocation also writes the estimator's sample from the same ray and pixel
// (sun_evidence_ground.glsl), which sun_evidence_reduce.comp reads after the frame's site map is drawn.
#extension GL_GOOGLE_include_directive : require

#define GROUND_MATCH_KERNEL
#include "sun_evidence_interface.h"  // and colour_match_interface.h
#include "colour.glsl"

layout(local_size_x = COLOUR_STATISTICS_TILE, local_size_y = COLOUR_STATISTICS_TILE) in;

layout(std430, set = 0, binding = GROUND_MATCH_CAMERA_BINDING) readonly buffer CameraPixels { uint camera_rgba8[]; };
layout(std430, set = 0, binding = GROUND_MATCH_PARTIAL_BINDING) writeonly buffer Samples {
    GroundMatchSample samples[];
};
layout(std430, set = 0, binding = GROUND_MATCH_CELL_BINDING) readonly buffer Cells { GroundMatchCellGpu cells[]; };
layout(std430, set = 0, binding = GROUND_MATCH_IRRADIANCE_BINDING) readonly buffer Irradiance { vec4 without[]; };
layout(std430, set = 0, binding = GROUND_MATCH_FRAME_BINDING) readonly buffer Frame { GroundMatchFrame view; };
layout(std430, set = 0, binding = GROUND_MATCH_SUN_EVIDENCE_BINDING) buffer SunEvidence {
    readonly SunEvidenceGroundFrame sun_frame;
    writeonly SunEvidenceSampleGpu sun_samples[];
};

float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }

// The cell whose square holds p (column 0 west, row 0 north), or -1 outside the grid.
int cellAt(vec2 p) {
    vec2 origin = vec2(view.ground_origin_east_m, view.ground_origin_north_m);
    vec2 index = floor((p - origin) / view.ground_cell_m);
    if (!(index.x >= 0.0 && index.x < float(view.columns) && index.y >= 0.0 && index.y < float(view.rows))) return -1;
    int row = int(view.rows) - 1 - int(index.y);
    return row * int(view.columns) + int(index.x);
}

// The ground cell under pixel centre `pixel`, or -1 (colour_match.h: groundMatchCellOfPixel).
int groundCellOfPixel(uvec2 pixel) {
    vec2 point = vec2(pixel) + 0.5;
    vec3 direction = point.x * view.ray_x + point.y * view.ray_y + view.ray_z;
    vec3 origin = view.camera_position;
    if (!(direction.z < -1e-6)) return -1;
    float height = view.first_plane_height_m;
    int cell = -1;
    int previous = -1;
    for (int step = 0; step <= GROUND_MATCH_HEIGHT_ITERATIONS; ++step) {
        float t = (height - origin.z) / direction.z;
        if (!(t > 0.0)) return -1;
        previous = cell;
        cell = cellAt(origin.xy + t * direction.xy);
        if (cell < 0 || cells[cell].ground < 0.5) return -1;
        // Settled: the next step would start from this same cell's height, so every later step repeats it.
        if (cell == previous) return cell;
        height = cells[cell].height_m;
    }
    return -1;  // not settled on one cell
}

vec3 slotWithout(uint slot, float weight, int cell) {
    if (!(weight > 0.0) || slot >= view.slot_count) return vec3(0.0);
    return weight * without[slot * view.cell_count + uint(cell)].rgb;
}

vec3 predictedRadiance(int cell) {
    vec3 irradiance = slotWithout(view.slot_index0, view.slot_weights.x, cell) +
                      slotWithout(view.slot_index1, view.slot_weights.y, cell) +
                      slotWithout(view.slot_index2, view.slot_weights.z, cell);
    if (view.sun_shines != 0u)
        irradiance += view.sun_irradiance *
                      max(0.0, dot(cells[cell].normal, view.sun_direction));
    return view.exposure * cells[cell].albedo / kPi * irradiance;
}

#include "sun_evidence_ground.glsl"

void main() {
    uvec2 sample_index = gl_GlobalInvocationID.xy;
    if (sample_index.x >= pc.samples_x || sample_index.y >= pc.samples_y) return;
    float bin = -1.0;
    vec3 observed = vec3(0.0);
    vec3 predicted = vec3(0.0);
    float clipped = 0.0;
    uvec2 pixel = uvec2(pc.first_sample_offset) + sample_index * pc.stride;
    int cell = groundCellOfPixel(pixel);
    uint word = 0u;
    if (cell >= 0) {
        word = camera_rgba8[pixel.y * pc.frame_width + pixel.x];
        uvec3 bytes = uvec3(word & 0xFFu, (word >> 8u) & 0xFFu, (word >> 16u) & 0xFFu);
        if (any(equal(bytes, uvec3(255u))) || all(equal(bytes, uvec3(0u)))) {
            clipped = 1.0;
        } else {
            predicted = predictedRadiance(cell);
            if (luminance(predicted) >= GROUND_MATCH_MIN_PREDICTED) {
                observed = srgbDecode(vec3(bytes) / 255.0);
                float ratio = log2(luminance(observed) / luminance(predicted));
                float index = floor((ratio - GROUND_MATCH_LOWEST_LOG2_RATIO) * GROUND_MATCH_BINS_PER_STOP);
                bin = clamp(index, 0.0, float(GROUND_MATCH_BINS - 1));
            }
        }
    }
    uint index = sample_index.y * pc.samples_x + sample_index.x;
    // Member by member (see colour_statistics.comp: synchronization validation follows single access chains).
    samples[index].observed = observed;
    samples[index].bin = bin;
    samples[index].predicted = predicted;
    samples[index].clipped = clipped;
    if (sun_frame.measure != 0u) writeSunEvidenceSample(index, pixel, cell, word);
}

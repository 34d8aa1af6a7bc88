#version 450
// The sun-evidence estimator's first pass (issue 41 items 1 and 2; the CPU reference and the choices in
// engine/include/gusuku/maths/sun_evidence.h: sunEvidenceSamples). One invocation per sample of the ground colour
// match's grid: its ray is followed onto the ground grid's height field (as colour_statistics_ground.comp does), and
// the sample is written with log2(Y observed / Y predicted without the sun), the cell's clear-sun share q and its
// kind: shadowed (the site's map shadows the cell's centre, or its face turns from the sun), lit, or none (no
// ground, clipped, penumbra, no light, or a ray that meets the side of a step, a wall, before its cell). No shared
// memory, no barrier (llvmpipe runs a barrier as a switch between invocations); sun_evidence_reduce.comp takes the
// medians.
#extension GL_GOOGLE_include_directive : require

#define SUN_EVIDENCE_KERNEL
#include "sun_evidence_interface.h"
#include "colour.glsl"

layout(local_size_x = COLOUR_STATISTICS_TILE, local_size_y = COLOUR_STATISTICS_TILE) in;

layout(std430, set = 0, binding = SUN_EVIDENCE_CAMERA_BINDING) readonly buffer CameraPixels { uint camera_rgba8[]; };
layout(std430, set = 0, binding = SUN_EVIDENCE_SAMPLE_BINDING) writeonly buffer Samples {
    SunEvidenceSampleGpu samples[];
};
layout(std430, set = 0, binding = SUN_EVIDENCE_CELL_BINDING) readonly buffer Cells { GroundMatchCellGpu cells[]; };
layout(std430, set = 0, binding = SUN_EVIDENCE_IRRADIANCE_BINDING) readonly buffer Irradiance { vec4 without[]; };
layout(std430, set = 0, binding = SUN_EVIDENCE_FRAME_BINDING) readonly buffer Frame { GroundMatchFrame view; };
layout(set = 0, binding = SUN_EVIDENCE_SITE_SHADOW_BINDING) uniform sampler2DShadow site_shadow;

// runtime_shadow_coordinates.glsl's bounds on the slope-scaled bias (the ground pass's site lookup).
const float kShadowMinCosine = 0.05;
const float kShadowMaxBiasTangent = 10.0;

float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }

// The cell whose square holds p (column 0 west, row 0 north), or -1 outside the grid.
int cellAt(vec2 p) {
    vec2 origin = vec2(view.ground_origin_east_m, view.ground_origin_north_m);
    vec2 index = floor((p - origin) / view.ground_cell_m);
    if (!(index.x >= 0.0 && index.x < float(view.columns) && index.y >= 0.0 && index.y < float(view.rows))) return -1;
    int row = int(view.rows) - 1 - int(index.y);
    return row * int(view.columns) + int(index.x);
}

// The ground cell under pixel centre `pixel`, or -1 (colour_match.h: groundMatchCellOfPixel; the same march as
// colour_statistics_ground.comp's).
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
        if (cell == previous) return cell;
        height = cells[cell].height_m;
    }
    return -1;
}

// A cell's height by column and row from the south, or a depth that never blocks where there is no ground.
float columnHeight(int column, int row_from_south) {
    if (column < 0 || column >= int(view.columns) || row_from_south < 0 || row_from_south >= int(view.rows))
        return -1e30;
    int cell = (int(view.rows) - 1 - row_from_south) * int(view.columns) + column;
    return cells[cell].ground < 0.5 ? -1e30 : cells[cell].height_m;
}

// Whether the ray comes down onto `cell` from above rather than through the side of a step (a wall) before it
// (sunEvidenceRayReachesCell): walking back towards the camera over the cell edges, the ray at each edge is no more
// than SUN_EVIDENCE_STEP_TOLERANCE_M below either neighbouring cell's height; it ends once the ray is above the
// highest ground cell.
bool rayReachesCell(vec3 origin, vec3 direction, int cell) {
    float t_hit = (cells[cell].height_m - origin.z) / direction.z;
    vec2 hit = (origin.xy + t_hit * direction.xy - vec2(view.ground_origin_east_m, view.ground_origin_north_m)) /
               view.ground_cell_m;
    vec2 back = -direction.xy / view.ground_cell_m;
    int row = cell / int(view.columns);
    int column = cell - row * int(view.columns);
    int row_from_south = int(view.rows) - 1 - row;
    int step_column = back.x > 0.0 ? 1 : -1;
    int step_row = back.y > 0.0 ? 1 : -1;
    const float kInfinity = 1e30;
    float next_x = back.x != 0.0 ? (float(column + (back.x > 0.0 ? 1 : 0)) - hit.x) / back.x : kInfinity;
    float next_y = back.y != 0.0 ? (float(row_from_south + (back.y > 0.0 ? 1 : 0)) - hit.y) / back.y : kInfinity;
    float delta_x = back.x != 0.0 ? 1.0 / abs(back.x) : kInfinity;
    float delta_y = back.y != 0.0 ? 1.0 / abs(back.y) : kInfinity;
    for (uint crossing = 0u; crossing < SUN_EVIDENCE_MAX_CROSSINGS; ++crossing) {
        float s = min(next_x, next_y);
        if (!(s < t_hit)) return true;
        float ray_height = origin.z + (t_hit - s) * direction.z;
        if (pc.ground_top_m <= ray_height + SUN_EVIDENCE_STEP_TOLERANCE_M) return true;  // above every step from here
        float left = columnHeight(column, row_from_south);
        if (next_x < next_y) {
            column += step_column;
            next_x += delta_x;
        } else {
            row_from_south += step_row;
            next_y += delta_y;
        }
        float entered = columnHeight(column, row_from_south);
        if (max(left, entered) > ray_height + SUN_EVIDENCE_STEP_TOLERANCE_M) return false;
    }
    return true;
}

vec3 slotWithout(uint slot, float weight, int cell) {
    if (!(weight > 0.0) || slot >= view.slot_count) return vec3(0.0);
    return weight * without[slot * view.cell_count + uint(cell)].rgb;
}

// The site map's visibility (bilinear compare) at the cell's centre; 1 outside the map's window.
float siteVisibility(int cell, float cosine) {
    uint row = uint(cell) / view.columns;
    uint column = uint(cell) - row * view.columns;
    vec2 centre = vec2(view.ground_origin_east_m, view.ground_origin_north_m) +
                  (vec2(float(column), float(view.rows - 1u - row)) + 0.5) * view.ground_cell_m;
    vec4 clip = pc.enu_to_shadow_clip * vec4(centre, cells[cell].height_m, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    float held = clamp(cosine, kShadowMinCosine, 1.0);
    float tangent = sqrt(1.0 - held * held) / held;
    float depth = clip.z - pc.shadow_depth_bias * (1.0 + min(tangent, kShadowMaxBiasTangent));
    return texture(site_shadow, vec3(uv, depth));
}

void main() {
    uvec2 sample_index = gl_GlobalInvocationID.xy;
    if (sample_index.x >= pc.samples_x || sample_index.y >= pc.samples_y) return;
    float kind = SUN_EVIDENCE_KIND_NONE;
    float ratio = 0.0;
    float share = 0.0;
    float log2_predicted = 0.0;
    uvec2 pixel = uvec2(pc.first_sample_offset) + sample_index * pc.stride;
    int cell = pc.sun_up != 0u ? groundCellOfPixel(pixel) : -1;
    // A ray that meets the side of a step before its cell shows a wall, not the cell's ground: left out.
    if (cell >= 0) {
        vec2 point = vec2(pixel) + 0.5;
        vec3 direction = point.x * view.ray_x + point.y * view.ray_y + view.ray_z;
        if (!rayReachesCell(view.camera_position, direction, cell)) cell = -1;
    }
    if (cell >= 0) {
        uint word = camera_rgba8[pixel.y * pc.frame_width + pixel.x];
        uvec3 bytes = uvec3(word & 0xFFu, (word >> 8u) & 0xFFu, (word >> 16u) & 0xFFu);
        bool clipped = any(equal(bytes, uvec3(255u))) || all(equal(bytes, uvec3(0u)));
        vec3 irradiance = slotWithout(view.slot_index0, view.slot_weights.x, cell) +
                          slotWithout(view.slot_index1, view.slot_weights.y, cell) +
                          slotWithout(view.slot_index2, view.slot_weights.z, cell);
        vec3 albedo = cells[cell].albedo;
        float predicted = luminance(view.exposure * albedo / kPi * irradiance);
        if (!clipped && predicted >= GROUND_MATCH_MIN_PREDICTED) {
            vec3 observed = srgbDecode(vec3(bytes) / 255.0);
            float cosine = dot(cells[cell].normal, view.sun_direction);
            ratio = log2(luminance(observed) / predicted);
            log2_predicted = log2(predicted);
            share = luminance(albedo * view.sun_irradiance) * max(0.0, cosine) * view.exposure / kPi / predicted;
            if (cosine <= 0.0) {
                kind = SUN_EVIDENCE_KIND_SHADOWED;
            } else {
                float visibility = siteVisibility(cell, cosine);
                if (visibility <= SUN_EVIDENCE_SHADOWED_VISIBILITY) kind = SUN_EVIDENCE_KIND_SHADOWED;
                else if (visibility >= SUN_EVIDENCE_LIT_VISIBILITY) kind = SUN_EVIDENCE_KIND_LIT;
            }
        }
    }
    uint index = sample_index.y * pc.samples_x + sample_index.x;
    samples[index].log2_ratio = ratio;
    samples[index].sun_share = share;
    samples[index].kind = kind;
    samples[index].log2_predicted = log2_predicted;
}

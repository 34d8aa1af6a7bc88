// The sun-evidence estimator's per-sample step (issue 41 items 1 and 2; the CPU reference and the choices in
// engine/include/gusuku/maths/sun_evidence.h: sunEvidenceSamples), run by colour_statistics_ground.comp on the
// frames the estimator measures: the ground match has already followed the sample's ray onto its cell and read its
// camera pixel, so the estimator reuses both (one march, one decode). The sample is written with log2(Y observed /
// Y predicted without the sun), the cell's clear-sun share q and its kind: shadowed (its face turns from the sun),
// lit (outside the site map's window), SITE_LOOKUP (the site map decides: it is drawn later in the frame, so
// sun_evidence_reduce.comp looks it up at the coordinates written here), or none (no ground, clipped, no light, or a
// ray that meets the side of a step, a wall, before its cell). The includer declares `view`, `cells`, `without`,
// `sun_frame`, `sun_samples`, cellAt, slotWithout and luminance.

// runtime_shadow_coordinates.glsl's bounds on the slope-scaled bias (the ground pass's site lookup).
const float kShadowMinCosine = 0.05;
const float kShadowMaxBiasTangent = 10.0;

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
        if (sun_frame.ground_top_m <= ray_height + SUN_EVIDENCE_STEP_TOLERANCE_M) return true;  // above every step
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

// The cell centre's site-map coordinates (uv, biased depth) for the bilinear compare, or uv outside [0, 1] beyond
// the map's window (lit there, as the ground pass reads it).
vec3 siteCoordinates(int cell, float cosine) {
    uint row = uint(cell) / view.columns;
    uint column = uint(cell) - row * view.columns;
    vec2 centre = vec2(view.ground_origin_east_m, view.ground_origin_north_m) +
                  (vec2(float(column), float(view.rows - 1u - row)) + 0.5) * view.ground_cell_m;
    vec4 clip = sun_frame.enu_to_shadow_clip * vec4(centre, cells[cell].height_m, 1.0);
    float held = clamp(cosine, kShadowMinCosine, 1.0);
    float tangent = sqrt(1.0 - held * held) / held;
    return vec3(clip.xy * 0.5 + 0.5, clip.z - sun_frame.shadow_depth_bias * (1.0 + min(tangent, kShadowMaxBiasTangent)));
}

// Sample `index` of the estimator: pixel's ray met `cell` (-1: none) and its camera word is `word`.
void writeSunEvidenceSample(uint index, uvec2 pixel, int cell, uint word) {
    float kind = SUN_EVIDENCE_KIND_NONE;
    float ratio = 0.0;
    float share = 0.0;
    float log2_predicted = 0.0;
    vec3 coordinates = vec3(0.0);
    if (sun_frame.sun_up == 0u) cell = -1;
    // A ray that meets the side of a step before its cell shows a wall, not the cell's ground: left out.
    if (cell >= 0) {
        vec2 point = vec2(pixel) + 0.5;
        vec3 direction = point.x * view.ray_x + point.y * view.ray_y + view.ray_z;
        if (!rayReachesCell(view.camera_position, direction, cell)) cell = -1;
    }
    if (cell >= 0) {
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
            share = luminance(albedo * sun_frame.clear_sun_irradiance) * max(0.0, cosine) * view.exposure / kPi /
                    predicted;
            if (cosine <= 0.0) {
                kind = SUN_EVIDENCE_KIND_SHADOWED;
            } else {
                coordinates = siteCoordinates(cell, cosine);
                bool in_window = all(greaterThanEqual(coordinates.xy, vec2(0.0))) &&
                                 all(lessThanEqual(coordinates.xy, vec2(1.0)));
                kind = in_window ? SUN_EVIDENCE_KIND_SITE_LOOKUP : SUN_EVIDENCE_KIND_LIT;  // 1 outside the window
            }
        }
    }
    // Member by member (see colour_statistics.comp: synchronization validation follows single access chains).
    sun_samples[index].log2_ratio = ratio;
    sun_samples[index].sun_share = share;
    sun_samples[index].kind = kind;
    sun_samples[index].log2_predicted = log2_predicted;
    sun_samples[index].site_coordinates = coordinates;
}

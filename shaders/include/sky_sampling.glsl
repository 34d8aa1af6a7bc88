// Sky radiance lookup and importance sampling on the GPU: the twin of sky_importance.cpp (gusuku_bake/sky_light.h
// documents the buffers' layout and the densities; keep the two in step, tests/test_sky_light.cpp holds them to
// each other through shaders/tests/sky_probe.comp).
//
// The includer defines, before including:
//   SKY_RADIANCE_BINDING  set-0 binding of SkySamplingTables::radiance_rgba (width * height vec4, row 0 zenith),
//                         a uniform texel buffer of VK_FORMAT_R32G32B32A32_SFLOAT
//   SKY_TABLE_BINDING     set-0 binding of SkySamplingTables::table (header, marginal CDF, conditional CDFs),
//                         a uniform texel buffer of VK_FORMAT_R32_SFLOAT
// and gets, for unit ENU directions (east, north, up):
//   vec3  skyRadiance(vec3 direction_enu)                       texel containing the direction, unfiltered
//   vec3  sampleSkyDirection(vec2 xi, out float pdf_solid_angle) xi in [0, 1)^2; pdf per steradian
//   float skyPdf(vec3 direction_enu)                            density of sampleSkyDirection per steradian
//   vec3  skyRadianceAndPdf(vec3 direction_enu, out float pdf)   both of the above from one texel load
//   ivec2 skyRowsFacing(vec3 normal)                            rows holding every direction above the plane
//   float skyRowsProbability(ivec2 rows)                        sampleSkyDirection's chance of those rows
//   vec3  sampleSkyDirectionInRows(vec2 xi, ivec2 rows, out float pdf)  sampleSkyDirection conditioned on them
// Equirect convention (gusuku/maths/equirect.h): azimuth = 360 u - north_azimuth_in_image_deg, v = theta / pi.
#ifndef GUSUKU_SKY_SAMPLING_GLSL
#define GUSUKU_SKY_SAMPLING_GLSL

#if !defined(SKY_RADIANCE_BINDING) || !defined(SKY_TABLE_BINDING)
#error "define SKY_RADIANCE_BINDING and SKY_TABLE_BINDING before including sky_sampling.glsl"
#endif

#include "constants.glsl"

// Both read as uniform texel buffers (views of format RGBA32F and R32F): lavapipe gathers a texel fetch's lanes
// in straight-line vector code, where a storage-buffer load at per-lane addresses (a texel per direction, a CDF
// entry per search) runs as a loop over the SIMD lanes (bvh_layout.glsl). A float view returns the stored
// floats unchanged, so every result equals the storage-buffer reads' bit for bit.
#ifdef TRACE_INPUTS_STORAGE_BUFFERS
// The storage-buffer variant (bvh_layout.glsl): the same floats.
layout(std430, set = 0, binding = SKY_RADIANCE_BINDING) readonly buffer SkyRadianceValues { vec4 sky_radiance_values[]; };
layout(std430, set = 0, binding = SKY_TABLE_BINDING) readonly buffer SkyTableValues { float sky_table_values[]; };

vec4 skyRadianceTexel(int index) { return sky_radiance_values[index]; }
float skyTable(int index) { return sky_table_values[index]; }
#else
layout(set = 0, binding = SKY_RADIANCE_BINDING) uniform samplerBuffer sky_radiance_texels;
layout(set = 0, binding = SKY_TABLE_BINDING) uniform samplerBuffer sky_table_texels;

vec4 skyRadianceTexel(int index) { return texelFetch(sky_radiance_texels, index); }
float skyTable(int index) { return texelFetch(sky_table_texels, index).x; }
#endif

const int SKY_TABLE_HEADER_FLOATS = 4;
// Largest float below 1: xi == 1 would pick the last CDF entry even when it has no mass.
const float SKY_ONE_MINUS_EPSILON = 0.99999994;
// sin theta floor: keeps the pdf finite at the poles.
const float SKY_MIN_SIN_THETA = 1e-7;

int skyWidth() { return int(skyTable(0)); }
int skyHeight() { return int(skyTable(1)); }
float skyNorthAzimuthDeg() { return skyTable(2); }
int skyMarginalOffset() { return SKY_TABLE_HEADER_FLOATS; }
int skyConditionalOffset(int row) { return SKY_TABLE_HEADER_FLOATS + skyHeight() + 1 + row * (skyWidth() + 1); }

// Guide tables (sky_light.h): the smallest power of two >= intervals, and where each guide starts.
int skyGuideCells(int intervals) { return intervals <= 1 ? 1 : 1 << (findMSB(intervals - 1) + 1); }
int skyMarginalGuideOffset() { return skyConditionalOffset(skyHeight()); }
int skyConditionalGuideOffset(int row) {
    return skyMarginalGuideOffset() + skyGuideCells(skyHeight()) + 1 + row * (skyGuideCells(skyWidth()) + 1);
}

// Largest i in [0, n-1] with cdf[offset + i] <= xi (the CDF has n + 1 entries), searched only between the
// guide's entries for xi's cell: the answer at the cell's two ends, between which it lies (it grows with xi).
// Why: a binary search over a 1024-texel row is ten dependent loads, each a loop over the SIMD lanes on
// lavapipe; the guided one is two loads and, on most of the map, no iteration at all.
int skyFindInterval(int offset, int guide_offset, int cells, float xi) {
    int cell = min(int(xi * float(cells)), cells - 1);
    int lo = int(skyTable(guide_offset + cell));
    int hi = int(skyTable(guide_offset + cell + 1));
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (skyTable(offset + mid) <= xi)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

// p(u, v) over the unit square for texel (x, y), from the CDFs alone.
float skyUnitSquareDensity(int x, int y) {
    int marginal = skyMarginalOffset();
    int conditional = skyConditionalOffset(y);
    float row_probability = skyTable(marginal + y + 1) - skyTable(marginal + y);
    float column_probability = skyTable(conditional + x + 1) - skyTable(conditional + x);
    return row_probability * float(skyHeight()) * column_probability * float(skyWidth());
}

float skySolidAnglePdf(float unit_square_density, float sin_theta) {
    return unit_square_density / (2.0 * kPi * kPi * max(sin_theta, SKY_MIN_SIN_THETA));
}

// Texel containing a direction; also returns sin theta of the direction.
ivec2 skyTexelOf(vec3 direction_enu, out float sin_theta) {
    float horizontal = length(direction_enu.xy);
    float len = length(direction_enu);
    // atan(y, x) is undefined at (0, 0): a vertical (or zero) direction reads azimuth 0 / the zenith.
    float theta = len > 0.0 ? atan(horizontal, direction_enu.z) : 0.0;
    float azimuth_rad = horizontal > 0.0 ? atan(direction_enu.x, direction_enu.y) : 0.0;
    float u = (degrees(azimuth_rad) + skyNorthAzimuthDeg()) / 360.0;
    u -= floor(u);
    float v = theta / kPi;
    sin_theta = len > 0.0 ? horizontal / len : 0.0;
    int width = skyWidth();
    int height = skyHeight();
    return ivec2(clamp(int(u * float(width)), 0, width - 1), clamp(int(v * float(height)), 0, height - 1));
}

vec3 skyRadiance(vec3 direction_enu) {
    float sin_theta;
    ivec2 texel = skyTexelOf(direction_enu, sin_theta);
    return skyRadianceTexel(texel.y * skyWidth() + texel.x).rgb;
}

// The texel's fourth float is its unit-square density, stored as skyUnitSquareDensity computes it (sky_light.h),
// so this equals (skyRadiance, skyPdf) bit for bit.
vec3 skyRadianceAndPdf(vec3 direction_enu, out float pdf_solid_angle) {
    float sin_theta;
    ivec2 texel = skyTexelOf(direction_enu, sin_theta);
    vec4 radiance_density = skyRadianceTexel(texel.y * skyWidth() + texel.x);
    pdf_solid_angle = skySolidAnglePdf(radiance_density.w, sin_theta);
    return radiance_density.rgb;
}

float skyPdf(vec3 direction_enu) {
    float sin_theta;
    ivec2 texel = skyTexelOf(direction_enu, sin_theta);
    return skySolidAnglePdf(skyUnitSquareDensity(texel.x, texel.y), sin_theta);
}

vec3 sampleSkyDirection(vec2 xi, out float pdf_solid_angle) {
    xi = clamp(xi, vec2(0.0), vec2(SKY_ONE_MINUS_EPSILON));
    int width = skyWidth();
    int height = skyHeight();
    int marginal = skyMarginalOffset();
    int y = skyFindInterval(marginal, skyMarginalGuideOffset(), skyGuideCells(height), xi.x);
    int conditional = skyConditionalOffset(y);
    int x = skyFindInterval(conditional, skyConditionalGuideOffset(y), skyGuideCells(width), xi.y);

    float row_low = skyTable(marginal + y);
    float row_high = skyTable(marginal + y + 1);
    float column_low = skyTable(conditional + x);
    float row_fraction = (xi.x - row_low) / (row_high - row_low);
    float column_fraction = (xi.y - column_low) / (skyTable(conditional + x + 1) - column_low);
    float u = (float(x) + column_fraction) / float(width);
    float v = (float(y) + row_fraction) / float(height);

    // sin theta from the distance to the nearer pole, measured from that pole's side of the row, and z through
    // the elevation: both keep float precision at the poles (1 - v would not).
    float v_from_pole = (2 * y + 1 < height)
        ? v
        : (float(height - 1 - y) + (row_high - xi.x) / (row_high - row_low)) / float(height);
    float sin_theta = sin(kPi * v_from_pole);
    float azimuth_rad = radians(360.0 * u - skyNorthAzimuthDeg());
    vec3 direction_enu = vec3(sin_theta * sin(azimuth_rad), sin_theta * cos(azimuth_rad), sin((0.5 - v) * kPi));
    pdf_solid_angle = skySolidAnglePdf(skyUnitSquareDensity(x, y), sin_theta);
    return direction_enu;
}

// The map conditioned on a band of rows (a hemisphere's): a surface can take light only from above its plane, and
// a draw below it is a shadow ray's lane left idle while the others of its SIMD group trace (on the shrine
// site, 45 % of the map's rejected draws lay in rows no direction above the texel's plane reaches). The rows of
// the open hemisphere dot(normal, d) > 0 are those within 90 deg of the normal's polar angle, widened by one row
// at each end so that rounding never leaves a direction above the plane outside them.
ivec2 skyRowsFacing(vec3 normal) {
    int height = skyHeight();
    float v_normal = acos(clamp(normal.z, -1.0, 1.0)) / kPi;
    int first = int(floor((v_normal - 0.5) * float(height))) - 1;
    int last = int(floor((v_normal + 0.5) * float(height))) + 1;
    return ivec2(clamp(first, 0, height - 1), clamp(last, 0, height - 1));
}

// The marginal CDF's mass over rows [rows.x, rows.y]: 0 when they hold no light (or rows.x > rows.y).
float skyRowsProbability(ivec2 rows) {
    if (rows.x > rows.y) return 0.0;
    return skyTable(skyMarginalOffset() + rows.y + 1) - skyTable(skyMarginalOffset() + rows.x);
}

// sampleSkyDirection restricted to rows [rows.x, rows.y]: xi.x is mapped into those rows' part of the marginal
// CDF (kept below its upper end, so the search stays inside), so the density is skyPdf / skyRowsProbability
// there and 0 elsewhere. pdf 0 (and the zenith) when the rows hold no light: the caller traces nothing.
vec3 sampleSkyDirectionInRows(vec2 xi, ivec2 rows, out float pdf_solid_angle) {
    float probability = skyRowsProbability(rows);
    if (!(probability > 0.0)) {
        pdf_solid_angle = 0.0;
        return vec3(0.0, 0.0, 1.0);
    }
    float low = skyTable(skyMarginalOffset() + rows.x);
    float high = skyTable(skyMarginalOffset() + rows.y + 1);
    float below_high = uintBitsToFloat(floatBitsToUint(high) - 1u);  // high > 0 here
    float row_xi = min(low + clamp(xi.x, 0.0, 1.0) * probability, below_high);
    vec3 direction_enu = sampleSkyDirection(vec2(row_xi, xi.y), pdf_solid_angle);
    pdf_solid_angle /= probability;
    return direction_enu;
}

#endif  // GUSUKU_SKY_SAMPLING_GLSL

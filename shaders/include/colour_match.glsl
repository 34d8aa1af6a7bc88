// The colour match's transfer for shaders (docs/design.md 4): the GLSL twin of the transfer in
// engine/include/gusuku/maths/colour_match.h (read the choices and contracts there), same steps, float. The building's
// fragment shader calls applyColourMatch on its linear radiance before writing:
//
//   #extension GL_GOOGLE_include_directive : require
//   #include "colour_match.glsl"
//   layout(std430, set = S, binding = B) readonly buffer ColourMatchStateBuffer { ColourMatchState colour_match; };
//   ... out_colour = vec4(srgbEncode(applyColourMatch(linear_radiance, colour_match)), 1.0);
//
// The state is written by ColourStatisticsPass (engine/src/runtime/colour_statistics_pass.h) one frame ahead.
// tests/test_colour_match.cpp holds these functions to the C++ through shaders/tests/colour_match_probe.comp.
// Self-contained apart from colour.glsl and the interface header: no bindings, no extensions.
#ifndef GUSUKU_COLOUR_MATCH_GLSL
#define GUSUKU_COLOUR_MATCH_GLSL

#include "colour.glsl"
#include "colour_match_interface.h"

const float kColourMatchMaxWhiteBalanceShift = COLOUR_MATCH_MAX_WHITE_BALANCE_SHIFT;
const int kColourMatchGamutSteps = COLOUR_MATCH_GAMUT_STEPS;
const float kColourMatchMaxLinear = COLOUR_MATCH_MAX_LINEAR;
const float kColourMatchGamutTolerance = COLOUR_MATCH_GAMUT_TOLERANCE;

bool colourMatchActive(ColourMatchState state) {
    if (state.mode == COLOUR_MATCH_MODE_GROUND) return state.ground_valid != 0u;
    return state.mode != COLOUR_MATCH_MODE_OFF && state.camera_valid != 0u;
}

// The per-channel Lab transfer of the state's mode, before clamping and gamut mapping (identity when inactive).
vec3 colourMatchTransferLab(vec3 lab, ColourMatchState state) {
    if (!colourMatchActive(state) || state.mode == COLOUR_MATCH_MODE_GROUND) return lab;  // ground: not Lab
    vec3 source_mean = state.source_lab_mean.xyz;
    vec3 target_mean = state.camera_lab_mean.xyz;
    vec3 target_sigma = sqrt(max(state.camera_lab_variance.xyz, vec3(0.0)));
    vec3 gain = labTransferGain(state.source_lab_sigma.xyz, target_sigma, state.gain_limit);
    if (state.mode == COLOUR_MATCH_MODE_PAPER) return applyLabTransfer(lab, source_mean, gain, target_mean);
    // Preserve: L moved like the paper's; a, b keep their spread and take a bounded white-balance shift.
    vec2 shift = target_mean.yz - source_mean.yz;
    float shift_length = length(shift);
    if (shift_length > kColourMatchMaxWhiteBalanceShift) shift *= kColourMatchMaxWhiteBalanceShift / shift_length;
    return vec3((lab.x - source_mean.x) * gain.x + target_mean.x, lab.yz + shift);
}

bool colourMatchInUnitCube(vec3 rgb) {
    return all(greaterThanEqual(rgb, vec3(-kColourMatchGamutTolerance))) &&
           all(lessThanEqual(rgb, vec3(1.0 + kColourMatchGamutTolerance)));
}

// Preserve's gamut mapping: L clamped to [0, 100], chroma scaled towards the L axis (same L, same hue) by
// bisection until linear Rec.709 lies in [0, 1]; scale 0 (the grey of that L) is always inside.
vec3 colourMatchChromaIntoGamut(vec3 lab) {
    float lightness = clamp(lab.x, 0.0, 100.0);
    if (colourMatchInUnitCube(linearRec709FromLab(vec3(lightness, lab.yz)))) return vec3(lightness, lab.yz);
    float inside = 0.0;
    float outside = 1.0;
    for (int step = 0; step < kColourMatchGamutSteps; ++step) {
        float middle = 0.5 * (inside + outside);
        if (colourMatchInUnitCube(linearRec709FromLab(vec3(lightness, lab.yz * middle)))) inside = middle;
        else outside = middle;
    }
    return vec3(lightness, lab.yz * inside);
}

// The whole transfer of one linear Rec.709 colour: displayable linear RGB in [0, 1], never NaN. Mode GROUND
// takes the exposed radiance and multiplies it by the smoothed von Kries gain; the Lab modes take radiance.
vec3 applyColourMatch(vec3 linear_rgb, ColourMatchState state) {
    vec3 rgb = linear_rgb;
    for (int c = 0; c < 3; ++c) rgb[c] = isnan(rgb[c]) ? 0.0 : clamp(rgb[c], 0.0, kColourMatchMaxLinear);
    if (!colourMatchActive(state)) return clamp(rgb, vec3(0.0), vec3(1.0));
    if (state.mode == COLOUR_MATCH_MODE_GROUND) return clamp(rgb * state.ground_gain.xyz, vec3(0.0), vec3(1.0));
    vec3 lab = colourMatchTransferLab(labFromLinearRec709(rgb), state);
    lab.x = clamp(lab.x, 0.0, 100.0);
    if (state.mode == COLOUR_MATCH_MODE_PRESERVE) lab = colourMatchChromaIntoGamut(lab);
    return clamp(linearRec709FromLab(lab), vec3(0.0), vec3(1.0));
}

#endif  // GUSUKU_COLOUR_MATCH_GLSL

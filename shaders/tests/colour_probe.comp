#version 450
// Test kernel for shaders/include/colour.glsl: evaluates every function there for a list of colours, so
// tests/test_colour.cpp can hold each to its C++ twin in engine/include/gusuku/maths/colour.h.
// Bindings: 0 inputs, per probe: vec4(rgb, 0) (linear RGB, also read as sRGB-encoded), vec4(lab1, 0),
// vec4(lab2, 0) (two Lab colours for CIEDE2000 and the inverse chain);
// 1 transfer statistics: vec4(source mean, max_gain), vec4(source sigma, 0), vec4(target mean, 0),
// vec4(target sigma, 0);
// 2 outputs, per probe (kColourProbeOutputs vec4s): (srgbEncode(rgb), luminanceRec709(rgb)),
// (srgbDecode(rgb), ciede2000(lab1, lab2)), (xyzFromLinearRec709(rgb), 0), (labFromLinearRec709(rgb), 0),
// (linearRec709FromLab(lab1), 0), (applyLabTransfer(lab1, ...), 0), (labTransferGain(...), 0).
#extension GL_GOOGLE_include_directive : require

#include "colour.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer ProbeInputs { vec4 probe_inputs[]; };
layout(std430, set = 0, binding = 1) readonly buffer TransferStatistics { vec4 statistics[4]; };
layout(std430, set = 0, binding = 2) writeonly buffer ProbeOutputs { vec4 probe_outputs[]; };
layout(push_constant) uniform PushConstants { uint probe_count; } pc;

const uint kColourProbeOutputs = 7u;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.probe_count) return;
    vec3 rgb = probe_inputs[3u * i].xyz;
    vec3 lab1 = probe_inputs[3u * i + 1u].xyz;
    vec3 lab2 = probe_inputs[3u * i + 2u].xyz;

    vec3 gain = labTransferGain(statistics[1].xyz, statistics[3].xyz, statistics[0].w);
    uint o = kColourProbeOutputs * i;
    probe_outputs[o] = vec4(srgbEncode(rgb), luminanceRec709(rgb));
    probe_outputs[o + 1u] = vec4(srgbDecode(rgb), ciede2000(lab1, lab2));
    probe_outputs[o + 2u] = vec4(xyzFromLinearRec709(rgb), 0.0);
    probe_outputs[o + 3u] = vec4(labFromLinearRec709(rgb), 0.0);
    probe_outputs[o + 4u] = vec4(linearRec709FromLab(lab1), 0.0);
    probe_outputs[o + 5u] = vec4(applyLabTransfer(lab1, statistics[0].xyz, gain, statistics[2].xyz), 0.0);
    probe_outputs[o + 6u] = vec4(gain, 0.0);
}

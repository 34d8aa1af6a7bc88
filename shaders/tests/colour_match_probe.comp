#version 450
// Test kernel for shaders/include/colour_match.glsl: runs its transfer for a list of colours, so
// tests/test_colour_match.cpp can hold it to the C++ reference in engine/include/gusuku/maths/colour_match.h.
// Bindings: 0 the ColourMatchState; 1 inputs, per probe: vec4(linear rgb, 0), vec4(lab, 0);
// 2 outputs, per probe: vec4(colourMatchTransferLab(lab), 0), vec4(applyColourMatch(rgb), 0).
#extension GL_GOOGLE_include_directive : require

#include "colour_match.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer StateBuffer { ColourMatchState colour_match; };
layout(std430, set = 0, binding = 1) readonly buffer ProbeInputs { vec4 probe_inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer ProbeOutputs { vec4 probe_outputs[]; };
layout(push_constant) uniform PushConstants { uint probe_count; } pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.probe_count) return;
    ColourMatchState state = colour_match;
    probe_outputs[2u * i] = vec4(colourMatchTransferLab(probe_inputs[2u * i + 1u].xyz, state), 0.0);
    probe_outputs[2u * i + 1u] = vec4(applyColourMatch(probe_inputs[2u * i].xyz, state), 0.0);
}

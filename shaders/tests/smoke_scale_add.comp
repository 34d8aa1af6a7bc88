#version 450
// Smoke test for the compute path (tests/test_vulkan.cpp): out[i] = scale * in[i] + offset, plus one
// subgroupAdd reduction so the test proves subgroup arithmetic works on the device (docs/design.md 5 relies on it
// for colour statistics).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer InputValues { float in_values[]; };
layout(std430, set = 0, binding = 1) writeonly buffer OutputValues { float out_values[]; };
// key_sum accumulates (i % 1000) + 1 over all elements: an exact integer the CPU can recompute.
layout(std430, set = 0, binding = 2) buffer KeySum { uint key_sum; };

layout(push_constant) uniform ScaleAdd {
    float scale;
    float offset;
    uint count;
} params;

void main() {
    uint index = gl_GlobalInvocationID.x;
    bool in_range = index < params.count;
    if (in_range) {
        // precise: no fused multiply-add, so the result is bit-identical to the CPU's two roundings.
        precise float scaled = params.scale * in_values[index] + params.offset;
        out_values[index] = scaled;
    }
    // Outside any branch: subgroupAdd needs every invocation of the subgroup to take part.
    uint key = in_range ? (index % 1000u) + 1u : 0u;
    uint subgroup_key_sum = subgroupAdd(key);
    if (subgroupElect())
        atomicAdd(key_sum, subgroup_key_sum);
}

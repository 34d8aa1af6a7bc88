#version 450
// Test kernel for shaders/include/sky_sampling.glsl: evaluates sampleSkyDirection, skyRadiance and skyPdf for a
// list of inputs, so tests can compare them with the CPU twins (gusuku_bake/sky_light.h, runSkyProbeGpu).
// Bindings: 0 sky radiance, 1 sky table (uniform texel buffers, RGBA32F and R32F), 2 inputs (per probe: vec4(xi, 0, 0), vec4(direction, 0)),
// 3 outputs (per probe: vec4(sampled direction, pdf), vec4(radiance(direction), pdf(direction)),
// vec4(radiance(sampled), pdf(sampled)), vec4(skyRadianceAndPdf(direction)), vec4(skyRowsFacing(direction) as
// floats, skyRowsProbability of them, 0), vec4(sampleSkyDirectionInRows(xi, those rows), its pdf)).
#extension GL_GOOGLE_include_directive : require

#define SKY_RADIANCE_BINDING 0
#define SKY_TABLE_BINDING 1
#include "sky_sampling.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 2) readonly buffer ProbeInputs { vec4 probe_inputs[]; };
layout(std430, set = 0, binding = 3) writeonly buffer ProbeOutputs { vec4 probe_outputs[]; };
layout(push_constant) uniform PushConstants { uint probe_count; } pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.probe_count) return;
    vec2 xi = probe_inputs[2 * i].xy;
    vec3 direction_enu = probe_inputs[2 * i + 1].xyz;

    float sampled_pdf;
    vec3 sampled_direction = sampleSkyDirection(xi, sampled_pdf);
    probe_outputs[6 * i] = vec4(sampled_direction, sampled_pdf);
    probe_outputs[6 * i + 1] = vec4(skyRadiance(direction_enu), skyPdf(direction_enu));
    probe_outputs[6 * i + 2] = vec4(skyRadiance(sampled_direction), skyPdf(sampled_direction));
    float combined_pdf;
    vec3 combined_radiance = skyRadianceAndPdf(direction_enu, combined_pdf);
    probe_outputs[6 * i + 3] = vec4(combined_radiance, combined_pdf);
    // The direction taken as a surface's normal: the rows above its plane, and the map drawn in them.
    ivec2 rows = skyRowsFacing(direction_enu);
    probe_outputs[6 * i + 4] = vec4(float(rows.x), float(rows.y), skyRowsProbability(rows), 0.0);
    float rows_pdf;
    vec3 rows_direction = sampleSkyDirectionInRows(xi, rows, rows_pdf);
    probe_outputs[6 * i + 5] = vec4(rows_direction, rows_pdf);
}

#version 450
// Test kernel for shaders/include/ground_ratio.glsl: evaluates every function of the include for a list of
// probes, so tests/test_ground_ratio.cpp can compare them with gusuku/formats/ground_grid.h on the CPU.
// Bindings: 0 float inputs (per probe 6 vec4: (x, y, 0, 0), (E_with, V_bld), (E_without, V_scene), (I_sun, 0),
// (normal, 0), (sun direction, 0)), 1 integer inputs (per probe ivec4(column, row, index, 0)), 2 outputs (per
// probe 5 vec4: (cell centre, uv of the point), (found, cell at the point, index of the cell),
// (cell from index, inside, 0), (E_sun, 0), (ratio, 0)). Push constants: the grid and the probe count.
#extension GL_GOOGLE_include_directive : require

#include "ground_ratio.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer FloatInputs { vec4 float_inputs[]; };
layout(std430, set = 0, binding = 1) readonly buffer IntInputs { ivec4 int_inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer ProbeOutputs { vec4 probe_outputs[]; };
layout(push_constant) uniform PushConstants {
    vec2 origin_enu_m;
    float cell_m;
    int columns;
    int rows;
    uint probe_count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.probe_count) return;
    GroundGrid grid = GroundGrid(pc.origin_enu_m, pc.cell_m, pc.columns, pc.rows);
    vec2 point = float_inputs[6 * i].xy;
    vec4 with_and_building = float_inputs[6 * i + 1];
    vec4 without_and_scene = float_inputs[6 * i + 2];
    vec3 sun_irradiance = float_inputs[6 * i + 3].xyz;
    vec3 normal = float_inputs[6 * i + 4].xyz;
    vec3 sun_direction = float_inputs[6 * i + 5].xyz;
    ivec4 cell_and_index = int_inputs[i];

    ivec2 found_cell;
    bool found = groundCellAt(grid, point, found_cell);
    ivec2 from_index = groundCellFromIndex(grid, cell_and_index.z);
    vec3 e_sun = groundSunIrradiance(sun_irradiance, normal, sun_direction, without_and_scene.w);
    probe_outputs[5 * i] = vec4(groundCellCentreEnu(grid, cell_and_index.xy), groundGridUv(grid, point));
    probe_outputs[5 * i + 1] = vec4(found ? 1.0 : 0.0, vec2(found_cell), float(groundCellIndex(grid, cell_and_index.xy)));
    probe_outputs[5 * i + 2] = vec4(vec2(from_index), groundCellInside(grid, cell_and_index.xy) ? 1.0 : 0.0, 0.0);
    probe_outputs[5 * i + 3] = vec4(e_sun, 0.0);
    probe_outputs[5 * i + 4] = vec4(groundShadowRatio(with_and_building.xyz, without_and_scene.xyz, e_sun,
                                                      with_and_building.w), 0.0);
}

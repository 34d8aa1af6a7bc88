// Runs shaders/tests/sky_probe.comp: the GLSL sky lookup and sampling evaluated on the device, so tests can hold
// sky_sampling.glsl to its CPU twin in sky_importance.cpp.

#include <stdexcept>

#include "gusuku/gpu/gpu_compute.h"
#include "sky_probe.h"
#include "sky_probe_comp_spv.h"

namespace gusuku::bake {

std::vector<SkyProbeResult> runSkyProbeGpu(VulkanContext& context, const SkySamplingTables& tables,
                                           const std::vector<glm::vec2>& xi,
                                           const std::vector<glm::vec3>& directions_enu) {
    if (xi.size() != directions_enu.size())
        throw std::invalid_argument("runSkyProbeGpu: xi and directions_enu differ in size");
    if (xi.empty()) return {};
    constexpr uint32_t kLocalSize = 64;  // local_size_x in sky_probe.comp
    constexpr size_t kFloatsPerProbe = 24;  // six vec4 outputs per probe

    std::vector<float> inputs;
    inputs.reserve(xi.size() * 8);
    for (size_t i = 0; i < xi.size(); ++i) {
        inputs.insert(inputs.end(), {xi[i].x, xi[i].y, 0.0f, 0.0f});
        inputs.insert(inputs.end(), {directions_enu[i].x, directions_enu[i].y, directions_enu[i].z, 0.0f});
    }
    // The sky's two buffers as the tracers bind them: uniform texel buffers (sky_sampling.glsl).
    GpuBuffer radiance_buffer(context, tables.radiance_rgba.size() * sizeof(float),
                              VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    GpuBuffer table_buffer(context, tables.table.size() * sizeof(float), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    GpuBuffer input_buffer(context, inputs.size() * sizeof(float));
    GpuBuffer output_buffer(context, xi.size() * kFloatsPerProbe * sizeof(float));
    radiance_buffer.uploadVector(tables.radiance_rgba);
    table_buffer.uploadVector(tables.table);
    input_buffer.uploadVector(inputs);

    ComputePipeline pipeline(context, kSkyProbeCompSpirv, sizeof(kSkyProbeCompSpirv), 4, sizeof(uint32_t),
                             {{0, VK_FORMAT_R32G32B32A32_SFLOAT}, {1, VK_FORMAT_R32_SFLOAT}});
    pipeline.bindBuffers({&radiance_buffer, &table_buffer, &input_buffer, &output_buffer});
    const uint32_t probe_count = uint32_t(xi.size());
    pipeline.dispatchAndWait(&probe_count, (probe_count + kLocalSize - 1) / kLocalSize);

    const std::vector<float> outputs = output_buffer.downloadVector<float>(xi.size() * kFloatsPerProbe);
    std::vector<SkyProbeResult> results(xi.size());
    for (size_t i = 0; i < xi.size(); ++i) {
        const float* o = outputs.data() + i * kFloatsPerProbe;
        results[i].sampled_direction_enu = {o[0], o[1], o[2]};
        results[i].sampled_pdf = o[3];
        results[i].radiance_at_direction = {o[4], o[5], o[6]};
        results[i].pdf_at_direction = o[7];
        results[i].radiance_at_sample = {o[8], o[9], o[10]};
        results[i].pdf_at_sample = o[11];
        results[i].combined_radiance = {o[12], o[13], o[14]};
        results[i].combined_pdf = o[15];
        results[i].rows = {int(o[16]), int(o[17])};
        results[i].rows_probability = o[18];
        results[i].rows_sampled_direction_enu = {o[20], o[21], o[22]};
        results[i].rows_sampled_pdf = o[23];
    }
    return results;
}

}  // namespace gusuku::bake

// The building in the main pass (building_pass.h).

#include "building_pass.h"

#include <cstddef>

#include "building_frag_spv.h"
#include "building_vert_spv.h"
#include "frame_set.h"
#include "material_sets.h"
#include "runtime_interface.h"
#include "runtime_material_push.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {

using shader_interface::MaterialPushConstants;

BuildingPass::BuildingPass(const PassContext& context, const FrameSet& frame_set, const MaterialSets& materials,
                           VkRenderPass main_pass, VkSampleCountFlagBits samples)
    : context_(context), frame_set_(frame_set), materials_(materials) {
    const VkDevice device = context.gpu.device;
    GraphicsPipelineDescription building;
    building.layout = frame_set.shadingLayout();
    building.render_pass = main_pass;
    building.samples = samples;
    building.vertex_spirv = kBuildingVertSpirv;
    building.vertex_spirv_bytes = sizeof(kBuildingVertSpirv);
    building.fragment_spirv = kBuildingFragSpirv;
    building.fragment_spirv_bytes = sizeof(kBuildingFragSpirv);
    building.vertex_input.stride = sizeof(BuildingVertex);
    building.vertex_input.attributes = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, base_colour_uv)},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, lightmap_uv)},
    };
    building.stencil = StencilUse::kMarkBuilding;  // the ground ratio leaves these pixels alone
    pipeline_ = Pipeline(device, createGraphicsPipeline(device, building));

    // Only a bake set with an alpha-masked material gets this (an opaque one creates what it did before).
    bool any_masked = false;
    for (float cutoff : context.scene.alpha_cutoffs) any_masked |= cutoff >= 0.0f;
    if (!any_masked) return;
    // building.frag's kAlphaMasked and kAlphaToCoverage. With multisampling the mask's edge becomes a coverage
    // (alpha to coverage) rather than a per-pixel discard: a cut-out card's leaves and gaps smaller than a pixel
    // then cover the share of the pixel they cover in the texture, as the path tracer's pixel average does,
    // instead of all or nothing (on the shared house, its vine and tree cards held about half of the composite's
    // error over the building with a discard; docs/measurements.md).
    const bool to_coverage = samples != VK_SAMPLE_COUNT_1_BIT;
    const VkBool32 constants[2] = {VK_TRUE, to_coverage ? VK_TRUE : VK_FALSE};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(VkBool32)}, {1, sizeof(VkBool32), sizeof(VkBool32)}};
    const VkSpecializationInfo specialization{2, entries, sizeof constants, constants};
    GraphicsPipelineDescription masked = building;
    masked.fragment_specialization = &specialization;
    masked.alpha_to_coverage = to_coverage;
    masked_pipeline_ = Pipeline(device, createGraphicsPipeline(device, masked));
}

void BuildingPass::recordInMainPass(PassRecording& recording) {
    const VkCommandBuffer cmd = recording.cmd;
    const GpuScene& scene = context_.scene;
    const VkPipelineLayout layout = frame_set_.shadingLayout();
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    frame_set_.bindOnce(recording);
    const VkBuffer vertex_buffer = scene.building_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene.building_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    bool masked_bound = false;
    for (const MaterialDraw& draw : scene.draws) {
        // The masked materials come last (runtime_scene.h): one switch of pipeline, same layout.
        const float cutoff = scene.alpha_cutoffs[draw.material];
        if (cutoff >= 0.0f && !masked_bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_pipeline_.get());
            masked_bound = true;
        }
        materials_.bind(cmd, layout, RUNTIME_MATERIAL_SET, draw.material);
        const glm::vec4& factor = scene.base_colour_factors[draw.material];
        const MaterialPushConstants push{{{factor.r, factor.g, factor.b, factor.a}}, cutoff};
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
        vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, 0, 0);
    }
}

}  // namespace gusuku::runtime_detail

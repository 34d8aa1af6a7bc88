// The runtime's graphics pipelines (runtime_impl.h): their layouts, the depth-only ones (the shadow maps and the
// occluder), the building's and the ground's three variants. The generic plumbing is runtime_pipelines.h.

#include <cstddef>

#include "building_frag_spv.h"
#include "building_vert_spv.h"
#include "depth_masked_frag_spv.h"
#include "depth_masked_vert_spv.h"
#include "depth_only_vert_spv.h"
#include "ground_frag_spv.h"
#include "ground_vert_spv.h"
#include "gusuku/gpu/gpu_compute.h"
#include "runtime_impl.h"
#include "runtime_masked_depth_push.h"
#include "runtime_material_push.h"
#include "runtime_pipelines.h"

namespace gusuku::runtime_detail {

using shader_interface::DepthOnlyPushConstants;
using shader_interface::FrameUniforms;
using shader_interface::MaskedDepthPushConstants;
using shader_interface::MaterialPushConstants;

void RuntimeImpl::createPipelines() {
    const VkDevice device = gpu_.device;
    VkPushConstantRange depth_push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(DepthOnlyPushConstants)};
    VkPipelineLayoutCreateInfo depth_layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    depth_layout.pushConstantRangeCount = 1;
    depth_layout.pPushConstantRanges = &depth_push;
    checkVk(vkCreatePipelineLayout(device, &depth_layout, nullptr, &depth_layout_), "vkCreatePipelineLayout");
    const VkDescriptorSetLayout set_layouts[2] = {frame_set_layout_, material_set_layout_};
    VkPushConstantRange material_push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(MaterialPushConstants)};
    VkPipelineLayoutCreateInfo shading_layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    shading_layout.setLayoutCount = 2;
    shading_layout.pSetLayouts = set_layouts;
    shading_layout.pushConstantRangeCount = 1;
    shading_layout.pPushConstantRanges = &material_push;
    checkVk(vkCreatePipelineLayout(device, &shading_layout, nullptr, &shading_layout_), "vkCreatePipelineLayout");

    VertexInput positions_only;  // the building's vertices read for position alone, and the occluder's vec3s
    positions_only.stride = sizeof(BuildingVertex);
    positions_only.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
    VertexInput occluder_positions = positions_only;
    occluder_positions.stride = sizeof(float) * 3;
    VertexInput building_vertex;
    building_vertex.stride = sizeof(BuildingVertex);
    building_vertex.attributes = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, base_colour_uv)},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, lightmap_uv)},
    };

    GraphicsPipelineDescription shadow;
    shadow.layout = depth_layout_;
    shadow.render_pass = shadow_pass_;
    shadow.vertex_spirv = kDepthOnlyVertSpirv;
    shadow.vertex_spirv_bytes = sizeof(kDepthOnlyVertSpirv);
    shadow.vertex_input = positions_only;
    shadow.has_colour_attachment = false;
    shadow_pipeline_ = createGraphicsPipeline(device, shadow);
    // The occluder's vertices are bare vec3s: the stride is part of a pipeline, so it has pipelines of its own.
    GraphicsPipelineDescription site_shadow = shadow;
    site_shadow.vertex_input = occluder_positions;
    site_shadow_pipeline_ = createGraphicsPipeline(device, site_shadow);
    GraphicsPipelineDescription occluder = shadow;
    occluder.render_pass = main_passes_[0];
    occluder.samples = mainPassSamples();  // every main-pass pipeline rasterises at the pass's sample count
    occluder.vertex_input = occluder_positions;
    occluder.has_colour_attachment = true;
    occluder.blend = BlendMode::kNoColourWrites;
    occluder_pipeline_ = createGraphicsPipeline(device, occluder);

    GraphicsPipelineDescription building;
    building.layout = shading_layout_;
    building.render_pass = main_passes_[0];
    building.samples = mainPassSamples();
    building.vertex_spirv = kBuildingVertSpirv;
    building.vertex_spirv_bytes = sizeof(kBuildingVertSpirv);
    building.fragment_spirv = kBuildingFragSpirv;
    building.fragment_spirv_bytes = sizeof(kBuildingFragSpirv);
    building.vertex_input = building_vertex;
    building.stencil = StencilUse::kMarkBuilding;  // the ground ratio leaves these pixels alone
    building_pipeline_ = createGraphicsPipeline(device, building);
    createMaskedPipelines(building, shadow);

    GraphicsPipelineDescription ground;
    ground.vertex_input.stride = sizeof(float);  // per cell: the building's shadow may fall here this frame
    ground.vertex_input.attributes = {{0, 0, VK_FORMAT_R32_SFLOAT, 0}};
    ground.layout = shading_layout_;
    ground.render_pass = main_passes_[0];
    ground.samples = mainPassSamples();
    ground.vertex_spirv = kGroundVertSpirv;
    ground.vertex_spirv_bytes = sizeof(kGroundVertSpirv);
    ground.fragment_spirv = kGroundFragSpirv;
    ground.fragment_spirv_bytes = sizeof(kGroundFragSpirv);
    ground.depth_write = false;
    ground.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
    ground.blend = BlendMode::kMultiplyTwice;
    ground.stencil = StencilUse::kSkipBuilding;
    // Two variants of the ground's shader, by a specialisation constant: llvmpipe runs every branch of a
    // fragment shader for the whole SIMD group (masked), so a shadow lookup that most fragments skip still costs
    // them all; the quads no shadow can reach get a shader without one.
    // constant 0: read the building's shadow; constant 1: the sun shines (read the site's shadow, add E_sun).
    const VkBool32 variants[3][2] = {{VK_TRUE, VK_TRUE}, {VK_FALSE, VK_TRUE}, {VK_FALSE, VK_FALSE}};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(VkBool32)}, {1, sizeof(VkBool32), sizeof(VkBool32)}};
    VkSpecializationInfo specialization{2, entries, sizeof(variants[0]), variants[0]};
    ground.fragment_specialization = &specialization;
    ground_pipeline_ = createGraphicsPipeline(device, ground);
    specialization.pData = variants[1];
    ground_baked_pipeline_ = createGraphicsPipeline(device, ground);
    specialization.pData = variants[2];
    ground_sunless_pipeline_ = createGraphicsPipeline(device, ground);
}

// Only a bake set with an alpha-masked material gets these (an opaque one creates what it did before).
void RuntimeImpl::createMaskedPipelines(const GraphicsPipelineDescription& building,
                                        const GraphicsPipelineDescription& shadow) {
    bool any_masked = false;
    for (float cutoff : scene_.alpha_cutoffs) any_masked |= cutoff >= 0.0f;
    if (!any_masked) return;
    const VkDevice device = gpu_.device;
    // building.frag's kAlphaMasked and kAlphaToCoverage. With multisampling the mask's edge becomes a coverage
    // (alpha to coverage) rather than a per-pixel discard: a cut-out card's leaves and gaps smaller than a pixel
    // then cover the share of the pixel they cover in the texture, as the path tracer's pixel average does,
    // instead of all or nothing (on the shared house, its vine and tree cards held about half of the composite's
    // error over the building with a discard; docs/measurements.md).
    const bool to_coverage = building.samples != VK_SAMPLE_COUNT_1_BIT;
    const VkBool32 constants[2] = {VK_TRUE, to_coverage ? VK_TRUE : VK_FALSE};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(VkBool32)}, {1, sizeof(VkBool32), sizeof(VkBool32)}};
    const VkSpecializationInfo specialization{2, entries, sizeof constants, constants};
    GraphicsPipelineDescription building_masked = building;
    building_masked.fragment_specialization = &specialization;
    building_masked.alpha_to_coverage = to_coverage;
    building_masked_pipeline_ = createGraphicsPipeline(device, building_masked);

    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                             sizeof(MaskedDepthPushConstants)};
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.setLayoutCount = 1;
    layout.pSetLayouts = &material_set_layout_;
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &push;
    checkVk(vkCreatePipelineLayout(device, &layout, nullptr, &masked_depth_layout_), "vkCreatePipelineLayout");
    GraphicsPipelineDescription masked_shadow = shadow;
    masked_shadow.layout = masked_depth_layout_;
    masked_shadow.vertex_spirv = kDepthMaskedVertSpirv;
    masked_shadow.vertex_spirv_bytes = sizeof(kDepthMaskedVertSpirv);
    masked_shadow.fragment_spirv = kDepthMaskedFragSpirv;
    masked_shadow.fragment_spirv_bytes = sizeof(kDepthMaskedFragSpirv);
    masked_shadow.vertex_input.stride = sizeof(BuildingVertex);
    masked_shadow.vertex_input.attributes = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, position)},
        {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, base_colour_uv)},
    };
    masked_shadow_pipeline_ = createGraphicsPipeline(device, masked_shadow);
}

}  // namespace gusuku::runtime_detail

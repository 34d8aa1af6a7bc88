// The sun's shadow maps (shadow_pass.h).

#include "shadow_pass.h"

#include <cstddef>

#include "depth_masked_frag_spv.h"
#include "depth_masked_vert_spv.h"
#include "depth_only_vert_spv.h"
#include "frame_preparation.h"
#include "material_sets.h"
#include "runtime_masked_depth_push.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {

using shader_interface::DepthOnlyPushConstants;
using shader_interface::MaskedDepthPushConstants;

ShadowPass::ShadowPass(const PassContext& context, const MaterialSets& materials, float occluder_drop_m)
    : context_(context), materials_(materials), occluder_drop_m_(occluder_drop_m) {
    const VkDevice device = context.gpu.device;
    const uint32_t size = context.options.shadow_map_size;
    render_pass_ = RenderPass(device, createShadowRenderPass(device));
    GpuImageDescription description;
    description.format = kDepthFormat;
    description.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    description.width = description.height = size;
    description.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    for (ShadowMap* map : {&building_, &site_}) {
        map->image = GpuImage(context.gpu, description);
        map->framebuffer =
            Framebuffer(device, createFramebuffer(device, render_pass_.get(), {map->image.view()}, size, size));
    }
    // The maps start in the layout the frame set's descriptors name, so a frame that skips them reads a defined
    // (cleared) map.
    GpuSubmitter submitter(context.gpu);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        for (const ShadowMap* map : {&building_, &site_})
            recordImageLayoutTransition(cmd, map->image.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, VK_ACCESS_SHADER_READ_BIT,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    createPipelines();
}

void ShadowPass::createPipelines() {
    const VkDevice device = context_.gpu.device;
    depth_layout_ = createPipelineLayout(device, {}, VK_SHADER_STAGE_VERTEX_BIT, sizeof(DepthOnlyPushConstants));
    GraphicsPipelineDescription building;
    building.layout = depth_layout_.get();
    building.render_pass = render_pass_.get();
    building.vertex_spirv = kDepthOnlyVertSpirv;
    building.vertex_spirv_bytes = sizeof(kDepthOnlyVertSpirv);
    building.vertex_input.stride = sizeof(BuildingVertex);  // read for position alone
    building.vertex_input.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
    building.has_colour_attachment = false;
    building_pipeline_ = Pipeline(device, createGraphicsPipeline(device, building));
    // The occluder's vertices are bare vec3s: the stride is part of a pipeline, so it has a pipeline of its own.
    GraphicsPipelineDescription site = building;
    site.vertex_input.stride = sizeof(float) * 3;
    site_pipeline_ = Pipeline(device, createGraphicsPipeline(device, site));

    // Only a bake set with an alpha-masked material gets these (an opaque one creates what it did before).
    bool any_masked = false;
    for (float cutoff : context_.scene.alpha_cutoffs) any_masked |= cutoff >= 0.0f;
    if (!any_masked) return;
    masked_layout_ = createPipelineLayout(device, {materials_.layout()},
                                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                          sizeof(MaskedDepthPushConstants));
    GraphicsPipelineDescription masked = building;
    masked.layout = masked_layout_.get();
    masked.vertex_spirv = kDepthMaskedVertSpirv;
    masked.vertex_spirv_bytes = sizeof(kDepthMaskedVertSpirv);
    masked.fragment_spirv = kDepthMaskedFragSpirv;
    masked.fragment_spirv_bytes = sizeof(kDepthMaskedFragSpirv);
    masked.vertex_input.attributes = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, position)},
        {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, base_colour_uv)},
    };
    masked_pipeline_ = Pipeline(device, createGraphicsPipeline(device, masked));
}

void ShadowPass::prepare(const glm::dvec3& shadow_sun, bool sun_shines, bool site_shadows) {
    if (shadow_sun != sun_direction_) {
        const GpuScene& scene = context_.scene;
        sun_direction_ = shadow_sun;
        invalidate();
        fit_ = fitShadowMap(scene.receivers_min, scene.receivers_max, scene.casters_min, scene.casters_max,
                            shadow_sun, context_.options.shadow_map_size);
    }
    building_.render = sun_shines && !building_.valid;
    site_.render = site_shadows && !site_.valid;
    push_ = shadowPushFor(fit_);
}

void ShadowPass::recordBefore(PassRecording& recording) {
    const VkCommandBuffer cmd = recording.cmd;
    const GpuScene& scene = context_.scene;
    if (building_.render) {
        beginMap(cmd, building_, {building_pipeline_.get(), scene.building_vertices, scene.building_indices,
                                  scene.opaque_index_count});
        recordMaskedMaterials(cmd);
        vkCmdEndRenderPass(cmd);
        building_.valid = true;
    }
    if (site_.render) {
        // The occluder lowered by its simplification error, as the camera sees it: raised above the real ground by
        // up to that error, its ground put a low sun's shadow on a building's foot (a 2 cm platform's sunlit side
        // 0.57 of the truth at a 17 degree sun; docs/design.md 3).
        beginMap(cmd, site_, {site_pipeline_.get(), scene.occluder_vertices, scene.occluder_indices,
                              scene.occluder_index_count, occluder_drop_m_});
        vkCmdEndRenderPass(cmd);
        site_.valid = true;
    }
}

// The map's pass begun (cleared to far) and the caster's one draw.
void ShadowPass::beginMap(VkCommandBuffer cmd, const ShadowMap& map, const Caster& caster) const {
    const uint32_t size = context_.options.shadow_map_size;
    VkClearValue clear{};
    clear.depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass_.get();
    begin.framebuffer = map.framebuffer.get();
    begin.renderArea = {{0, 0}, {size, size}};
    begin.clearValueCount = 1;
    begin.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    recordViewport(cmd, size, size);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster.pipeline);
    DepthOnlyPushConstants push = push_;
    push.drop_m = caster.drop_m;
    vkCmdPushConstants(cmd, depth_layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push, &push);
    const VkDeviceSize offset = 0;
    const VkBuffer vertex_buffer = caster.vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, caster.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    if (caster.index_count > 0) vkCmdDrawIndexed(cmd, caster.index_count, 1, 0, 0, 0);
}

// Inside the building's map, after its opaque materials: each alpha-masked material with its alpha test
// (depth_masked.frag). Nothing when every material is opaque.
void ShadowPass::recordMaskedMaterials(VkCommandBuffer cmd) const {
    const GpuScene& scene = context_.scene;
    if (scene.opaque_index_count == scene.building_index_count) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_pipeline_.get());
    for (const MaterialDraw& draw : scene.draws) {
        const float cutoff = scene.alpha_cutoffs[draw.material];
        if (cutoff < 0.0f) continue;
        materials_.bind(cmd, masked_layout_.get(), 0, draw.material);
        MaskedDepthPushConstants push{};
        push.enu_to_clip = push_.enu_to_clip;
        push.base_colour_alpha = scene.base_colour_factors[draw.material].a;
        push.alpha_cutoff = cutoff;
        vkCmdPushConstants(cmd, masked_layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof push, &push);
        vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, 0, 0);
    }
}

}  // namespace gusuku::runtime_detail

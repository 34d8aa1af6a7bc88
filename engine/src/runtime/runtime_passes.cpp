// The frame on the GPU, pass by pass (runtime_impl.h; docs/design.md 8): the uniforms and the camera readied, the
// colour statistics, the sun's shadow maps, the occluder's depth, the building, the ground ratio, the read-back. Each
// records into a command buffer and submits nothing (runtime_submission.cpp does).

#include "gusuku/gpu/gpu_compute.h"
#include "runtime_impl.h"
#include "runtime_masked_depth_push.h"
#include "runtime_material_push.h"
#include "runtime_pipelines.h"

namespace gusuku::runtime_detail {

using shader_interface::DepthOnlyPushConstants;
using shader_interface::MaskedDepthPushConstants;
using shader_interface::MaterialPushConstants;

// Outside any render pass, before the others: this frame's uniforms into their buffer (in the command buffer,
// so no host write can land under a frame still in flight), and the camera readied for sampling.
void RuntimeImpl::recordFrameStart(VkCommandBuffer cmd, const FrameInput& frame) {
    static_assert(sizeof uniforms_ <= 65536 && sizeof uniforms_ % 4 == 0, "vkCmdUpdateBuffer's limits");
    const VkPipelineStageFlags uniform_readers =
        VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};  // the earlier frames' reads first (execution only)
    vkCmdPipelineBarrier(cmd, uniform_readers, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    vkCmdUpdateBuffer(cmd, uniform_buffer_.handle(), 0, sizeof uniforms_, &uniforms_);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_UNIFORM_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, uniform_readers, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    // The pack writes only the pixels this frame's statistics read (the ground grid, or the Lab modes' grid),
    // and only on the frames that measure.
    const ColourStatisticsGrid* pack_grid = nullptr;
    if (statistics_ && frame_measures_colour_)
        pack_grid = frame_colour_mode_ == ColourMatchMode::kGround ? &statistics_->groundGrid() : &statistics_->grid();
    camera_->recordBeforePasses(cmd, slot_, frame, pack_grid);
}

void RuntimeImpl::recordStatistics(VkCommandBuffer cmd, const FrameInput& frame) {
    if (!statistics_) return;  // no colour match on this device (prepareColourMatch refused any other mode)
    // Every frame: the mode and the source follow the frame; the smoothed camera state stays between measurements.
    statistics_->recordSourceUpdate(cmd, frame_source_statistics_, frame_colour_mode_, options_.colour_gain_limit);
    if (!frame_measures_colour_) return;
    if (frame_colour_mode_ == ColourMatchMode::kGround)
        statistics_->recordGround(cmd, camera_->packedBuffer(), frame_ground_view_);
    else if (frame_colour_mode_ != ColourMatchMode::kOff)
        statistics_->record(cmd, camera_->packedBuffer());
}

void RuntimeImpl::recordShadows(VkCommandBuffer cmd) {
    if (!render_building_shadow_ && !render_site_shadow_) return;
    const VkDeviceSize offset = 0;
    auto shadowPass = [&](VkFramebuffer framebuffer, const DepthOnlyPushConstants& push, VkPipeline pipeline,
                          const GpuBuffer& vertices, const GpuBuffer& indices, uint32_t index_count) {
        VkClearValue clear{};
        clear.depthStencil = {1.0f, 0};
        VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        begin.renderPass = shadow_pass_;
        begin.framebuffer = framebuffer;
        begin.renderArea = {{0, 0}, {options_.shadow_map_size, options_.shadow_map_size}};
        begin.clearValueCount = 1;
        begin.pClearValues = &clear;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        recordViewport(cmd, options_.shadow_map_size, options_.shadow_map_size);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdPushConstants(cmd, depth_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push, &push);
        const VkBuffer vertex_buffer = vertices.handle();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
        vkCmdBindIndexBuffer(cmd, indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        if (index_count > 0) vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
        if (&vertices == &scene_.building_vertices) recordMaskedShadows(cmd);
        vkCmdEndRenderPass(cmd);
    };
    if (render_building_shadow_) {
        shadowPass(building_shadow_framebuffer_, shadow_push_, shadow_pipeline_, scene_.building_vertices,
                   scene_.building_indices, scene_.opaque_index_count);
        building_shadow_valid_ = true;
    }
    if (render_site_shadow_) {
        shadowPass(site_shadow_framebuffer_, shadow_push_, site_shadow_pipeline_, scene_.occluder_vertices,
                   scene_.occluder_indices, scene_.occluder_index_count);
        site_shadow_valid_ = true;
    }
}

// Inside the building's shadow pass, after its opaque materials: each alpha-masked material with its alpha test
// (depth_masked.frag). Nothing when every material is opaque.
void RuntimeImpl::recordMaskedShadows(VkCommandBuffer cmd) {
    if (scene_.opaque_index_count == scene_.building_index_count) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_shadow_pipeline_);
    for (const MaterialDraw& draw : scene_.draws) {
        const float cutoff = scene_.alpha_cutoffs[draw.material];
        if (cutoff < 0.0f) continue;
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_depth_layout_, 0, 1,
                                &material_sets_[draw.material], 0, nullptr);
        MaskedDepthPushConstants push{};
        push.enu_to_clip = shadow_push_.enu_to_clip;
        push.base_colour_alpha = scene_.base_colour_factors[draw.material].a;
        push.alpha_cutoff = cutoff;
        vkCmdPushConstants(cmd, masked_depth_layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof push, &push);
        vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, 0, 0);
    }
}

// The variants that start the frame's main pass (kWhole, kFirst) do not load the composite: the camera-in draw
// writes every pixel of it first.
void RuntimeImpl::beginMainPass(VkCommandBuffer cmd, VkRenderPass render_pass) {
    VkClearValue clears[2]{};
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass;
    begin.framebuffer = slots_[slot_].framebuffer;  // compatible with every variant
    begin.renderArea = {{0, 0}, {options_.frame_width, options_.frame_height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    recordViewport(cmd, options_.frame_width, options_.frame_height);
    if (render_pass == main_passes_[0] || render_pass == main_passes_[1]) camera_->recordDraw(cmd, slot_);
}

void RuntimeImpl::recordOccluder(VkCommandBuffer cmd) {
    if (scene_.occluder_index_count == 0) return;
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, occluder_pipeline_);
    vkCmdPushConstants(cmd, depth_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof occluder_push_, &occluder_push_);
    const VkBuffer vertex_buffer = scene_.occluder_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene_.occluder_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, scene_.occluder_index_count, 1, 0, 0, 0);
}

void RuntimeImpl::recordBuilding(VkCommandBuffer cmd) {
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, building_pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_FRAME_SET, 1, &frame_set_,
                            0, nullptr);
    frame_set_bound_ = true;
    const VkBuffer vertex_buffer = scene_.building_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene_.building_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    bool masked_bound = false;
    for (const MaterialDraw& draw : scene_.draws) {
        // The masked materials come last (runtime_scene.h): one switch of pipeline, same layout.
        const float cutoff = scene_.alpha_cutoffs[draw.material];
        if (cutoff >= 0.0f && !masked_bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, building_masked_pipeline_);
            masked_bound = true;
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_MATERIAL_SET, 1,
                                &material_sets_[draw.material], 0, nullptr);
        const glm::vec4& factor = scene_.base_colour_factors[draw.material];
        const MaterialPushConstants push{{{factor.r, factor.g, factor.b, factor.a}}, cutoff};
        vkCmdPushConstants(cmd, shading_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
        vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, 0, 0);
    }
}

void RuntimeImpl::recordGround(VkCommandBuffer cmd) {
    if (!draw_ground_) return;
    // The frame set is bound once per command buffer (by the building, which always draws first in the whole
    // frame), never again here. On lavapipe (Mesa 22.3) each vkCmdBindDescriptorSets makes new gallium sampler
    // views for the set's images, and when the next draw's vertex shader samples them (the ground's reads the
    // ground geometry and irradiance) the driver keeps what it made for that vertex-stage sampling until the
    // device is destroyed: a rebind right before the ground draw grew resident memory by ~280 KB every frame,
    // on the driver's thread, with the validation layer silent (vertex sampling of views already bound and used
    // by the building's draw keeps nothing). Rebinding the same set was redundant anyway: the building's
    // pipeline layout is the ground's, so the binding stays valid across the pipeline change.
    if (!frame_set_bound_)
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_FRAME_SET, 1,
                                &frame_set_, 0, nullptr);
    const FrameSlot& slot = slots_[slot_];
    const VkBuffer candidates = slot.ground_candidates.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &candidates, &offset);
    vkCmdBindIndexBuffer(cmd, slot.ground_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    if (ground_shadow_index_count_ > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ground_pipeline_);
        vkCmdDrawIndexed(cmd, ground_shadow_index_count_, 1, 0, 0, 0);
    }
    if (ground_index_count_ > ground_shadow_index_count_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          sun_shines_ ? ground_baked_pipeline_ : ground_sunless_pipeline_);
        vkCmdDrawIndexed(cmd, ground_index_count_ - ground_shadow_index_count_, 1, ground_shadow_index_count_, 0, 0);
    }
}

void RuntimeImpl::recordReadback(VkCommandBuffer cmd) {
    // The main pass left the composite in TRANSFER_SRC_OPTIMAL (its final layout).
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {options_.frame_width, options_.frame_height, 1};
    vkCmdCopyImageToBuffer(cmd, slots_[slot_].composite.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           slots_[slot_].readback.handle(), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr,
                         0, nullptr);
}


}  // namespace gusuku::runtime_detail

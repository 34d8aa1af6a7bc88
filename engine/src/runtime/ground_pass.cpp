// The ground ratio (ground_pass.h).

#include "ground_pass.h"

#include <algorithm>

#include "frame_set.h"
#include "ground_frag_spv.h"
#include "ground_vert_spv.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {

GroundPass::GroundPass(const PassContext& context, const GroundGrid& grid, const FrameSet& frame_set,
                       uint32_t slot_count, VkRenderPass main_pass, VkSampleCountFlagBits samples)
    : context_(context), grid_(grid), frame_set_(frame_set) {
    const GpuScene& scene = context.scene;
    cell_marked_.assign(scene.ground_cell_state.size(), 0);
    shadow_candidate_.assign(scene.ground_cell_state.size(), 0.0f);
    quad_indices_.assign(size_t(scene.ground_quad_capacity) * 6, 0);
    const size_t index_bytes = std::max<size_t>(quad_indices_.size() * sizeof(uint32_t), kMinBufferBytes);
    const size_t candidate_bytes = std::max<size_t>(shadow_candidate_.size() * sizeof(float), kMinBufferBytes);
    slots_.resize(slot_count);
    for (SlotBuffers& slot : slots_) {
        slot.indices = GpuBuffer(context.gpu, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, GpuMemory::kHostVisible);
        slot.candidates =
            GpuBuffer(context.gpu, candidate_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, GpuMemory::kHostVisible);
    }

    const VkDevice device = context.gpu.device;
    GraphicsPipelineDescription ground;
    ground.vertex_input.stride = sizeof(float);  // per cell: the building's shadow may fall here this frame
    ground.vertex_input.attributes = {{0, 0, VK_FORMAT_R32_SFLOAT, 0}};
    ground.layout = frame_set.shadingLayout();
    ground.render_pass = main_pass;
    ground.samples = samples;
    ground.vertex_spirv = kGroundVertSpirv;
    ground.vertex_spirv_bytes = sizeof(kGroundVertSpirv);
    ground.fragment_spirv = kGroundFragSpirv;
    ground.fragment_spirv_bytes = sizeof(kGroundFragSpirv);
    ground.depth_write = false;
    ground.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
    ground.blend = BlendMode::kMultiplyTwice;
    ground.stencil = StencilUse::kSkipBuilding;
    // Three variants of the ground's shader, by specialisation constants: llvmpipe runs every branch of a
    // fragment shader for the whole SIMD group (masked), so a shadow lookup that most fragments skip still costs
    // them all; the quads no shadow can reach get a shader without one.
    // constant 0: read the building's shadow; constant 1: the sun shines (read the site's shadow, add E_sun).
    const VkBool32 variants[3][2] = {{VK_TRUE, VK_TRUE}, {VK_FALSE, VK_TRUE}, {VK_FALSE, VK_FALSE}};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(VkBool32)}, {1, sizeof(VkBool32), sizeof(VkBool32)}};
    VkSpecializationInfo specialization{2, entries, sizeof(variants[0]), variants[0]};
    ground.fragment_specialization = &specialization;
    shadow_pipeline_ = Pipeline(device, createGraphicsPipeline(device, ground));
    specialization.pData = variants[1];
    baked_pipeline_ = Pipeline(device, createGraphicsPipeline(device, ground));
    specialization.pData = variants[2];
    sunless_pipeline_ = Pipeline(device, createGraphicsPipeline(device, ground));
}

void GroundPass::choose(const GroundRequest& request) {
    chosen_for_ = request;
    index_count_ = shadow_index_count_ = 0;
    if (request.wanted) {
        const GpuScene& scene = context_.scene;
        const GroundCells cells{grid_, scene.ground_cell_state, scene.ground_cell_height};
        const GroundQuadSelection selection =
            selectGroundQuads(cells, scene.building_min, scene.building_max, request.include_baked_changes,
                              request.sun_shines, request.shadow_sun, cell_marked_, shadow_candidate_, quad_indices_);
        index_count_ = selection.index_count;
        shadow_index_count_ = selection.shadow_index_count;
    }
    ++generation_;
}

void GroundPass::prepare(uint32_t slot_index, const GroundRequest& request) {
    if (chosen_for_ != request) choose(request);
    SlotBuffers& slot = slots_[slot_index];
    if (slot.generation == generation_) return;
    slot.generation = generation_;
    if (index_count_ == 0) return;
    slot.indices.upload(quad_indices_.data(), index_count_ * sizeof(uint32_t));
    slot.candidates.upload(shadow_candidate_.data(), shadow_candidate_.size() * sizeof(float));
}

void GroundPass::recordInMainPass(PassRecording& recording) {
    if (index_count_ == 0) return;
    const VkCommandBuffer cmd = recording.cmd;
    // The building's pipeline layout is the ground's, so the frame set the building bound stays valid across the
    // pipeline change; bound here only in a command buffer of the ground's own (the profiled frame).
    frame_set_.bindOnce(recording);
    const SlotBuffers& slot = slots_[recording.slot];
    const VkBuffer candidates = slot.candidates.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &candidates, &offset);
    vkCmdBindIndexBuffer(cmd, slot.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    if (shadow_index_count_ > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow_pipeline_.get());
        vkCmdDrawIndexed(cmd, shadow_index_count_, 1, 0, 0, 0);
    }
    if (index_count_ > shadow_index_count_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          chosen_for_->sun_shines ? baked_pipeline_.get() : sunless_pipeline_.get());
        vkCmdDrawIndexed(cmd, index_count_ - shadow_index_count_, 1, shadow_index_count_, 0, 0);
    }
}

uint64_t GroundPass::memoryBytes() const {
    uint64_t bytes = 0;
    for (const SlotBuffers& slot : slots_) bytes += slot.indices.size() + slot.candidates.size();
    return bytes;
}

}  // namespace gusuku::runtime_detail

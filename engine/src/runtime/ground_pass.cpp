// The ground ratio (ground_pass.h).

#include "ground_pass.h"

#include <algorithm>
#include <numbers>

#include <glm/vector_relational.hpp>

#include "frame_set.h"
#include "gusuku/maths/shadow_fit.h"
#include "ground_frag_spv.h"
#include "ground_vert_spv.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {
namespace {
constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
// A cell the bake marks is left undrawn where the frame's light keeps its ratio within this of 1 (ground_sunlit.h's
// proof). The shader itself writes exactly 1 only within kPassThroughThreshold; a cell between the two would scale a
// camera pixel's linear value by less than 2/255 (0.8 %), which moves its 8-bit sRGB code c by about c x 0.008 / 2.4:
// under one code at any value. Measured at 1280 x 720 against every marked cell drawn (ground_change_threshold 0):
// byte-identical on the sample at 10:30 and the shrine at 12:00, one code on 598 of the house's 921,600 pixels;
// drawn quads 1,528 -> 1,152 (sample), 968 -> 486 (shrine), 1,085 -> 784 (house) (docs/measurements.md, "The
// ground ratio's cost at the runtime's defaults"): the part of the ground pass direct-only does not pay.
constexpr float kGroundSkipThreshold = 2.0f / 255.0f;
}  // namespace

GroundPass::GroundPass(const PassContext& context, const GroundGrid& grid, const FrameSet& frame_set,
                       uint32_t slot_count, VkRenderPass main_pass, VkSampleCountFlagBits samples)
    : context_(context), grid_(grid), frame_set_(frame_set) {
    const GpuScene& scene = context.scene;
    cell_marked_.assign(scene.ground_cell_state.size(), 0);
    shadow_candidate_.assign(scene.ground_cell_state.size(), 0.0f);
    pass_through_.assign(scene.ground_cell_state.size(), 0);
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

void GroundPass::choose(const GroundRequest& request, const SlotBlend& blend, const glm::dvec3& sun_irradiance_rgb) {
    chosen_for_ = request;
    index_count_ = shadow_index_count_ = quads_drawn_ = 0;
    if (request.wanted) {
        const GpuScene& scene = context_.scene;
        const GroundCells cells{grid_, scene.ground_cell_state, scene.ground_cell_height, scene.ground_cell_normal};
        std::fill(pass_through_.begin(), pass_through_.end(), uint8_t(0));
        // A threshold of 0 asks for every cell the building changes (a debugging view, and the C API's control that
        // an appended option is read): no cell is left to the pass-through proof then.
        if (request.include_baked_changes && context_.options.ground_change_threshold > 0.0f) {
            PassThroughLight light;
            for (int index = 0; index < 3; ++index)
                light.slots[index] = blend.slots[index], light.weights[index] = blend.weights[index];
            light.sun_shines = request.sun_shines;
            light.shadow_sun = request.shadow_sun;
            sun_floor_ = kGroundSunFloorFraction * sun_irradiance_rgb;
            light.sun_irradiance_floor = sun_floor_;
            // The frame's sun lies within the rounding step of the shadow maps' sun (in both angles), which moves a
            // cosine by less than the step in radians.
            light.cosine_slack = double(std::max(context_.options.shadow_sun_step_deg, 0.0f)) * kRadiansPerDegree + 0.001;
            light.pass_through_threshold = kGroundSkipThreshold;
            // The site's map as the shadow pass fits it for this sun (shadow_pass.cpp).
            const double texel_m = fitShadowMap(scene.receivers_min, scene.receivers_max, scene.casters_min,
                                                scene.casters_max, request.shadow_sun,
                                                context_.options.shadow_map_size)
                                       .texel_size_m;
            light.site_shadow = {texel_m, double(context_.options.shadow_bias_texels)};
            markPassThroughCells(cells, scene.ground_slot_light, scene.site_heights, light, pass_through_);
        }
        const GroundQuadSelection selection =
            selectGroundQuads(cells, scene.building_min, scene.building_max, request.include_baked_changes,
                              request.sun_shines, request.shadow_sun, cell_marked_, shadow_candidate_, quad_indices_,
                              pass_through_);
        index_count_ = selection.index_count;
        shadow_index_count_ = selection.shadow_index_count;
        quads_drawn_ = selection.quads;
    }
    ++generation_;
}

void GroundPass::prepare(uint32_t slot_index, GroundRequest request, const SlotBlend& blend,
                         const glm::dvec3& sun_irradiance_rgb) {
    for (int index = 0; index < 3; ++index)
        request.slots_in_use[size_t(index)] = blend.weights[index] > 0.0f ? blend.slots[index] : -1;
    const bool sun_below_floor = request.sun_shines && request.include_baked_changes &&
                                 glm::any(glm::lessThan(sun_irradiance_rgb, sun_floor_));
    if (chosen_for_ != request || sun_below_floor) choose(request, blend, sun_irradiance_rgb);
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

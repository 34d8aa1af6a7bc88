// The sun read from the site's shadows (sun_evidence_pass.h).

#include "sun_evidence_pass.h"
#include "memory_barrier.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "sun_evidence_comp_spv.h"
#include "sun_evidence_reduce_comp_spv.h"

namespace gusuku::runtime_detail {

using shader_interface::GroundMatchCellGpu;
using shader_interface::GroundMatchFrame;
using shader_interface::SunEvidencePushConstants;
using shader_interface::SunEvidenceReducePushConstants;
using shader_interface::SunEvidenceResult;
using shader_interface::SunEvidenceSampleGpu;

// std430 and C++ agree (interface_types.h's rules), and the GLSL's constants are the CPU reference's.
static_assert(sizeof(SunEvidenceSampleGpu) == 16);
static_assert(offsetof(SunEvidenceResult, cue) == 12 && offsetof(SunEvidenceResult, frame_serial) == 36);
static_assert(sizeof(SunEvidenceResult) == 48);
static_assert(offsetof(SunEvidencePushConstants, frame_width) == 64 && sizeof(SunEvidencePushConstants) == 96);
static_assert(SUN_EVIDENCE_BINS == kSunEvidenceBins);
static_assert(SUN_EVIDENCE_LOWEST_LOG2_RATIO == kSunEvidenceLowestLog2Ratio);
static_assert(SUN_EVIDENCE_LOG2_RATIO_SPAN == kSunEvidenceLog2RatioSpan);
static_assert(SUN_EVIDENCE_LOWEST_STRENGTH == kSunEvidenceLowestStrength);
static_assert(SUN_EVIDENCE_STRENGTH_SPAN == kSunEvidenceStrengthSpan);
static_assert(SUN_EVIDENCE_WINDOW_BINS == kSunEvidenceWindowBins);
static_assert(SUN_EVIDENCE_MIN_SUN_SHARE == kSunEvidenceMinSunShare);
static_assert(SUN_EVIDENCE_SHADOWED_VISIBILITY == kSunEvidenceShadowedVisibility);
static_assert(SUN_EVIDENCE_LIT_VISIBILITY == kSunEvidenceLitVisibility);
static_assert(SUN_EVIDENCE_MIN_SAMPLES == kSunEvidenceMinSamples);
static_assert(SUN_EVIDENCE_FULL_SAMPLES == kSunEvidenceFullSamples);
static_assert(SUN_EVIDENCE_OUT_STRENGTH == kSunEvidenceOutStrength);
static_assert(SUN_EVIDENCE_MIN_WIDTH == kSunEvidenceMinWidth);
static_assert(SUN_EVIDENCE_STEP_TOLERANCE_M == kSunEvidenceStepToleranceM);
static_assert(SUN_EVIDENCE_MAX_CROSSINGS == kSunEvidenceMaxCrossings);
static_assert(SUN_EVIDENCE_MIN_RESPONSE_SPREAD_LOG2 == kSunEvidenceMinResponseSpreadLog2);
static_assert(SUN_EVIDENCE_MIN_RESPONSE_GAMMA == kSunEvidenceMinResponseGamma);
static_assert(SUN_EVIDENCE_MAX_RESPONSE_GAMMA == kSunEvidenceMaxResponseGamma);
static_assert(offsetof(SunEvidenceResult, response_gamma) == 40);
static_assert(SUN_EVIDENCE_KIND_SHADOWED == double(SunEvidenceSampleKind::kShadowed));
static_assert(SUN_EVIDENCE_KIND_LIT == double(SunEvidenceSampleKind::kLit));

namespace {

uint32_t divideRoundingUp(uint64_t value, uint32_t divisor) { return uint32_t((value + divisor - 1) / divisor); }

// The highest cell with ground (sunEvidenceGroundTop), read once from the colour match's cells.
float groundTopOf(const GpuBuffer& cell_buffer) {
    std::vector<GroundMatchCellGpu> cells(cell_buffer.size() / sizeof(GroundMatchCellGpu));
    cell_buffer.download(cells.data(), cells.size() * sizeof(GroundMatchCellGpu));
    float top = -std::numeric_limits<float>::max();
    for (const GroundMatchCellGpu& cell : cells)
        if (cell.ground > 0.5f) top = std::max(top, cell.height_m);
    return top;
}

}  // namespace

SunEvidencePass::SunEvidencePass(const PassContext& context, const ColourStatisticsPass& statistics,
                                 const GpuBuffer& packed_camera, const ShadowPass& shadows, uint32_t frames_in_flight)
    : context_(context),
      statistics_(statistics),
      grid_(statistics.groundGrid()),
      workgroups_x_(divideRoundingUp(grid_.samples_x, COLOUR_STATISTICS_TILE)),
      workgroups_y_(divideRoundingUp(grid_.samples_y, COLOUR_STATISTICS_TILE)),
      sample_buffer_(context.gpu, size_t(grid_.sampleCount()) * sizeof(SunEvidenceSampleGpu),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal),
      frame_buffer_(context.gpu, sizeof(GroundMatchFrame),
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuMemory::kDeviceLocal),
      result_buffer_(context.gpu, frames_in_flight * sizeof(SunEvidenceResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     GpuMemory::kHostVisible),
      reduce_(context.gpu, kSunEvidenceReduceCompSpirv, sizeof kSunEvidenceReduceCompSpirv,
              SUN_EVIDENCE_REDUCE_BINDING_COUNT, sizeof(SunEvidenceReducePushConstants)),
      slots_(frames_in_flight),
      ground_top_m_(groundTopOf(statistics.groundCellBuffer())) {
    const GroundMatchFrame no_view{};
    frame_buffer_.upload(&no_view, sizeof no_view);
    reduce_.bindBuffers({&sample_buffer_, &result_buffer_});
    createSamplePipeline(statistics, packed_camera, shadows);
}

void SunEvidencePass::createSamplePipeline(const ColourStatisticsPass& statistics, const GpuBuffer& packed_camera,
                                           const ShadowPass& shadows) {
    const VkDevice device = context_.gpu.device;
    // The site map as the ground pass reads it: bilinear compare, lit outside (frame_set.cpp's shadow sampler).
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_LINEAR;
    sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    sampler.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    sampler.compareEnable = VK_TRUE;
    sampler.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    VkSampler sampler_handle = VK_NULL_HANDLE;
    checkVk(vkCreateSampler(device, &sampler, nullptr, &sampler_handle), "vkCreateSampler (sun evidence)");
    site_sampler_ = Sampler(device, sampler_handle);

    VkDescriptorSetLayoutBinding bindings[SUN_EVIDENCE_BINDING_COUNT];
    for (uint32_t binding = 0; binding < SUN_EVIDENCE_BINDING_COUNT; ++binding)
        bindings[binding] = {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    bindings[SUN_EVIDENCE_SITE_SHADOW_BINDING].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    VkDescriptorSetLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout_info.bindingCount = SUN_EVIDENCE_BINDING_COUNT;
    layout_info.pBindings = bindings;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &set_layout),
            "vkCreateDescriptorSetLayout (sun evidence)");
    set_layout_ = DescriptorSetLayout(device, set_layout);
    const VkDescriptorPoolSize pool_sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, SUN_EVIDENCE_BINDING_COUNT - 1},
                                                {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 2;
    pool_info.pPoolSizes = pool_sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool (sun evidence)");
    pool_ = DescriptorPool(device, pool);
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = pool;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &set_layout;
    checkVk(vkAllocateDescriptorSets(device, &allocate, &set_), "vkAllocateDescriptorSets (sun evidence)");

    // Every binding is fixed for the runtime's life: the set is written once.
    const GpuBuffer* buffers[SUN_EVIDENCE_BINDING_COUNT - 1] = {&packed_camera, &sample_buffer_,
                                                                &statistics.groundCellBuffer(),
                                                                &statistics.groundIrradianceBuffer(), &frame_buffer_};
    VkDescriptorBufferInfo buffer_infos[SUN_EVIDENCE_BINDING_COUNT - 1];
    VkWriteDescriptorSet writes[SUN_EVIDENCE_BINDING_COUNT];
    for (uint32_t binding = 0; binding < SUN_EVIDENCE_BINDING_COUNT; ++binding) {
        writes[binding] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[binding].dstSet = set_;
        writes[binding].dstBinding = binding;
        writes[binding].descriptorCount = 1;
        writes[binding].descriptorType = bindings[binding].descriptorType;
        if (binding == SUN_EVIDENCE_SITE_SHADOW_BINDING) continue;
        buffer_infos[binding] = {buffers[binding]->handle(), 0, VK_WHOLE_SIZE};
        writes[binding].pBufferInfo = &buffer_infos[binding];
    }
    const VkDescriptorImageInfo site_map{site_sampler_.get(), shadows.siteMap().view(),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    writes[SUN_EVIDENCE_SITE_SHADOW_BINDING].pImageInfo = &site_map;
    vkUpdateDescriptorSets(device, SUN_EVIDENCE_BINDING_COUNT, writes, 0, nullptr);

    layout_ = createPipelineLayout(device, {set_layout}, VK_SHADER_STAGE_COMPUTE_BIT,
                                   sizeof(SunEvidencePushConstants));
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = sizeof(kSunEvidenceCompSpirv);
    module_info.pCode = kSunEvidenceCompSpirv;
    VkShaderModule module = VK_NULL_HANDLE;
    checkVk(vkCreateShaderModule(device, &module_info, nullptr, &module), "vkCreateShaderModule (sun evidence)");
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout_.get();
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult result = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    checkVk(result, "vkCreateComputePipelines (sun evidence)");
    pipeline_ = Pipeline(device, pipeline);
}

void SunEvidencePass::prepare(uint32_t slot, bool measure, const GroundMatchView& view,
                              const shader_interface::FrameUniforms& uniforms, double utc_unix_seconds) {
    ++frames_;
    slot_ = slot;
    harvest(slot);  // the slot's fence has signalled (FrameSubmission::prepare): its last result is final
    // One of the colour match's measurements in kSunEvidenceMeasurementInterval (the first after a reset): the
    // filter's hysteresis carries the reading between them.
    if (measure) {
        if (measurements_to_skip_ > 0) {
            --measurements_to_skip_;
            measure = false;
        } else {
            measurements_to_skip_ = kSunEvidenceMeasurementInterval - 1;
        }
    }
    measure_ = measure;
    if (!measure) return;
    frame_ = statistics_.groundFrameFor(view);
    push_.enu_to_shadow_clip = uniforms.enu_to_shadow_clip;
    push_.frame_width = context_.options.frame_width;
    push_.stride = grid_.stride;
    push_.first_sample_offset = grid_.offset;
    push_.samples_x = grid_.samples_x;
    push_.samples_y = grid_.samples_y;
    push_.shadow_depth_bias = uniforms.shadow_depth_bias;
    push_.sun_up = view.sun_direction_enu.z > 0.0 ? 1u : 0u;
    push_.ground_top_m = ground_top_m_;
    slots_[slot] = {true, frames_, utc_unix_seconds};
}

void SunEvidencePass::recordAfter(PassRecording& recording) {
    if (!measure_) return;
    const VkCommandBuffer cmd = recording.cmd;
    // The earlier frames' kernels read the view before this write replaces it (write after read: execution only).
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
    vkCmdUpdateBuffer(cmd, frame_buffer_.handle(), 0, sizeof frame_, &frame_);
    // The view's write, this frame's site map (its pass ended in SHADER_READ_ONLY_OPTIMAL), and the camera pack
    // (made visible to compute by the colour match's barrier) against the kernel; the earlier frames' reduce's reads
    // of the samples against their rewrite.
    recordMemoryBarrier(cmd,
                        VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push_, &push_);
    vkCmdDispatch(cmd, workgroups_x_, workgroups_y_, 1);
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    SunEvidenceReducePushConstants reduce{};
    reduce.sample_count = uint32_t(grid_.sampleCount());
    reduce.result_index = slot_;
    reduce.frame_serial = uint32_t(slots_[slot_].frame_index);
    reduce_.recordDispatch(cmd, &reduce, 1);
    // The result to the host after the fence; the samples to later readers (tests' downloads are transfers); and the
    // site map's read before a later frame's shadow pass writes it again (write after read: the shadow render pass's
    // own dependency waits only for fragment shaders).
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void SunEvidencePass::harvest(uint32_t slot) {
    Slot& held = slots_[slot];
    if (!held.pending) return;
    held.pending = false;
    SunEvidenceResult result{};
    result_buffer_.download(&result, sizeof result, slot * sizeof result);
    // A later frame's result may already be harvested (slots finish in order, but are read in any).
    if (latest_ && latest_->frame_index > held.frame_index) return;
    RuntimeSunEvidence reading;
    reading.frame_index = held.frame_index;
    reading.utc_unix_seconds = held.utc_unix_seconds;
    SunEvidenceEstimate& estimate = reading.estimate;
    estimate.evidence.sun_out_probability = result.sun_out_probability;
    estimate.evidence.confidence = result.confidence;
    estimate.evidence.sun_strength = result.sun_strength;
    estimate.cue = result.cue <= 2u ? SunEvidenceCue(result.cue) : SunEvidenceCue::kNone;  // 2: the metered ground
    estimate.shadowed_samples = result.shadowed_samples;
    estimate.lit_samples = result.lit_samples;
    estimate.shade_log2_ratio = result.shade_log2_ratio;
    estimate.strength = result.strength;
    estimate.strength_standard_error = result.strength_standard_error;
    estimate.response_gamma = result.response_gamma;
    latest_ = reading;
}

}  // namespace gusuku::runtime_detail

// The sun read from the site's shadows (sun_evidence_pass.h).

#include "sun_evidence_pass.h"
#include "memory_barrier.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "sun_evidence_reduce_comp_spv.h"

namespace gusuku::runtime_detail {

using shader_interface::GroundMatchCellGpu;
using shader_interface::SunEvidenceGroundFrame;
using shader_interface::SunEvidenceReducePushConstants;
using shader_interface::SunEvidenceResult;
using shader_interface::SunEvidenceSampleGpu;

// std430 and C++ agree (interface_types.h's rules), and the GLSL's constants are the CPU reference's.
static_assert(sizeof(SunEvidenceSampleGpu) == 32 && offsetof(SunEvidenceSampleGpu, site_coordinates) == 16);
static_assert(offsetof(SunEvidenceGroundFrame, clear_sun_irradiance) == 64 &&
              offsetof(SunEvidenceGroundFrame, ground_top_m) == 88 && sizeof(SunEvidenceGroundFrame) == 96);
static_assert(offsetof(SunEvidenceResult, cue) == 12 && offsetof(SunEvidenceResult, frame_serial) == 36);
static_assert(sizeof(SunEvidenceResult) == 48);
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

SunEvidencePass::SunEvidencePass(const PassContext& context, ColourStatisticsPass& statistics, const ShadowPass& shadows,
                                 uint32_t frames_in_flight)
    : context_(context),
      statistics_(statistics),
      grid_(statistics.groundGrid()),
      result_buffer_(context.gpu, frames_in_flight * sizeof(SunEvidenceResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     GpuMemory::kHostVisible),
      slots_(frames_in_flight),
      ground_top_m_(groundTopOf(statistics.groundCellBuffer())) {
    statistics_.enableSunEvidence();
    createReducePipeline(shadows);
}

void SunEvidencePass::createReducePipeline(const ShadowPass& shadows) {
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

    constexpr uint32_t kBindings = SUN_EVIDENCE_REDUCE_BINDING_COUNT;
    constexpr uint32_t kSiteShadow = SUN_EVIDENCE_REDUCE_SITE_SHADOW_BINDING;
    VkDescriptorSetLayoutBinding bindings[kBindings];
    for (uint32_t binding = 0; binding < kBindings; ++binding)
        bindings[binding] = {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    bindings[kSiteShadow].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    VkDescriptorSetLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout_info.bindingCount = kBindings;
    layout_info.pBindings = bindings;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &set_layout),
            "vkCreateDescriptorSetLayout (sun evidence)");
    set_layout_ = DescriptorSetLayout(device, set_layout);
    const VkDescriptorPoolSize pool_sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindings - 1},
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
    const VkDescriptorBufferInfo buffer_infos[2] = {{statistics_.sunEvidenceBuffer().handle(), 0, VK_WHOLE_SIZE},
                                                    {result_buffer_.handle(), 0, VK_WHOLE_SIZE}};
    static_assert(SUN_EVIDENCE_REDUCE_SAMPLE_BINDING == 0 && SUN_EVIDENCE_REDUCE_RESULT_BINDING == 1 &&
                  kSiteShadow == 2);
    const VkDescriptorImageInfo site_map{site_sampler_.get(), shadows.siteMap().view(),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet writes[kBindings];
    for (uint32_t binding = 0; binding < kBindings; ++binding) {
        writes[binding] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[binding].dstSet = set_;
        writes[binding].dstBinding = binding;
        writes[binding].descriptorCount = 1;
        writes[binding].descriptorType = bindings[binding].descriptorType;
        if (binding == kSiteShadow) writes[binding].pImageInfo = &site_map;
        else writes[binding].pBufferInfo = &buffer_infos[binding];
    }
    vkUpdateDescriptorSets(device, kBindings, writes, 0, nullptr);

    layout_ = createPipelineLayout(device, {set_layout}, VK_SHADER_STAGE_COMPUTE_BIT,
                                   sizeof(SunEvidenceReducePushConstants));
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = sizeof(kSunEvidenceReduceCompSpirv);
    module_info.pCode = kSunEvidenceReduceCompSpirv;
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
    // The ground kernel's own view carries the camera, the blend and the sun's direction (the same as this view's);
    // the clear sun's irradiance, against which the share q is taken, comes here.
    SunEvidenceGroundFrame frame{};
    frame.enu_to_shadow_clip = uniforms.enu_to_shadow_clip;
    frame.clear_sun_irradiance = statistics_.groundFrameFor(view).sun_irradiance;
    frame.shadow_depth_bias = uniforms.shadow_depth_bias;
    frame.sun_up = view.sun_direction_enu.z > 0.0 ? 1u : 0u;
    frame.ground_top_m = ground_top_m_;
    statistics_.requestSunEvidence(frame);
    slots_[slot] = {true, frames_, utc_unix_seconds};
}

void SunEvidencePass::recordAfter(PassRecording& recording) {
    if (!measure_) return;
    const VkCommandBuffer cmd = recording.cmd;
    // The ground kernel's samples (written before the main pass) and this frame's site map (its pass ended in
    // SHADER_READ_ONLY_OPTIMAL) against the reduce, which reads both and writes the samples' kinds.
    recordMemoryBarrier(cmd,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    SunEvidenceReducePushConstants reduce{};
    reduce.sample_count = uint32_t(grid_.sampleCount());
    reduce.result_index = slot_;
    reduce.frame_serial = uint32_t(slots_[slot_].frame_index);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof reduce, &reduce);
    vkCmdDispatch(cmd, 1, 1, 1);
    // The result to the host after the fence; the samples to later readers (the next measurement's ground kernel
    // rewrites them; tests' downloads are transfers); and the site map's read before a later frame's shadow pass
    // writes it again (write after read: the shadow render pass's own dependency waits only for fragment shaders).
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                            VK_ACCESS_SHADER_WRITE_BIT);
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

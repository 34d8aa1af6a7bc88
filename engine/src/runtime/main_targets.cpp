// The main pass's targets (main_targets.h).

#include "main_targets.h"

#include "gusuku/gpu/gpu_compute.h"

namespace gusuku::runtime_detail {

MainTargets::MainTargets(const PassContext& context, uint32_t slot_count)
    : context_(context), samples_(VkSampleCountFlagBits(context.options.msaa_samples)) {
    const GpuDevice& gpu = context.gpu;
    const uint32_t width = context.options.frame_width, height = context.options.frame_height;
    const VkFormat depth_format = mainDepthStencilFormat(gpu.physical_device);  // checked by checkDeviceRequirements
    const VkImageAspectFlags depth_aspect = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    if (samples_ == VK_SAMPLE_COUNT_1_BIT) {
        GpuImageDescription depth;
        depth.format = depth_format;
        depth.width = width;
        depth.height = height;
        depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        depth.aspect = depth_aspect;
        depth_ = GpuImage(gpu, depth);
    } else {
        msaa_colour_ = MultisampleTarget(gpu, {kColourFormat, VK_IMAGE_ASPECT_COLOR_BIT, width, height, samples_});
        msaa_depth_ = MultisampleTarget(gpu, {depth_format, depth_aspect, width, height, samples_});
    }
    for (MainPassVariant variant : {MainPassVariant::kWhole, MainPassVariant::kFirst, MainPassVariant::kMiddle,
                                    MainPassVariant::kLast})
        render_passes_[size_t(variant)] =
            RenderPass(gpu.device, createMainRenderPass(gpu.device, variant, samples_, depth_format));

    GpuImageDescription colour;
    colour.format = kColourFormat;
    colour.width = width;
    colour.height = height;
    colour.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    slots_.resize(slot_count);
    for (Slot& slot : slots_) {
        slot.composite = GpuImage(gpu, colour);
        const std::vector<VkImageView> views =
            samples_ == VK_SAMPLE_COUNT_1_BIT
                ? std::vector<VkImageView>{slot.composite.view(), depth_.view()}
                : std::vector<VkImageView>{msaa_colour_.view(), msaa_depth_.view(), slot.composite.view()};
        slot.framebuffer = Framebuffer(
            gpu.device, createFramebuffer(gpu.device, renderPass(MainPassVariant::kWhole), views, width, height));
    }
    GpuSubmitter submitter(gpu);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        for (const Slot& slot : slots_)
            recordImageLayoutTransition(cmd, slot.composite.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, 0,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    });
}

void MainTargets::begin(VkCommandBuffer cmd, uint32_t slot, MainPassVariant variant) const {
    const uint32_t width = context_.options.frame_width, height = context_.options.frame_height;
    VkClearValue clears[2]{};
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = renderPass(variant);
    begin.framebuffer = slots_[slot].framebuffer.get();  // compatible with every variant
    begin.renderArea = {{0, 0}, {width, height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    recordViewport(cmd, width, height);
}

uint64_t MainTargets::memoryBytes() const {
    uint64_t bytes = depth_.memoryBytes() + msaa_colour_.memoryBytes() + msaa_depth_.memoryBytes();
    for (const Slot& slot : slots_) bytes += slot.composite.memoryBytes();
    return bytes;
}

}  // namespace gusuku::runtime_detail

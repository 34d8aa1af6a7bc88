// The frame's submission (frame_submission.h).

#include "frame_submission.h"

#include "main_targets.h"
#include "runtime_camera.h"

namespace gusuku::runtime_detail {

FrameSubmission::FrameSubmission(const PassContext& context, const MainTargets& targets)
    : context_(context), targets_(targets) {
    const GpuDevice& gpu = context.gpu;
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = gpu.queue_family_index;
    VkCommandPool pool = VK_NULL_HANDLE;
    checkVk(vkCreateCommandPool(gpu.device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    pool_ = CommandPool(gpu.device, pool);
    slots_.resize(context.options.frames_in_flight);
    const size_t readback_bytes = size_t(context.options.frame_width) * context.options.frame_height * 4;
    for (Slot& slot : slots_) {
        slot.readback = GpuBuffer(gpu, readback_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate_info.commandPool = pool;
        allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate_info.commandBufferCount = 1;
        checkVk(vkAllocateCommandBuffers(gpu.device, &allocate_info, &slot.command_buffer),
                "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        checkVk(vkCreateFence(gpu.device, &fence_info, nullptr, &fence), "vkCreateFence");
        slot.fence = Fence(gpu.device, fence);
    }
}

void FrameSubmission::prepare() {
    slot_ = (last_slot_ + 1) % uint32_t(slots_.size());
    waitFor(slots_[slot_]);
}

void FrameSubmission::waitFor(Slot& slot) {
    if (!slot.in_flight) return;
    const VkFence fence = slot.fence.get();
    checkVk(vkWaitForFences(context_.gpu.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    checkVk(vkResetFences(context_.gpu.device, 1, &fence), "vkResetFences");
    slot.in_flight = false;
}

void FrameSubmission::waitAll() {
    for (Slot& slot : slots_) waitFor(slot);
}

bool FrameSubmission::finished(uint32_t slot) const {
    const Slot& held = slots_[slot];
    return !held.in_flight || vkGetFenceStatus(context_.gpu.device, held.fence.get()) == VK_SUCCESS;
}

VkCommandBuffer FrameSubmission::begin() {
    const VkCommandBuffer cmd = slots_[slot_].command_buffer;
    checkVk(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    return cmd;
}

void FrameSubmission::submit(const FrameSync* sync) {
    Slot& slot = slots_[slot_];
    checkVk(vkEndCommandBuffer(slot.command_buffer), "vkEndCommandBuffer");
    VkSubmitInfo submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit_info.commandBufferCount = 1;
    submit_info.pCommandBuffers = &slot.command_buffer;
    VkPipelineStageFlags all_stages[kMaxFrameSemaphores];  // waits without stages given wait at every stage
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    if (sync != nullptr && sync->wait_count + sync->signal_count > 0) {
        for (VkPipelineStageFlags& stages : all_stages) stages = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
        submit_info.waitSemaphoreCount = sync->wait_count;
        submit_info.pWaitSemaphores = sync->wait_semaphores;
        submit_info.pWaitDstStageMask = sync->wait_stages != nullptr ? sync->wait_stages : all_stages;
        submit_info.signalSemaphoreCount = sync->signal_count;
        submit_info.pSignalSemaphores = sync->signal_semaphores;
        if (sync->wait_values != nullptr || sync->signal_values != nullptr) {
            timeline.waitSemaphoreValueCount = sync->wait_values != nullptr ? sync->wait_count : 0;
            timeline.pWaitSemaphoreValues = sync->wait_values;
            timeline.signalSemaphoreValueCount = sync->signal_values != nullptr ? sync->signal_count : 0;
            timeline.pSignalSemaphoreValues = sync->signal_values;
            submit_info.pNext = &timeline;
        }
    }
    checkVk(context_.gpu.submitToQueue(submit_info, slot.fence.get()), "vkQueueSubmit");
    slot.in_flight = true;
    last_slot_ = slot_;
}

// The main pass left the composite in TRANSFER_SRC_OPTIMAL (its final layout).
void FrameSubmission::recordAfter(PassRecording& recording) {
    if (!recording.read_back) return;
    const VkCommandBuffer cmd = recording.cmd;
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {context_.options.frame_width, context_.options.frame_height, 1};
    vkCmdCopyImageToBuffer(cmd, targets_.composite(recording.slot).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           slots_[recording.slot].readback.handle(), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr,
                         0, nullptr);
}

void FrameSubmission::readBack(uint8_t* output_rgba8) {
    Slot& slot = slots_[slot_];
    waitFor(slot);
    slot.readback.download(output_rgba8, size_t(context_.options.frame_width) * context_.options.frame_height * 4);
}

uint64_t FrameSubmission::memoryBytes() const {
    uint64_t bytes = 0;
    for (const Slot& slot : slots_) bytes += slot.readback.size();
    return bytes;
}

}  // namespace gusuku::runtime_detail

// Submission (runtime_impl.h): the frame slots and their fences, each frame's one command buffer submitted with
// the app's semaphores; the composite read back only when the caller asks for bytes; the frame whole, or pass by
// pass with wall-clock timings for the profiling mode (the GPU idle around each pass).

#include <chrono>

#include "gusuku/gpu/gpu_compute.h"
#include "runtime_camera.h"
#include "runtime_error_category.h"
#include "runtime_impl.h"

namespace gusuku::runtime_detail {

namespace {
// What a frame call does, for its errors' messages ("gusuku runtime: out of host memory rendering a frame").
constexpr const char* kRendering = "rendering a frame";
}  // namespace

// The next slot, once the GPU is done with the frame that used it last: the one wait of the GPU-resident
// path, which blocks only when frames_in_flight frames are all still on the GPU.
void RuntimeImpl::acquireSlot(const FrameInput& frame) {
    slot_ = (last_slot_ + 1) % uint32_t(slots_.size());
    waitForSlot(slots_[slot_]);
    if (camera_->needsEviction(frame)) waitIdle();  // a view other frames may read is about to go
}

void RuntimeImpl::waitForSlot(FrameSlot& slot) {
    if (!slot.in_flight) return;
    checkVk(vkWaitForFences(gpu_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    checkVk(vkResetFences(gpu_.device, 1, &slot.fence), "vkResetFences");
    slot.in_flight = false;
}

void RuntimeImpl::waitIdle() {
    try {
        for (FrameSlot& slot : slots_) waitForSlot(slot);
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidFrame, "waiting for the frames in flight");
    }
}

void RuntimeImpl::forgetCameraImage(VkImage image) {
    waitIdle();
    camera_->forget(image);
}

void RuntimeImpl::beginCommands() {
    const VkCommandBuffer cmd = slots_[slot_].command_buffer;
    checkVk(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    frame_set_bound_ = false;
}

void RuntimeImpl::submitCommands(const FrameSync* sync) {
    FrameSlot& slot = slots_[slot_];
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
    checkVk(gpu_.submitToQueue(submit_info, slot.fence), "vkQueueSubmit");
    slot.in_flight = true;
    last_slot_ = slot_;
}

void RuntimeImpl::finishOutput(uint8_t* output_rgba8) {
    if (output_rgba8 == nullptr) return;
    FrameSlot& slot = slots_[slot_];
    waitForSlot(slot);
    slot.readback.download(output_rgba8, size_t(options_.frame_width) * options_.frame_height * 4);
}

FrameInfo RuntimeImpl::renderFrame(const FrameInput& frame, uint8_t* output_rgba8) {
    checkFrame(frame);
    FrameInfo info;
    try {
        acquireSlot(frame);
        info = prepareFrame(frame);
        submit(
            [&](VkCommandBuffer cmd) {
                recordFrameStart(cmd, frame);
                recordStatistics(cmd, frame);
                recordShadows(cmd);
                beginMainPass(cmd, main_passes_[0]);
                recordOccluder(cmd);
                recordBuilding(cmd);
                recordGround(cmd);
                vkCmdEndRenderPass(cmd);
                camera_->recordAfterPasses(cmd, frame);
                if (output_rgba8 != nullptr) recordReadback(cmd);
            },
            &frame.sync, false);
        finishOutput(output_rgba8);
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidFrame, kRendering);
    }
    return info;
}

FrameInfo RuntimeImpl::renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) {
    using Clock = std::chrono::steady_clock;
    auto milliseconds = [](Clock::time_point from, Clock::time_point to) {
        return std::chrono::duration<double, std::milli>(to - from).count();
    };
    const Clock::time_point start = Clock::now();
    checkFrame(frame);
    FrameInfo info;
    // Each pass alone in its own submission, waited for: lavapipe writes timestamps only when graphics work is
    // flushed (docs/design.md 5), so wall time around a fenced submission is the honest per-pass figure.
    auto timed = [&](double& slot, const auto& record) {
        const Clock::time_point pass_start = Clock::now();
        submit(record, nullptr, true);
        slot = milliseconds(pass_start, Clock::now());
    };
    try {
        waitIdle();  // every pass alone, with nothing else on the GPU
        acquireSlot(frame);
        info = prepareFrame(frame);
        timed(timings.upload_ms, [&](VkCommandBuffer cmd) { recordFrameStart(cmd, frame); });
        timed(timings.statistics_ms, [&](VkCommandBuffer cmd) { recordStatistics(cmd, frame); });
        timed(timings.shadow_ms, [&](VkCommandBuffer cmd) { recordShadows(cmd); });
        timed(timings.occluder_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[1]);
            recordOccluder(cmd);
            vkCmdEndRenderPass(cmd);
        });
        timed(timings.building_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[2]);
            recordBuilding(cmd);
            vkCmdEndRenderPass(cmd);
        });
        timed(timings.ground_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[3]);
            recordGround(cmd);
            vkCmdEndRenderPass(cmd);
            camera_->recordAfterPasses(cmd, frame);
        });
        timed(timings.readback_ms, [&](VkCommandBuffer cmd) { recordReadback(cmd); });
        const Clock::time_point copy_start = Clock::now();
        finishOutput(output_rgba8);
        timings.readback_ms += milliseconds(copy_start, Clock::now());
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidFrame, kRendering);
    }
    timings.total_ms = milliseconds(start, Clock::now());
    return info;
}

}  // namespace gusuku::runtime_detail

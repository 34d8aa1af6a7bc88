// Submission (runtime_impl.h): the frame's one command buffer, submitted and waited on with one fence; the
// composite read back; the frame whole, or pass by pass with wall-clock timings for the profiling mode.

#include <chrono>

#include "gusuku/gpu/gpu_compute.h"
#include "runtime_impl.h"

namespace gusuku::runtime_detail {

void RuntimeImpl::beginCommands() {
    checkVk(vkResetCommandBuffer(command_buffer_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(command_buffer_, &begin), "vkBeginCommandBuffer");
    frame_set_bound_ = false;
}

void RuntimeImpl::submitCommandsAndWait() {
    checkVk(vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");
    VkSubmitInfo submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit_info.commandBufferCount = 1;
    submit_info.pCommandBuffers = &command_buffer_;
    checkVk(gpu_.submitToQueue(submit_info, fence_), "vkQueueSubmit");
    checkVk(vkWaitForFences(gpu_.device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    checkVk(vkResetFences(gpu_.device, 1, &fence_), "vkResetFences");
}

void RuntimeImpl::finishOutput(uint8_t* output_rgba8) {
    if (output_rgba8 != nullptr)
        readback_buffer_.download(output_rgba8, size_t(options_.frame_width) * options_.frame_height * 4);
}

FrameInfo RuntimeImpl::renderFrame(const FrameInput& frame, uint8_t* output_rgba8) {
    const FrameInfo info = prepareFrame(frame);
    try {
        submit([&](VkCommandBuffer cmd) {
            recordCameraIn(cmd, frame);
            recordStatistics(cmd, frame);
            recordShadows(cmd);
            beginMainPass(cmd, main_passes_[0]);
            recordOccluder(cmd);
            recordBuilding(cmd);
            recordGround(cmd);
            vkCmdEndRenderPass(cmd);
            recordReadback(cmd);
        });
        finishOutput(output_rgba8);
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
    return info;
}

FrameInfo RuntimeImpl::renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) {
    using Clock = std::chrono::steady_clock;
    auto milliseconds = [](Clock::time_point from, Clock::time_point to) {
        return std::chrono::duration<double, std::milli>(to - from).count();
    };
    const Clock::time_point start = Clock::now();
    const FrameInfo info = prepareFrame(frame);
    // Each pass alone in its own submission, waited for: lavapipe writes timestamps only when graphics work is
    // flushed (docs/design.md 5), so wall time around a fenced submission is the honest per-pass figure.
    auto timed = [&](double& slot, const auto& record) {
        const Clock::time_point pass_start = Clock::now();
        submit(record);
        slot = milliseconds(pass_start, Clock::now());
    };
    try {
        timed(timings.upload_ms, [&](VkCommandBuffer cmd) { recordCameraIn(cmd, frame); });
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
        });
        timed(timings.readback_ms, [&](VkCommandBuffer cmd) { recordReadback(cmd); });
        const Clock::time_point copy_start = Clock::now();
        finishOutput(output_rgba8);
        timings.readback_ms += milliseconds(copy_start, Clock::now());
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
    timings.total_ms = milliseconds(start, Clock::now());
    return info;
}

}  // namespace gusuku::runtime_detail

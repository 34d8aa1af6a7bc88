// The frame recorded (runtime_impl.h): the list's hooks phase by phase, the main pass begun and ended around the
// main-pass hooks; the whole frame in one command buffer submitted with the app's semaphores, or (the profiling
// mode) each pass's share in a submission of its own, timed with the GPU idle around it.

#include <algorithm>
#include <chrono>

#include "runtime_error_category.h"
#include "runtime_impl.h"

namespace gusuku::runtime_detail {

namespace {
// What a frame call does, for its errors' messages ("gusuku runtime: out of host memory rendering a frame").
constexpr const char* kRendering = "rendering a frame";
constexpr int kInMainPass = 1;  // the phase of recordInMainPass
}  // namespace

// The next slot (FrameSubmission::prepare), and every frame in flight waited for when a camera view other frames
// may read is about to go.
void RuntimeImpl::acquireSlot(const FrameInput& frame) {
    submission_->prepare();
    if (camera_->needsEviction(frame)) waitIdle();
}

void RuntimeImpl::waitIdle() {
    try {
        submission_->waitAll();
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidFrame, "waiting for the frames in flight");
    }
}

void RuntimeImpl::forgetCameraImage(VkImage image) {
    waitIdle();
    camera_->forget(image);
}

// The frame's steps are the list's hooks phase by phase: step = phase * kPassCount + index in the list.
double PassTimings::*RuntimeImpl::hookTiming(size_t step) const {
    const ListedPass& listed = passes_[step % kPassCount];
    const int phase = int(step / kPassCount);
    return phase == 0 ? listed.before : phase == kInMainPass ? listed.in_main_pass : listed.after;
}

// Records steps [first, end): each hook the list names (all_hooks: every hook, the no-ops too), the main pass
// (`variant`) begun before the first main-pass hook and ended after the last.
void RuntimeImpl::recordSteps(PassRecording& recording, size_t first, size_t end, MainPassVariant variant,
                              bool all_hooks) {
    bool in_main_pass = false;
    for (size_t step = first; step < end; ++step) {
        if (!all_hooks && hookTiming(step) == nullptr) continue;
        FramePass& pass = *passes_[step % kPassCount].pass;
        const int phase = int(step / kPassCount);
        if (phase == kInMainPass && !in_main_pass) {
            targets_->begin(recording.cmd, recording.slot, variant);
            in_main_pass = true;
        } else if (phase != kInMainPass && in_main_pass) {
            vkCmdEndRenderPass(recording.cmd);
            in_main_pass = false;
        }
        if (phase == 0) pass.recordBefore(recording);
        else if (phase == kInMainPass) pass.recordInMainPass(recording);
        else pass.recordAfter(recording);
    }
    if (in_main_pass) vkCmdEndRenderPass(recording.cmd);
}

FrameInfo RuntimeImpl::renderFrame(const FrameInput& frame, uint8_t* output_rgba8) {
    checkFrame(frame);
    FrameInfo info;
    try {
        acquireSlot(frame);
        info = prepareFrame(frame);
        const bool read_back = output_rgba8 != nullptr;
        submit(
            frame, read_back,
            [&](PassRecording& recording) {
                recordSteps(recording, 0, kPhaseCount * kPassCount, MainPassVariant::kWhole, true);
            },
            &frame.sync, false);
        if (read_back) submission_->readBack(output_rgba8);
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
    timings = PassTimings{};  // figures add up: two runs of hooks may count toward one (statistics: colour, sun)
    checkFrame(frame);
    FrameInfo info;
    try {
        waitIdle();  // every pass alone, with nothing else on the GPU
        acquireSlot(frame);
        info = prepareFrame(frame);
        // The main pass split into its variants: kFirst for the first run that draws in it, kLast for the last.
        constexpr size_t kSteps = kPhaseCount * kPassCount;
        size_t first_main = kSteps, last_main = 0;
        for (size_t step = kInMainPass * kPassCount; step < (kInMainPass + 1) * kPassCount; ++step)
            if (hookTiming(step) != nullptr) {
                first_main = std::min(first_main, step);
                last_main = step;
            }
        // Each run of hooks that count toward one figure alone in its own submission, waited for: lavapipe
        // writes timestamps only when graphics work is flushed (docs/design.md 5), so wall time around a fenced
        // submission is the honest per-pass figure. The read-back is always recorded (its figure is always
        // measured); the bytes are copied out only when asked for.
        for (size_t first = 0; first < kSteps;) {
            double PassTimings::*const figure = hookTiming(first);
            if (figure == nullptr) {
                ++first;
                continue;
            }
            size_t end = first + 1;
            while (end < kSteps && (hookTiming(end) == nullptr || hookTiming(end) == figure)) ++end;
            const bool has_first = first <= first_main && first_main < end;
            const bool has_last = first <= last_main && last_main < end;
            const MainPassVariant variant = has_first ? (has_last ? MainPassVariant::kWhole : MainPassVariant::kFirst)
                                                      : (has_last ? MainPassVariant::kLast : MainPassVariant::kMiddle);
            const Clock::time_point pass_start = Clock::now();
            submit(
                frame, true,
                [&](PassRecording& recording) { recordSteps(recording, first, end, variant, false); }, nullptr,
                true);
            timings.*figure += milliseconds(pass_start, Clock::now());
            first = end;
        }
        const Clock::time_point copy_start = Clock::now();
        if (output_rgba8 != nullptr) submission_->readBack(output_rgba8);
        timings.readback_ms += milliseconds(copy_start, Clock::now());
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidFrame, kRendering);
    }
    timings.total_ms = milliseconds(start, Clock::now());
    return info;
}

}  // namespace gusuku::runtime_detail

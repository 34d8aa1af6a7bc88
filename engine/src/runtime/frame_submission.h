#pragma once
// The frame's submission (docs/design.md 8): frames_in_flight slots, each with its command buffer, fence and
// host-visible read-back buffer. A frame takes the next slot (waiting on its fence only when the GPU still works
// on it), records into its pre-allocated command buffer, submits it with the app's semaphores and returns; only
// the host-bytes path waits, to read the composite back. A FramePass (frame_pass.h), last in the list: its
// recordAfter copies the composite for the host path. Private to gusuku_runtime.

#include <cstdint>
#include <vector>

#include "device_object.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_compute.h"

namespace gusuku::runtime_detail {

class MainTargets;

class FrameSubmission final : public FramePass {
public:
    FrameSubmission(const PassContext& context, const MainTargets& targets);

    /// Host side: the next slot, once the GPU is done with the frame that used it last (the one wait of the
    /// GPU-resident path, which blocks only when frames_in_flight frames are all still on the GPU).
    void prepare();
    uint32_t slot() const { return slot_; }            // the slot being recorded
    uint32_t lastSlot() const { return last_slot_; }   // the slot of the last frame submitted
    /// The slot's command buffer, reset and begun.
    VkCommandBuffer begin();
    /// Ends the slot's command buffer and submits it, with sync's semaphores when given.
    void submit(const FrameSync* sync);
    /// Waits for the slot's submission.
    void wait() { waitFor(slots_[slot_]); }
    void waitAll();
    /// Whether the slot's last submission has finished on the GPU (no wait: its fence's status).
    bool finished(uint32_t slot) const;
    void recordAfter(PassRecording& recording) override;
    /// Waits for the slot's frame and copies its composite (recorded with read_back) into output_rgba8.
    void readBack(uint8_t* output_rgba8);
    uint64_t memoryBytes() const;

private:
    struct Slot {
        VkCommandBuffer command_buffer = VK_NULL_HANDLE;  // freed with the pool
        Fence fence;
        bool in_flight = false;  // submitted and its fence not yet waited for
        GpuBuffer readback;      // host-visible RGBA8, the host-bytes path only
    };
    void waitFor(Slot& slot);

    const PassContext context_;
    const MainTargets& targets_;
    CommandPool pool_;
    std::vector<Slot> slots_;
    uint32_t slot_ = 0;
    uint32_t last_slot_ = 0;
};

}  // namespace gusuku::runtime_detail

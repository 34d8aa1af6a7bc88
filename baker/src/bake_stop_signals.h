#pragma once
// Ctrl-C (SIGINT) and SIGTERM for `gusuku-bake bake`: the process ends within kStopDeadlineSeconds of the first
// signal at any moment, and at once on a second.
// - The signals are blocked in every thread of the bake (the mask is set before the device, the image readers or
//   the driver start theirs, and threads inherit it) and taken by one thread of this object's own, which waits
//   for them with sigtimedwait. So a signal never lands in a thread busy inside the driver or a library call,
//   nothing runs in a signal handler's restricted context, and the same thread keeps the deadline.
// - Before the bake's first poll (setup: reading the model, the BVH, the charts, the pipelines, the geometry
//   files) nothing is traced, so nothing is lost by ending at once: the thread says so and exits 130.
// - Once tracing has begun the stop is cooperative: the bake sees it after the current dispatch (about 0.25 s,
//   gusuku_bake/dispatch_budget.h), checkpoints and returns.
// - After the bake, while the runtime pack is written (beginPacking), the bake set is complete and the pack is
//   written to a temporary folder first, so a stop ends at once and says how to write the pack again.
// - Should that take longer than kStopDeadlineSeconds (a slot's files being written, the adaptive plan), or should
//   a second signal come, the process ends then as a kill would: the checkpoints on disk, written at least every
//   2 s and atomically, still resume the bake.

#include <csignal>
#include <atomic>
#include <functional>
#include <string>
#include <thread>

namespace gusuku::bake_cli {

/// The cooperative stop's deadline. The promise (CHANGELOG, docs/baker.md) is an end within 1.5 s of the first
/// signal; this leaves half a second for the process's own teardown (unmapping a large site's memory under load).
inline constexpr double kStopDeadlineSeconds = 1.0;

class BakeStopSignals {
public:
    /// Blocks SIGINT and SIGTERM in the calling thread (and so in every thread it starts later) and starts the
    /// thread that takes them. Construct it before anything starts threads. output_dir names the checkpoint
    /// folder in the messages. One object at a time.
    explicit BakeStopSignals(const std::string& output_dir);
    /// Ends the signal thread and restores the calling thread's signal mask: a signal that came after the bake
    /// returned then has its default effect.
    ~BakeStopSignals();
    BakeStopSignals(const BakeStopSignals&) = delete;
    BakeStopSignals& operator=(const BakeStopSignals&) = delete;

    /// For BakeOptions::should_stop: true once a signal came. Its first call marks the start of tracing.
    std::function<bool()> poll();
    /// The bake set is written; from here until this object ends, a signal ends the process at once. Returns
    /// true when a stop came before (while the bake returned): the caller then ends without packing.
    bool beginPacking();
    /// What to print when beginPacking() returned true.
    const std::string& packingMessage() const { return packing_message_; }

private:
    void takeSignals();
    [[noreturn]] void writeAndExit(const std::string& message) const;

    enum class Phase : int { kSetup, kTracing, kPacking };

    std::string setup_message_;     ///< a stop before tracing: nothing was traced
    std::string packing_message_;   ///< a stop while the pack is written: the set is complete
    std::string deadline_message_;  ///< a stop that did not wait for the bake: the checkpoints hold the work
    std::string second_signal_message_;  ///< the same, at once on a second signal
    // A copy of stderr taken at construction: while an image is decoded, descriptor 2 points at a capture file
    // (image_read.cpp's StderrCapture, for libpng's text), and a message written there would be lost.
    int stderr_copy_ = -1;
    sigset_t stop_signals_{};
    sigset_t previous_mask_{};
    std::atomic<Phase> phase_{Phase::kSetup};
    std::atomic<bool> stop_requested_{false};
    std::atomic<bool> finished_{false};
    std::thread signal_thread_;
};

}  // namespace gusuku::bake_cli

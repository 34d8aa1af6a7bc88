#pragma once
// Ctrl-C (SIGINT) and SIGTERM for `gusuku-bake bake`: a stop that ends the bake within about a second on any site.
// - Before the bake's first poll (setup: reading the model, the BVH, the charts, the pipelines, the geometry
//   files) nothing is traced, so nothing is lost by ending at once: the handler says so and exits 130.
// - Once tracing has begun the stop is cooperative: the bake sees it after the current dispatch (about 0.25 s,
//   gusuku_bake/dispatch_budget.h), checkpoints and returns.
// - Should that take longer than kStopDeadlineSeconds (a slot's files being written, the adaptive plan, a second
//   signal), the process ends then as a kill would: the checkpoints on disk, written at least every 2 s and
//   atomically, still resume the bake.

#include <atomic>
#include <functional>
#include <string>
#include <thread>

namespace gusuku::bake_cli {

inline constexpr double kStopDeadlineSeconds = 1.5;

class BakeStopSignals {
public:
    /// Installs the handlers (one object at a time) and starts the deadline watch. output_dir names the
    /// checkpoint folder in the messages.
    explicit BakeStopSignals(const std::string& output_dir);
    /// Restores the default handlers and ends the watch.
    ~BakeStopSignals();
    BakeStopSignals(const BakeStopSignals&) = delete;
    BakeStopSignals& operator=(const BakeStopSignals&) = delete;

    /// For BakeOptions::should_stop: true once a signal came. Its first call marks the start of tracing.
    std::function<bool()> poll();

private:
    void watchDeadline();

    std::atomic<bool> finished_{false};
    std::thread watch_;
};

}  // namespace gusuku::bake_cli

#pragma once
// The bake's progress bar on stderr: fraction done, samples per point, rays per second, elapsed and time left.
// On a terminal it redraws one line; otherwise (CI logs) it prints a line every 10 %.

#include <chrono>
#include <cstdint>
#include <string>

namespace gusuku::bake {

class BakeProgress {
public:
    /// total_work: point-samples over the whole bake (points x samples, summed over sets and slots).
    explicit BakeProgress(double total_work, bool enabled = true);

    /// Work already done before this run (a resumed bake); it counts as done but not towards rays per second.
    void addResumedWork(double work);

    /// Reports progress inside a set: `label` names it ("sunny_0900 building"), samples_done/samples_total
    /// are per point, work_done the point-samples just finished, rays the rays they cost, trace_seconds the
    /// time they took on the device (what the time left is estimated from).
    void advance(const std::string& label, uint32_t samples_done, uint32_t samples_total, double work_done,
                 uint64_t rays, double trace_seconds);

    void finish();  ///< final line with totals

    uint64_t raysTraced() const { return rays_; }
    double resumedFraction() const { return resumed_work_ / total_work_; }
    double secondsElapsed() const;
    double raysPerSecond() const;
    /// Time left from measured throughput only: work left / (work traced / seconds spent tracing it). Setup
    /// (BVH build, pipeline compilation) and resumed work are not in the rate, so the first estimate is not
    /// inflated by them. NaN until something has been traced and timed.
    double secondsLeft() const;

private:
    void draw(bool final_line);

    double total_work_;
    double done_work_ = 0.0;
    double resumed_work_ = 0.0;
    double traced_work_ = 0.0;      ///< work this run traced itself
    double traced_seconds_ = 0.0;   ///< the time that took
    uint64_t rays_ = 0;
    bool enabled_;
    bool is_terminal_;
    int last_decile_ = -1;
    std::string label_;
    uint32_t samples_done_ = 0, samples_total_ = 0;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
};

/// "1:05" or "1:02:03"; "--" for an unknown (NaN or negative) duration.
std::string formatDuration(double seconds);

}  // namespace gusuku::bake

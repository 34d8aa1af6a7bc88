#pragma once
// How much work the bake's next dispatch takes, so that each lasts about a target time whatever the site: a
// stop (Ctrl-C, SIGTERM) is honoured between dispatches, and none should make it wait long. The measure is the
// cost of one point-sample (one path from one query point) from the dispatches before, carried across point
// sets: a cheap ground set followed by a building set of 100x its points is sized by cost per point, not by
// samples. Where even one sample over every point of a set costs more than the target, the pass is cut into
// point ranges (IrradianceTracer::addSampleToNextPoints).

#include <cstdint>

namespace gusuku::bake {

/// One dispatch: `samples` whole passes over every point (points == the set's point count), or one sample over
/// the next `points` points of a pass (samples == 1, points below the rest of the pass).
struct DispatchSize {
    uint32_t samples = 1;
    uint32_t points = 0;
};

/// A dispatch holds at least this many points (a range is never cut smaller, so that a tiny target does not
/// turn a pass into thousands of submissions): at lavapipe's 2 M rays/s about 10 ms.
inline constexpr uint32_t kMinDispatchPoints = 4096;
/// A dispatch is sized from the measured cost, but at most this many times the work of the one before, so
/// that one fast measurement (a set whose points mostly see the sky) does not size a long dispatch elsewhere.
inline constexpr double kMaxDispatchGrowth = 4.0;
/// Whole passes per dispatch at most (the bake's chunks before dispatches were sized by time).
inline constexpr uint32_t kMaxSamplesPerDispatch = 64;

class DispatchBudget {
public:
    /// target_seconds: the length each dispatch aims at (BakeOptions::target_chunk_seconds); > 0.
    explicit DispatchBudget(double target_seconds);

    /// The next dispatch of a set of point_count points (> 0) with `samples_left` (> 0) samples to go, of which
    /// the current pass has given its sample to points [0, points_with_next_sample) already. Before any
    /// measurement: one sample over kMinDispatchPoints points (the rest of the pass when fewer).
    DispatchSize next(uint32_t point_count, uint32_t points_with_next_sample, uint32_t samples_left) const;

    /// A dispatch of point_samples paths took `seconds`.
    void measured(double point_samples, double seconds);

    /// The measured cost of one point-sample in seconds (0 before the first measurement).
    double secondsPerPointSample() const { return seconds_per_point_sample_; }

private:
    double target_seconds_;
    double seconds_per_point_sample_ = 0.0;
    double last_point_samples_ = 0.0;
};

}  // namespace gusuku::bake

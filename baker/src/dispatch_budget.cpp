#include "gusuku_bake/dispatch_budget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gusuku::bake {

DispatchBudget::DispatchBudget(double target_seconds) : target_seconds_(target_seconds) {
    if (!(target_seconds > 0.0) || !std::isfinite(target_seconds))
        throw std::invalid_argument("DispatchBudget: target seconds must be positive, got " +
                                    std::to_string(target_seconds));
}

DispatchSize DispatchBudget::next(uint32_t point_count, uint32_t points_with_next_sample, uint32_t samples_left) const {
    if (point_count == 0 || samples_left == 0 || points_with_next_sample >= point_count)
        throw std::invalid_argument("DispatchBudget::next: needs points and samples left, and a pass not done");
    const uint32_t points_left_in_pass = point_count - points_with_next_sample;
    // Unmeasured: one sample over a small range (all of a small set), the bake's first dispatch before time sizes it.
    if (seconds_per_point_sample_ <= 0.0) return {1u, std::min(kMinDispatchPoints, points_left_in_pass)};
    const double wanted =
        std::min(target_seconds_ / seconds_per_point_sample_, last_point_samples_ * kMaxDispatchGrowth);
    // Whole passes only from a pass boundary, and only when one of them fits the target.
    if (points_with_next_sample == 0 && wanted >= double(point_count)) {
        const double passes = std::floor(wanted / double(point_count));
        return {uint32_t(std::clamp(passes, 1.0, double(std::min(samples_left, kMaxSamplesPerDispatch)))),
                point_count};
    }
    const double range = std::max(wanted, double(kMinDispatchPoints));
    return {1u, uint32_t(std::min(range, double(points_left_in_pass)))};
}

void DispatchBudget::measured(double point_samples, double seconds) {
    if (!(point_samples > 0.0)) return;
    seconds_per_point_sample_ = std::max(seconds, 1e-6) / point_samples;
    last_point_samples_ = point_samples;
}

}  // namespace gusuku::bake

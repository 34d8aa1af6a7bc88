#pragma once
// Percentiles of a sample, one definition for the runtime's helpers and the benchmark's metrics.

#include <vector>

namespace gusuku {

/// The `fraction` quantile (clamped to [0, 1]) of `values`, linearly interpolated between order statistics:
/// position fraction * (n - 1) in the sorted values. 0 for an empty sample. Sorts a copy: O(n log n).
double percentile(std::vector<double> values, double fraction);

}  // namespace gusuku

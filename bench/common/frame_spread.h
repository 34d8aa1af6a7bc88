#pragma once
// The summary of repeated timings the tools print: median and the 10th and 90th percentiles, so one slow frame
// on a shared machine moves neither the figure nor its spread much.

#include <vector>

namespace gusuku::bench_common {

struct Spread {
    double median = 0.0;
    double low = 0.0;   ///< 10th percentile
    double high = 0.0;  ///< 90th percentile
};

/// Nearest-rank percentiles (index round(fraction x (n - 1)) of the sorted values). Empty input: all 0.
Spread spreadOf(std::vector<double> values);

}  // namespace gusuku::bench_common

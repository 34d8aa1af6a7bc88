// Median and spread of timings (see frame_spread.h).

#include "frame_spread.h"

#include <algorithm>

namespace gusuku::bench_common {

Spread spreadOf(std::vector<double> values) {
    if (values.empty()) return {};
    std::sort(values.begin(), values.end());
    auto at = [&](double fraction) { return values[size_t(fraction * double(values.size() - 1) + 0.5)]; };
    return {at(0.5), at(0.1), at(0.9)};
}

}  // namespace gusuku::bench_common

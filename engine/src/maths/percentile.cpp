// Percentiles of a sample (see percentile.h).

#include "gusuku/maths/percentile.h"

#include <algorithm>
#include <cmath>

namespace gusuku {

double percentile(std::vector<double> values, double fraction) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double position = std::clamp(fraction, 0.0, 1.0) * double(values.size() - 1);
    const size_t below = size_t(std::floor(position));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - double(below)) * (values[above] - values[below]);
}

}  // namespace gusuku

// The bake set's range checks (gusuku/formats/bakeset_ranges.h), shared by both bake set readers.
#include "gusuku/formats/bakeset_ranges.h"

#include <cmath>
#include <cstdio>

namespace gusuku {
namespace {

std::string formatNumber(double value) {
    if (std::isnan(value)) return "NaN";
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string formatBound(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", value);
    return text;
}

}  // namespace

std::string describeBakeSetRange(const BakeSetRange& range) {
    return "[" + formatBound(range.minimum) + ", " + formatBound(range.maximum) + "]";
}

std::optional<std::string> bakeSetValueProblem(const BakeSetRange& range, double value) {
    const bool inside = value >= range.minimum && value <= range.maximum;  // false for NaN
    if (inside && !(range.whole_number && value != std::floor(value))) return std::nullopt;
    const std::string bounds = describeBakeSetRange(range) + " " + range.unit;
    if (!std::isfinite(value)) return formatNumber(value) + " is not a finite number in " + bounds;
    if (!inside) return formatNumber(value) + " is outside " + bounds;
    return formatNumber(value) + " is not a whole number";
}

std::optional<std::string> bakeSetDirectionProblem(const BakeSetRange& range, double x, double y, double z) {
    for (const double component : {x, y, z})
        if (std::optional<std::string> problem = bakeSetValueProblem(range, component)) return problem;
    if (!(range.length_tolerance > 0.0)) return std::nullopt;
    const double length = std::sqrt(x * x + y * y + z * z);
    if (std::fabs(length - 1.0) <= range.length_tolerance) return std::nullopt;
    return "(" + formatNumber(x) + ", " + formatNumber(y) + ", " + formatNumber(z) + ") has length " +
           formatNumber(length) + ", not 1";
}

std::optional<BakeSetTexelProblem> findBakeSetTexelProblem(const BakeSetImage& image,
                                                           std::initializer_list<BakeSetRange> ranges) {
    static const char kChannel[4] = {'R', 'G', 'B', 'A'};
    const size_t texels = image.rgba.size() / 4;
    const size_t width = size_t(image.width > 0 ? image.width : 1);
    for (size_t texel = 0; texel < texels; ++texel) {
        const float* rgba = image.rgba.data() + texel * 4;
        // Named only on failure: building the text for every texel would cost more than the checks.
        const auto where = [&] {
            return "texel (" + std::to_string(texel % width) + ", " + std::to_string(texel / width) + ")";
        };
        for (const BakeSetRange& range : ranges) {
            for (int channel = range.first_channel; channel < range.first_channel + range.channels; ++channel)
                if (std::optional<std::string> problem = bakeSetValueProblem(range, rgba[channel]))
                    return BakeSetTexelProblem{where() + " channel " + kChannel[channel],
                                               *problem + " (" + range.field + ")"};
            if (range.length_tolerance > 0.0 && range.channels == 3) {
                const int c = range.first_channel;
                if (std::optional<std::string> problem =
                        bakeSetDirectionProblem(range, rgba[c], rgba[c + 1], rgba[c + 2]))
                    return BakeSetTexelProblem{where(), *problem + " (" + range.field + ")"};
            }
        }
    }
    return std::nullopt;
}

}  // namespace gusuku

// The CPU's mip chain of an sRGB texture, box-filtered in linear light (see srgb_mip_chain.h).

#include "gusuku/maths/srgb_mip_chain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "gusuku/maths/colour.h"

namespace gusuku {
namespace {

// One destination texel's footprint along an axis: the source texels it covers and the fraction of each.
struct Footprint {
    uint32_t first = 0;
    std::vector<double> weights;  // sum to 1
};

// The footprints of `destination` texels over `source` along one axis: texel d covers [d s / n, (d + 1) s / n).
std::vector<Footprint> footprintsOf(uint32_t source, uint32_t destination) {
    std::vector<Footprint> footprints(destination);
    const double ratio = double(source) / double(destination);
    for (uint32_t texel = 0; texel < destination; ++texel) {
        const double low = texel * ratio, high = (texel + 1) * ratio;
        Footprint& footprint = footprints[texel];
        footprint.first = uint32_t(std::floor(low));
        for (uint32_t covered = footprint.first; covered < source && double(covered) < high; ++covered) {
            const double overlap = std::min(high, covered + 1.0) - std::max(low, double(covered));
            footprint.weights.push_back(overlap / ratio);
        }
    }
    return footprints;
}

// A level in linear light: RGBA per texel, RGB decoded, alpha as stored; for an alpha-masked texture also RGB
// times alpha (premultiplied), whose box filter over alpha's is the colour of the opaque part of a footprint.
struct LinearLevel {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
    std::vector<float> premultiplied_rgb;  ///< 3 per texel; empty when the colour is the plain box filter's
};

LinearLevel halved(const LinearLevel& above) {
    LinearLevel level;
    level.width = std::max(1u, above.width / 2);
    level.height = std::max(1u, above.height / 2);
    level.rgba.assign(size_t(level.width) * level.height * 4, 0.0f);
    const bool premultiplied = !above.premultiplied_rgb.empty();
    if (premultiplied) level.premultiplied_rgb.assign(size_t(level.width) * level.height * 3, 0.0f);
    const std::vector<Footprint> columns = footprintsOf(above.width, level.width);
    const std::vector<Footprint> rows = footprintsOf(above.height, level.height);
    for (uint32_t y = 0; y < level.height; ++y)
        for (uint32_t x = 0; x < level.width; ++x) {
            std::array<double, 4> sum{};
            std::array<double, 3> premultiplied_sum{};
            for (size_t row = 0; row < rows[y].weights.size(); ++row)
                for (size_t column = 0; column < columns[x].weights.size(); ++column) {
                    const double weight = rows[y].weights[row] * columns[x].weights[column];
                    const size_t source_texel = size_t(rows[y].first + row) * above.width + columns[x].first + column;
                    for (int channel = 0; channel < 4; ++channel)
                        sum[channel] += weight * above.rgba[source_texel * 4 + channel];
                    if (premultiplied)
                        for (int channel = 0; channel < 3; ++channel)
                            premultiplied_sum[channel] += weight * above.premultiplied_rgb[source_texel * 3 + channel];
                }
            const size_t texel = size_t(y) * level.width + x;
            for (int channel = 0; channel < 4; ++channel) level.rgba[texel * 4 + channel] = float(sum[channel]);
            if (!premultiplied) continue;
            for (int channel = 0; channel < 3; ++channel) {
                level.premultiplied_rgb[texel * 3 + channel] = float(premultiplied_sum[channel]);
                // The colour of the footprint's opaque part; a footprint with no opacity keeps the box filter's.
                if (sum[3] > 0.0) level.rgba[texel * 4 + channel] = float(premultiplied_sum[channel] / sum[3]);
            }
        }
    return level;
}

uint8_t toByte(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

// The factor by which a level's (float) alpha is scaled so that the share of its texels at or above
// `coverage_alpha`, once stored as bytes, is the nearest to `target`: the k-th largest alpha (k the target's texel
// count) is lifted to a quarter byte under the smallest passing byte, so that it rounds onto that byte and the
// alphas below it round under it (unless within a fraction of a byte of it). 1 when nothing is to pass or the
// k-th alpha is 0 (a transparent level stays transparent).
float coverageScale(const LinearLevel& level, float coverage_alpha, double target) {
    std::vector<float> alphas;
    alphas.reserve(level.rgba.size() / 4);
    for (size_t index = 3; index < level.rgba.size(); index += 4) alphas.push_back(level.rgba[index]);
    const size_t passing = size_t(std::llround(target * double(alphas.size())));
    if (passing == 0 || alphas.empty()) return 1.0f;
    std::nth_element(alphas.begin(), alphas.begin() + (passing - 1), alphas.end(), std::greater<float>());
    const float kth_largest = alphas[passing - 1];
    if (!(kth_largest > 0.0f)) return 1.0f;
    // The smallest byte that passes as alphaCoverage (and the shader's UNORM read) compares it.
    int passing_byte = 255;
    while (passing_byte > 0 && (passing_byte - 1) / 255.0f >= coverage_alpha) --passing_byte;
    return (float(passing_byte) - 0.25f) / 255.0f / kth_largest;
}

}  // namespace

double alphaCoverage(const uint8_t* rgba8, size_t count, float coverage_alpha) {
    if (count == 0) return 0.0;
    size_t covered = 0;
    for (size_t texel = 0; texel < count; ++texel) covered += rgba8[texel * 4 + 3] / 255.0f >= coverage_alpha;
    return double(covered) / double(count);
}

std::vector<std::vector<uint8_t>> boxFilteredSrgbMipLevels(const uint8_t* rgba8, uint32_t width, uint32_t height,
                                                            uint32_t level_count, float coverage_alpha) {
    std::vector<std::vector<uint8_t>> levels;
    if (level_count <= 1 || width == 0 || height == 0) return levels;
    std::array<float, 256> decoded{};
    for (int code = 0; code < 256; ++code) decoded[code] = srgbDecode(code / 255.0f);
    LinearLevel level{width, height, std::vector<float>(size_t(width) * height * 4)};
    for (size_t index = 0; index < level.rgba.size(); ++index)
        level.rgba[index] = index % 4 == 3 ? rgba8[index] / 255.0f : decoded[rgba8[index]];
    const bool preserve_coverage = keepsAlphaCoverage(coverage_alpha);
    if (preserve_coverage) {
        // A masked texture's holes usually hold black (or any) RGB that no drawn pixel shows: averaged in
        // unweighted, they darkened a foliage card's leaves the farther it was (the shared house's vine and tree
        // 9 % under the truth), while the truth's pixel averages the leaves' colour alone.
        level.premultiplied_rgb.resize(size_t(width) * height * 3);
        for (size_t texel = 0; texel < size_t(width) * height; ++texel)
            for (int channel = 0; channel < 3; ++channel)
                level.premultiplied_rgb[texel * 3 + channel] = level.rgba[texel * 4 + channel] * level.rgba[texel * 4 + 3];
    }
    const double level0_coverage =
        preserve_coverage ? alphaCoverage(rgba8, size_t(width) * height, coverage_alpha) : 0.0;
    for (uint32_t next = 1; next < level_count; ++next) {
        level = halved(level);
        std::vector<uint8_t> bytes(level.rgba.size());
        for (size_t index = 0; index < bytes.size(); ++index)
            bytes[index] = toByte(index % 4 == 3 ? level.rgba[index] : srgbEncode(level.rgba[index]));
        if (preserve_coverage) {
            // Scaled from the filtered float alpha, so that the level below is filtered from the unscaled one
            // (each level keeps level 0's coverage, not its parent's rounding).
            const float scale = coverageScale(level, coverage_alpha, level0_coverage);
            for (size_t index = 3; index < bytes.size(); index += 4)
                bytes[index] = toByte(std::min(1.0f, level.rgba[index] * scale));
        }
        levels.push_back(std::move(bytes));
    }
    return levels;
}

}  // namespace gusuku

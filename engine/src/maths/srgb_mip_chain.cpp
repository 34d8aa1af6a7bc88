// The CPU's mip chain of an sRGB texture, box-filtered in linear light (see srgb_mip_chain.h).

#include "gusuku/maths/srgb_mip_chain.h"

#include <algorithm>
#include <array>
#include <cmath>

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

// A level in linear light: RGBA per texel, RGB decoded, alpha as stored.
struct LinearLevel {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};

LinearLevel halved(const LinearLevel& above) {
    LinearLevel level;
    level.width = std::max(1u, above.width / 2);
    level.height = std::max(1u, above.height / 2);
    level.rgba.assign(size_t(level.width) * level.height * 4, 0.0f);
    const std::vector<Footprint> columns = footprintsOf(above.width, level.width);
    const std::vector<Footprint> rows = footprintsOf(above.height, level.height);
    for (uint32_t y = 0; y < level.height; ++y)
        for (uint32_t x = 0; x < level.width; ++x) {
            std::array<double, 4> sum{};
            for (size_t row = 0; row < rows[y].weights.size(); ++row)
                for (size_t column = 0; column < columns[x].weights.size(); ++column) {
                    const double weight = rows[y].weights[row] * columns[x].weights[column];
                    const size_t source =
                        (size_t(rows[y].first + row) * above.width + columns[x].first + column) * 4;
                    for (int channel = 0; channel < 4; ++channel) sum[channel] += weight * above.rgba[source + channel];
                }
            for (int channel = 0; channel < 4; ++channel)
                level.rgba[(size_t(y) * level.width + x) * 4 + channel] = float(sum[channel]);
        }
    return level;
}

uint8_t toByte(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

std::vector<std::vector<uint8_t>> boxFilteredSrgbMipLevels(const uint8_t* rgba8, uint32_t width, uint32_t height,
                                                            uint32_t level_count) {
    std::vector<std::vector<uint8_t>> levels;
    if (level_count <= 1 || width == 0 || height == 0) return levels;
    std::array<float, 256> decoded{};
    for (int code = 0; code < 256; ++code) decoded[code] = srgbDecode(code / 255.0f);
    LinearLevel level{width, height, std::vector<float>(size_t(width) * height * 4)};
    for (size_t index = 0; index < level.rgba.size(); ++index)
        level.rgba[index] = index % 4 == 3 ? rgba8[index] / 255.0f : decoded[rgba8[index]];
    for (uint32_t next = 1; next < level_count; ++next) {
        level = halved(level);
        std::vector<uint8_t> bytes(level.rgba.size());
        for (size_t index = 0; index < bytes.size(); ++index)
            bytes[index] = toByte(index % 4 == 3 ? level.rgba[index] : srgbEncode(level.rgba[index]));
        levels.push_back(std::move(bytes));
    }
    return levels;
}

}  // namespace gusuku

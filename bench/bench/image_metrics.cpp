// gusuku-bench's accuracy metrics (see image_metrics.h).

#include "image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gusuku/maths/colour.h"

namespace gusuku::bench {
namespace {

void requireSameSize(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth) {
    if (frame.size() != truth.size() || frame.size() % 4 != 0)
        throw std::invalid_argument("frames of different sizes (" + std::to_string(frame.size()) + " and " +
                                    std::to_string(truth.size()) + " bytes) cannot be compared");
}

void requireMaskSize(const std::vector<uint8_t>& mask, size_t pixel_count) {
    if (!mask.empty() && mask.size() != pixel_count)
        throw std::invalid_argument("a mask of " + std::to_string(mask.size()) + " pixels for a frame of " +
                                    std::to_string(pixel_count));
}

}  // namespace

glm::dvec3 labOfSrgb8(uint8_t red, uint8_t green, uint8_t blue) {
    const glm::dvec3 linear(srgbDecode(double(red) / 255.0), srgbDecode(double(green) / 255.0),
                            srgbDecode(double(blue) / 255.0));
    return labFromLinearRec709(linear);
}

std::vector<double> ciede2000PerPixel(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth) {
    requireSameSize(frame, truth);
    const size_t pixel_count = frame.size() / 4;
    std::vector<double> differences(pixel_count);
    for (size_t pixel = 0; pixel < pixel_count; ++pixel) {
        const uint8_t* a = frame.data() + 4 * pixel;
        const uint8_t* b = truth.data() + 4 * pixel;
        differences[pixel] = (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
                                 ? 0.0
                                 : ciede2000(labOfSrgb8(a[0], a[1], a[2]), labOfSrgb8(b[0], b[1], b[2]));
    }
    return differences;
}

double psnrDb(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth, const std::vector<uint8_t>& mask) {
    requireSameSize(frame, truth);
    requireMaskSize(mask, frame.size() / 4);
    double squared_sum = 0.0;
    size_t sample_count = 0;
    for (size_t pixel = 0; pixel < frame.size() / 4; ++pixel) {
        if (!mask.empty() && !mask[pixel]) continue;
        for (size_t channel = 0; channel < 3; ++channel) {
            const double difference = double(frame[4 * pixel + channel]) - double(truth[4 * pixel + channel]);
            squared_sum += difference * difference;
        }
        sample_count += 3;
    }
    if (sample_count == 0 || squared_sum == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(255.0 * 255.0 / (squared_sum / double(sample_count)));
}

ErrorSummary summariseDifferences(const std::vector<double>& de00_per_pixel, const std::vector<uint8_t>& mask) {
    requireMaskSize(mask, de00_per_pixel.size());
    std::vector<double> selected;
    selected.reserve(de00_per_pixel.size());
    double sum = 0.0;
    for (size_t pixel = 0; pixel < de00_per_pixel.size(); ++pixel)
        if (mask.empty() || mask[pixel]) {
            selected.push_back(de00_per_pixel[pixel]);
            sum += de00_per_pixel[pixel];
        }
    ErrorSummary summary;
    summary.pixel_count = selected.size();
    summary.mean_de00 = selected.empty() ? 0.0 : sum / double(selected.size());
    summary.p95_de00 = percentile(std::move(selected), 0.95);
    return summary;
}

ErrorSummary summariseError(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                            const std::vector<uint8_t>& mask) {
    ErrorSummary summary = summariseDifferences(ciede2000PerPixel(frame, truth), mask);
    summary.psnr_db = psnrDb(frame, truth, mask);
    return summary;
}

std::vector<uint8_t> changedPixelMask(const std::vector<uint8_t>& with_building,
                                      const std::vector<uint8_t>& without_building, double threshold_de00) {
    const std::vector<double> differences = ciede2000PerPixel(with_building, without_building);
    std::vector<uint8_t> mask(differences.size());
    for (size_t pixel = 0; pixel < differences.size(); ++pixel) mask[pixel] = differences[pixel] > threshold_de00;
    return mask;
}

std::vector<uint8_t> lowPass3x3Linear(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height) {
    if (rgba8.size() != size_t(width) * height * 4)
        throw std::invalid_argument("lowPass3x3Linear: the frame is not width x height RGBA8");
    std::vector<double> linear(size_t(width) * height * 3);
    for (size_t pixel = 0; pixel < size_t(width) * height; ++pixel)
        for (int channel = 0; channel < 3; ++channel)
            linear[pixel * 3 + channel] = srgbDecode(double(rgba8[pixel * 4 + channel]) / 255.0);
    std::vector<uint8_t> filtered(rgba8);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            double sum[3] = {0.0, 0.0, 0.0};
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int64_t sx = int64_t(x) + dx, sy = int64_t(y) + dy;
                    if (sx < 0 || sy < 0 || sx >= int64_t(width) || sy >= int64_t(height)) continue;
                    const size_t at = (size_t(sy) * width + size_t(sx)) * 3;
                    for (int channel = 0; channel < 3; ++channel) sum[channel] += linear[at + channel];
                    ++count;
                }
            for (int channel = 0; channel < 3; ++channel)
                filtered[(size_t(y) * width + x) * 4 + channel] =
                    uint8_t(std::lround(255.0 * std::clamp(srgbEncode(sum[channel] / count), 0.0, 1.0)));
        }
    return filtered;
}

double withoutTruthNoise(double mean_de00, double noise_between_seeds_de00) {
    return std::sqrt(std::max(0.0, mean_de00 * mean_de00 - 0.5 * noise_between_seeds_de00 * noise_between_seeds_de00));
}

}  // namespace gusuku::bench

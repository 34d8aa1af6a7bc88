// CPU reference of the runtime's colour match (gusuku/maths/colour_match.h): camera statistics, their smoothing and
// the transfer, in double, with the same steps as the GPU kernels and colour_match.glsl.
#include "gusuku/maths/colour_match.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

namespace gusuku {

ColourStatisticsGrid colourStatisticsGrid(uint32_t width, uint32_t height, uint32_t stride) {
    if (width == 0 || height == 0)
        throw std::invalid_argument("colour statistics: frame size: " + std::to_string(width) + " x " +
                                    std::to_string(height) + " has no pixels");
    if (stride == 0 || stride > width || stride > height)
        throw std::invalid_argument("colour statistics: statistics_stride: " + std::to_string(stride) +
                                    " must be in [1, min(width, height)]");
    ColourStatisticsGrid grid;
    grid.stride = stride;
    grid.offset = stride / 2;
    grid.samples_x = (width - grid.offset + stride - 1) / stride;
    grid.samples_y = (height - grid.offset + stride - 1) / stride;
    return grid;
}

CameraColourStatistics measureCameraColourStatistics(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
                                                     uint32_t stride) {
    const ColourStatisticsGrid grid = colourStatisticsGrid(width, height, stride);
    if (rgba8.size() < size_t(width) * height * 4)
        throw std::invalid_argument("colour statistics: camera image: " + std::to_string(rgba8.size()) +
                                    " bytes for " + std::to_string(width) + " x " + std::to_string(height));
    CameraColourStatistics statistics;
    // Two passes over the samples: the mean, then squared deviations from it.
    auto forEachValidSample = [&](auto&& visit) {
        for (uint32_t j = 0; j < grid.samples_y; ++j) {
            for (uint32_t i = 0; i < grid.samples_x; ++i) {
                const size_t x = grid.offset + size_t(i) * stride, y = grid.offset + size_t(j) * stride;
                const uint8_t* pixel = &rgba8[(y * width + x) * 4];
                if (isClippedCameraPixel(pixel[0], pixel[1], pixel[2])) continue;
                const glm::dvec3 encoded(pixel[0] / 255.0, pixel[1] / 255.0, pixel[2] / 255.0);
                visit(labFromLinearRec709(glm::dvec3(srgbDecode(encoded.r), srgbDecode(encoded.g),
                                                     srgbDecode(encoded.b))));
            }
        }
    };
    glm::dvec3 sum(0.0);
    forEachValidSample([&](const glm::dvec3& lab) {
        sum += lab;
        ++statistics.valid_samples;
    });
    statistics.clipped_samples = grid.sampleCount() - statistics.valid_samples;
    if (statistics.valid_samples == 0) return statistics;
    statistics.lab_mean = sum / double(statistics.valid_samples);
    glm::dvec3 squared_deviation(0.0);
    forEachValidSample([&](const glm::dvec3& lab) {
        const glm::dvec3 deviation = lab - statistics.lab_mean;
        squared_deviation += deviation * deviation;
    });
    statistics.lab_sigma = glm::sqrt(squared_deviation / double(statistics.valid_samples));
    return statistics;
}

uint32_t colourStatisticsMinValidSamples(uint64_t sample_count) {
    const double fraction = std::ceil(kColourStatisticsMinValidFraction * double(sample_count));
    const uint64_t needed = std::max<uint64_t>(kColourStatisticsMinValidSamplesFloor, uint64_t(fraction));
    return uint32_t(std::min<uint64_t>(needed, std::max<uint64_t>(sample_count, 1)));
}

double colourStatisticsSmoothingWeight(double smoothing_frames) {
    return smoothing_frames >= 1.0 ? 1.0 / smoothing_frames : 1.0;  // NaN compares false: 1
}

SmoothedColourStatistics smoothColourStatistics(const SmoothedColourStatistics& previous,
                                                const CameraColourStatistics& frame, uint32_t min_valid_samples,
                                                double smoothing_weight, bool reset) {
    SmoothedColourStatistics next = reset ? SmoothedColourStatistics{} : previous;
    const bool accepted = frame.valid_samples > 0 && frame.valid_samples >= min_valid_samples;
    if (!accepted) return next;
    const glm::dvec3 frame_variance = frame.lab_sigma * frame.lab_sigma;
    if (!next.valid) {
        next.lab_mean = frame.lab_mean;
        next.lab_variance = frame_variance;
    } else {
        next.lab_mean += smoothing_weight * (frame.lab_mean - next.lab_mean);
        next.lab_variance += smoothing_weight * (frame_variance - next.lab_variance);
    }
    next.valid = true;
    ++next.frames_accepted;
    return next;
}

LabStatistics blendLabStatistics(ConstSpan<LabStatistics> slots, ConstSpan<float> weights) {
    LabStatistics blended;
    if (slots.empty()) return blended;
    if (weights.size() != slots.size())
        throw std::invalid_argument("colour statistics: slot weights: " + std::to_string(weights.size()) +
                                    " weights for " + std::to_string(slots.size()) + " slots");
    double total = 0.0;
    for (float weight : weights) total += std::max(0.0, double(weight));
    glm::dvec3 mean(0.0), sigma(0.0);
    for (size_t s = 0; s < slots.size(); ++s) {
        const double weight = total > 0.0 ? std::max(0.0, double(weights[s])) / total : 1.0 / double(slots.size());
        mean += weight * glm::dvec3(slots[s].mean);
        sigma += weight * glm::dvec3(slots[s].standard_deviation);
    }
    blended.mean = glm::vec3(mean);
    blended.standard_deviation = glm::vec3(sigma);
    return blended;
}

namespace {

bool transferActive(const ColourMatchParameters& parameters) {
    if (parameters.mode == ColourMatchMode::kGround) return parameters.ground.valid;
    return parameters.mode != ColourMatchMode::kOff && parameters.target.valid;
}

bool inUnitCube(const glm::dvec3& rgb, double tolerance) {
    for (int c = 0; c < 3; ++c)
        if (!(rgb[c] >= -tolerance && rgb[c] <= 1.0 + tolerance)) return false;
    return true;
}

}  // namespace

glm::dvec3 colourMatchTransferLab(const glm::dvec3& lab, const ColourMatchParameters& parameters) {
    if (!transferActive(parameters) || parameters.mode == ColourMatchMode::kGround) return lab;  // kGround: not Lab
    LabStatistics target;
    target.mean = glm::vec3(parameters.target.lab_mean);
    const glm::dvec3 variance = glm::max(parameters.target.lab_variance, glm::dvec3(0.0));
    target.standard_deviation = glm::vec3(glm::sqrt(variance));
    // The gains exactly as the GPU computes them (float, colour.h's floor and clamp); the rest in double.
    const glm::dvec3 gain(makeLabTransfer(parameters.source, target, parameters.gain_limit).gain);
    const glm::dvec3 source_mean(parameters.source.mean);
    const glm::dvec3 target_mean(target.mean);
    if (parameters.mode == ColourMatchMode::kReinhard) return (lab - source_mean) * gain + target_mean;
    // kPreserve: L moved like kReinhard; a, b keep their spread and take a bounded white-balance shift.
    double shift_a = target_mean.y - source_mean.y, shift_b = target_mean.z - source_mean.z;
    const double shift_length = std::sqrt(shift_a * shift_a + shift_b * shift_b);
    if (shift_length > kColourMatchMaxWhiteBalanceShift) {
        const double shorten = kColourMatchMaxWhiteBalanceShift / shift_length;
        shift_a *= shorten;
        shift_b *= shorten;
    }
    return {(lab.x - source_mean.x) * gain.x + target_mean.x, lab.y + shift_a, lab.z + shift_b};
}

glm::dvec3 colourMatchChromaIntoGamut(const glm::dvec3& lab) {
    const double lightness = std::clamp(lab.x, 0.0, 100.0);
    auto withChromaScale = [&](double scale) { return glm::dvec3(lightness, lab.y * scale, lab.z * scale); };
    if (inUnitCube(linearRec709FromLab(withChromaScale(1.0)), kColourMatchGamutTolerance))
        return withChromaScale(1.0);
    double inside = 0.0, outside = 1.0;  // scale 0 is grey of that L: always inside
    for (int step = 0; step < kColourMatchGamutSteps; ++step) {
        const double middle = 0.5 * (inside + outside);
        if (inUnitCube(linearRec709FromLab(withChromaScale(middle)), kColourMatchGamutTolerance))
            inside = middle;
        else
            outside = middle;
    }
    return withChromaScale(inside);
}

glm::dvec3 applyColourMatch(const glm::dvec3& linear_rgb, const ColourMatchParameters& parameters) {
    glm::dvec3 rgb;
    for (int c = 0; c < 3; ++c)
        rgb[c] = std::isnan(linear_rgb[c]) ? 0.0 : std::clamp(linear_rgb[c], 0.0, kColourMatchMaxLinear);
    if (!transferActive(parameters)) return glm::clamp(rgb, glm::dvec3(0.0), glm::dvec3(1.0));
    // kGround: a von Kries gain on the exposed linear colour, as the GPU does it (float gain, double product).
    if (parameters.mode == ColourMatchMode::kGround)
        return glm::clamp(rgb * glm::dvec3(glm::vec3(parameters.ground.gain)), glm::dvec3(0.0), glm::dvec3(1.0));
    glm::dvec3 lab = colourMatchTransferLab(labFromLinearRec709(rgb), parameters);
    lab.x = std::clamp(lab.x, 0.0, 100.0);
    if (parameters.mode == ColourMatchMode::kPreserve) lab = colourMatchChromaIntoGamut(lab);
    return glm::clamp(linearRec709FromLab(lab), glm::dvec3(0.0), glm::dvec3(1.0));
}

}  // namespace gusuku

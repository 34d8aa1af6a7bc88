// Reinhard's transfer of Lab statistics (gusuku/maths/colour.h, docs/design.md 4): measuring mu and sigma, and turning two
// sets of them into per-channel gains with the documented floor and clamp. Applying it is one line in the
// header and in shaders/include/colour.glsl.
#include <algorithm>
#include <cmath>

#include "gusuku/maths/colour.h"

namespace gusuku {

LabStatistics measureLabStatistics(ConstSpan<glm::vec3> lab_pixels) {
    // Two passes in double: the mean first, then squared deviations from it (no cancellation from sum x^2).
    glm::dvec3 sum(0.0);
    size_t count = 0;
    auto isFinite = [](const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
    for (const glm::vec3& pixel : lab_pixels) {
        if (!isFinite(pixel)) continue;
        sum += glm::dvec3(pixel);
        ++count;
    }
    LabStatistics statistics;
    if (count == 0) return statistics;
    const glm::dvec3 mean = sum / double(count);
    glm::dvec3 squared_deviation(0.0);
    for (const glm::vec3& pixel : lab_pixels) {
        if (!isFinite(pixel)) continue;
        const glm::dvec3 deviation = glm::dvec3(pixel) - mean;
        squared_deviation += deviation * deviation;
    }
    const glm::dvec3 variance = squared_deviation / double(count);
    statistics.mean = glm::vec3(mean);
    statistics.standard_deviation =
        glm::vec3(float(std::sqrt(variance.x)), float(std::sqrt(variance.y)), float(std::sqrt(variance.z)));
    return statistics;
}

LabTransfer makeLabTransfer(const LabStatistics& source, const LabStatistics& target, float max_gain) {
    const float upper = max_gain >= 1.0f ? max_gain : 1.0f;  // below 1 (or NaN): a pure shift of means
    const float lower = 1.0f / upper;  // 0 for +infinity: no lower clamp
    LabTransfer transfer;
    transfer.source_mean = source.mean;
    transfer.target_mean = target.mean;
    for (int c = 0; c < 3; ++c) {
        const float source_sigma = std::max(source.standard_deviation[c], kLabTransferMinSourceSigma);
        transfer.gain[c] = std::clamp(target.standard_deviation[c] / source_sigma, lower, upper);
    }
    return transfer;
}

}  // namespace gusuku

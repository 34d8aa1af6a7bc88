// Cloud cover from the camera frame (see weather_estimate.h).

#include "gusuku/maths/weather_estimate.h"

#include <algorithm>
#include <cmath>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/percentile.h"

namespace gusuku {
namespace {

float clearness(float value, float overcast_value, float clear_value) {
    return std::clamp((value - overcast_value) / (clear_value - overcast_value), 0.0f, 1.0f);
}

}  // namespace

CloudEstimate estimateCloudCover(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height) {
    if (rgba8.size() != size_t(width) * height * 4) return estimateCloudCover(nullptr, 0, 0);
    return estimateCloudCover(rgba8.data(), width, height);
}

CloudEstimate estimateCloudCover(const uint8_t* rgba8, uint32_t width, uint32_t height) {
    CloudEstimate estimate;
    estimate.cloud_cover = 1.0f;
    if (rgba8 == nullptr || width < 2 || height < 8) return estimate;

    std::vector<glm::vec3> linear(size_t(width) * height);
    std::vector<double> luminance(linear.size());
    for (size_t pixel = 0; pixel < linear.size(); ++pixel) {
        const uint8_t* bytes = rgba8 + 4 * pixel;
        linear[pixel] = srgbDecode(glm::vec3(bytes[0], bytes[1], bytes[2]) / 255.0f);
        luminance[pixel] = luminanceRec709(glm::dvec3(linear[pixel]));
    }
    if (*std::max_element(luminance.begin(), luminance.end()) <= 0.0) return estimate;

    // Shadows: the lower half's luminance spread, floored at 1/255 of linear so black pixels stay finite.
    const std::vector<double> lower(luminance.begin() + ptrdiff_t(size_t(height / 2) * width), luminance.end());
    constexpr double kFloor = 1.0 / 255.0;
    estimate.shadow_contrast =
        float(std::log(std::max(percentile(lower, 0.9), kFloor) / std::max(percentile(lower, 0.1), kFloor)));

    // Sky: how much bluer the top rows are than the ground, ln(B / R) at the top eighth's 75th percentile (so a sky
    // that fills only part of those rows still counts) minus its median over the lower half. A white balance
    // multiplies B / R everywhere by one factor, so it cancels in the difference: a warm or cool camera reads the
    // same sky. Channels floored at 1/255 of linear, so black pixels stay finite.
    const auto logBlueOverRed = [&](const glm::vec3& rgb) {
        return std::log(std::max(double(rgb.b), kFloor) / std::max(double(rgb.r), kFloor));
    };
    std::vector<double> sky_blueness, ground_blueness;
    for (size_t pixel = 0; pixel < size_t(std::max(1u, height / 8)) * width; ++pixel)
        sky_blueness.push_back(logBlueOverRed(linear[pixel]));
    for (size_t pixel = size_t(height / 2) * width; pixel < linear.size(); ++pixel)
        ground_blueness.push_back(logBlueOverRed(linear[pixel]));
    estimate.sky_blueness = float(percentile(sky_blueness, 0.75) - percentile(ground_blueness, 0.5));

    // The sky cue decides when sky is in view (the top eighth's median luminance above the lower half's: a sky is
    // brighter than the ground under it in any weather); without sky, the shadow cue is all there is. The shadow
    // cue is the weaker one (the bench measured it not even monotone in cover at the sample's 10:30), so it is not
    // averaged in when the sky can answer.
    std::vector<double> sky_luminance(luminance.begin(), luminance.begin() + ptrdiff_t(size_t(std::max(1u, height / 8)) * width));
    estimate.sky_in_view = percentile(sky_luminance, 0.5) > percentile(lower, 0.5);
    const float clear = estimate.sky_in_view
                            ? clearness(estimate.sky_blueness, kOvercastSkyBlueness, kClearSkyBlueness)
                            : clearness(estimate.shadow_contrast, kOvercastShadowContrast, kClearShadowContrast);
    estimate.cloud_cover = 1.0f - clear;
    return estimate;
}

}  // namespace gusuku

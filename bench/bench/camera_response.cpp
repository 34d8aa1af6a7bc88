// A camera's response (see camera_response.h).

#include "camera_response.h"

#include <algorithm>
#include <cmath>

#include "gusuku/maths/colour.h"

namespace gusuku::bench {

std::vector<CameraResponse> benchCameraResponses() {
    return {
        {"neutral", 1.0f, glm::vec3(1.0f), ToneCurve::kLinear},
        {"warm_filmic", 1.0f, glm::vec3(1.15f, 1.0f, 0.8f), ToneCurve::kFilmic},
        {"cool_contrast", 0.8f, glm::vec3(0.85f, 1.0f, 1.2f), ToneCurve::kContrast},
    };
}

float applyToneCurve(ToneCurve curve, float linear) {
    const float x = std::max(linear, 0.0f);
    switch (curve) {
        case ToneCurve::kLinear: return x;
        case ToneCurve::kFilmic: return 1.6f * x * (1.0f + 0.25f * x) / (1.0f + x);
        case ToneCurve::kContrast: return 1.15f * std::pow(x, 1.25f);
    }
    return x;
}

std::vector<uint8_t> applyCameraResponse(const ImageRGBA& linear, float exposure, const CameraResponse& response) {
    const size_t pixel_count = size_t(linear.width) * size_t(linear.height);
    std::vector<uint8_t> bytes(pixel_count * 4);
    const glm::vec3 gain = exposure * response.exposure_scale * response.white_balance;
    for (size_t pixel = 0; pixel < pixel_count; ++pixel) {
        for (int channel = 0; channel < 3; ++channel) {
            const float value = applyToneCurve(response.curve, linear.texels[4 * pixel + channel] * gain[channel]);
            const float clamped = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
            bytes[4 * pixel + channel] = uint8_t(std::lround(srgbEncode(clamped) * 255.0f));
        }
        bytes[4 * pixel + 3] = 255;
    }
    return bytes;
}

}  // namespace gusuku::bench

#pragma once
// A camera's response: what a phone does between the light it sees and the bytes it hands the runtime. The
// bench applies it to the path-traced camera frame (the site without the building) and to the truth (the site
// with it) alike, so the truth is what this camera would film had the building stood there, and the runtime's
// colour match has a white balance and a tone curve to undo. The runtime is told the exposure only (as a
// camera's metadata would), never the white balance or the curve.
//
// Per pixel of a linear Rec.709 frame: v = curve(exposure x white_balance x rgb), clamped to [0, 1],
// sRGB-encoded, rounded to 8 bits.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/assets/image.h"

namespace gusuku::bench {

enum class ToneCurve {
    kLinear,    ///< v = x: a camera that only exposes (what the runtime assumes without its colour match)
    kFilmic,    ///< v = x (1 + x / 4) / (1 + x) x 1.6: a soft shoulder (highlights rolled off), mid-tones lifted
    kContrast,  ///< v = x^1.25 x 1.15: more contrast, darker shadows (a punchy phone look)
};

struct CameraResponse {
    std::string name;
    float exposure_scale = 1.0f;         ///< times the frame's middle-grey exposure
    glm::vec3 white_balance{1.0f};       ///< per-channel gain on linear RGB
    ToneCurve curve = ToneCurve::kLinear;
};

/// The bench's responses: "neutral" (exposure only), "warm_filmic" (white balance (1.15, 1, 0.8), filmic
/// curve), "cool_contrast" (white balance (0.85, 1, 1.2), 0.8 x exposure, contrast curve).
std::vector<CameraResponse> benchCameraResponses();

/// The curve's value for a linear input >= 0 (before clamping).
float applyToneCurve(ToneCurve curve, float linear);

/// The RGBA8 frame (alpha 255) this camera writes for a linear frame at this exposure (display value per unit
/// radiance, before exposure_scale).
std::vector<uint8_t> applyCameraResponse(const ImageRGBA& linear, float exposure, const CameraResponse& response);

}  // namespace gusuku::bench

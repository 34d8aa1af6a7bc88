#pragma once
// Colour conversions between scene-referred linear Rec.709 RGB, CIE XYZ and CIE L*a*b* (D65), float32
// (DESIGN.md 2). Lab constants: white (0.95047, 1, 1.08883), epsilon 216/24389, kappa 24389/27.

#include <glm/vec3.hpp>

namespace gusuku {

inline constexpr glm::vec3 kD65White{0.95047f, 1.0f, 1.08883f};

/// Linear Rec.709 (sRGB primaries, D65) to CIE XYZ (Y = relative luminance).
glm::vec3 xyzFromLinearRec709(const glm::vec3& rgb);
glm::vec3 linearRec709FromXyz(const glm::vec3& xyz);

/// CIE XYZ to L*a*b* relative to kD65White, and back.
glm::vec3 labFromXyz(const glm::vec3& xyz);
glm::vec3 xyzFromLab(const glm::vec3& lab);

inline glm::vec3 labFromLinearRec709(const glm::vec3& rgb) { return labFromXyz(xyzFromLinearRec709(rgb)); }
inline glm::vec3 linearRec709FromLab(const glm::vec3& lab) { return linearRec709FromXyz(xyzFromLab(lab)); }

/// Rec.709 luminance Y of linear RGB.
inline float luminanceRec709(const glm::vec3& rgb) { return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b; }

}  // namespace gusuku

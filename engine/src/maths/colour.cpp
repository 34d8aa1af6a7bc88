#include "gusuku/colour.h"

#include <cmath>

namespace gusuku {

namespace {
constexpr float kLabEpsilon = 216.0f / 24389.0f;
constexpr float kLabKappa = 24389.0f / 27.0f;

float labForward(float t) { return t > kLabEpsilon ? std::cbrt(t) : (kLabKappa * t + 16.0f) / 116.0f; }
}  // namespace

glm::vec3 xyzFromLinearRec709(const glm::vec3& rgb) {
    // IEC 61966-2-1 matrix (Rec.709 primaries, D65 white).
    return {0.4124564f * rgb.r + 0.3575761f * rgb.g + 0.1804375f * rgb.b,
            0.2126729f * rgb.r + 0.7151522f * rgb.g + 0.0721750f * rgb.b,
            0.0193339f * rgb.r + 0.1191920f * rgb.g + 0.9503041f * rgb.b};
}

glm::vec3 linearRec709FromXyz(const glm::vec3& xyz) {
    return {3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
            -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
            0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z};
}

glm::vec3 labFromXyz(const glm::vec3& xyz) {
    const float fx = labForward(xyz.x / kD65White.x);
    const float fy = labForward(xyz.y / kD65White.y);
    const float fz = labForward(xyz.z / kD65White.z);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

glm::vec3 xyzFromLab(const glm::vec3& lab) {
    const float fy = (lab.x + 16.0f) / 116.0f;
    const float fx = fy + lab.y / 500.0f;
    const float fz = fy - lab.z / 200.0f;
    const float fx3 = fx * fx * fx, fz3 = fz * fz * fz;
    const float xr = fx3 > kLabEpsilon ? fx3 : (116.0f * fx - 16.0f) / kLabKappa;
    const float yr = lab.x > kLabKappa * kLabEpsilon ? fy * fy * fy : lab.x / kLabKappa;
    const float zr = fz3 > kLabEpsilon ? fz3 : (116.0f * fz - 16.0f) / kLabKappa;
    return {xr * kD65White.x, yr * kD65White.y, zr * kD65White.z};
}

}  // namespace gusuku

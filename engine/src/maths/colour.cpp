// The sRGB curve and the linear Rec.709 -> XYZ -> Lab chain of gusuku/maths/colour.h, one template per formula so
// the float and double overloads cannot drift apart. shaders/include/colour.glsl is the float twin.
#include <cmath>

#include "gusuku/maths/colour.h"

namespace gusuku {

namespace {

// sRGB: the scalar formulas keep their float literals for float, so that the float overloads compute bit for
// bit what the baker's texture packing and the tests computed before this file held them.
template <typename T> T srgbEncodeT(T linear) {
    if (linear <= T(0.0031308)) return T(12.92) * linear;
    return T(1.055) * std::pow(linear, T(1) / T(2.4)) - T(0.055);
}

template <typename T> T srgbDecodeT(T encoded) {
    if (encoded <= T(0.04045)) return encoded / T(12.92);
    return std::pow((encoded + T(0.055)) / T(1.055), T(2.4));
}

// The Rec.709 primaries with white kD65WhiteXyz, to 7 digits (Lindbloom's published matrix; the rounded
// 4-digit IEC 61966-2-1 matrix misses the white by 1e-4): rows sum to the white to 1e-7, so white is Lab
// (100, 0, 0) to 1e-5. The 7-digit values are kept because bake sets record Lab statistics made with them.
// The inverse is this matrix's exact inverse to 16 digits, so double round trips are exact to rounding.
template <typename T> glm::vec<3, T> xyzFromLinearRec709T(const glm::vec<3, T>& rgb) {
    return {T(0.4124564) * rgb.r + T(0.3575761) * rgb.g + T(0.1804375) * rgb.b,
            T(0.2126729) * rgb.r + T(0.7151522) * rgb.g + T(0.0721750) * rgb.b,
            T(0.0193339) * rgb.r + T(0.1191920) * rgb.g + T(0.9503041) * rgb.b};
}

template <typename T> glm::vec<3, T> linearRec709FromXyzT(const glm::vec<3, T>& xyz) {
    return {T(3.2404548360214085) * xyz.x - T(1.5371388501025751) * xyz.y - T(0.4985315468684809) * xyz.z,
            T(-0.9692663898756538) * xyz.x + T(1.8760109288424912) * xyz.y + T(0.0415560823466735) * xyz.z,
            T(0.0556434196042137) * xyz.x - T(0.2040258542676981) * xyz.y + T(1.0572251624579288) * xyz.z};
}

// f(t) of the Lab definition: cube root above epsilon, the tangent-matched line (kappa t + 16) / 116 below.
template <typename T> T labForward(T relative) {
    return relative > T(kLabEpsilon) ? std::cbrt(relative) : (T(kLabKappa) * relative + T(16)) / T(116);
}

// Inverse of labForward for X and Z: f^3 where that lands above epsilon, the line's inverse below.
template <typename T> T labInverse(T f) {
    const T cube = f * f * f;
    return cube > T(kLabEpsilon) ? cube : (T(116) * f - T(16)) / T(kLabKappa);
}

template <typename T> glm::vec<3, T> labFromXyzT(const glm::vec<3, T>& xyz) {
    const T fx = labForward(xyz.x / T(kD65WhiteXyz.x));
    const T fy = labForward(xyz.y / T(kD65WhiteXyz.y));
    const T fz = labForward(xyz.z / T(kD65WhiteXyz.z));
    return {T(116) * fy - T(16), T(500) * (fx - fy), T(200) * (fy - fz)};
}

template <typename T> glm::vec<3, T> xyzFromLabT(const glm::vec<3, T>& lab) {
    const T fy = (lab.x + T(16)) / T(116);
    const T fx = fy + lab.y / T(500);
    const T fz = fy - lab.z / T(200);
    // Y from L directly: L > kappa * epsilon = 8 (exactly) is the cube-root segment, the junction fy^3 = eps.
    const T yr = lab.x > T(8) ? fy * fy * fy : lab.x / T(kLabKappa);
    return {labInverse(fx) * T(kD65WhiteXyz.x), yr * T(kD65WhiteXyz.y), labInverse(fz) * T(kD65WhiteXyz.z)};
}

}  // namespace

float srgbEncode(float linear) { return srgbEncodeT(linear); }
double srgbEncode(double linear) { return srgbEncodeT(linear); }
float srgbDecode(float encoded) { return srgbDecodeT(encoded); }
double srgbDecode(double encoded) { return srgbDecodeT(encoded); }

glm::vec3 srgbEncode(const glm::vec3& linear_rgb) {
    return {srgbEncode(linear_rgb.r), srgbEncode(linear_rgb.g), srgbEncode(linear_rgb.b)};
}

glm::vec3 srgbDecode(const glm::vec3& encoded_rgb) {
    return {srgbDecode(encoded_rgb.r), srgbDecode(encoded_rgb.g), srgbDecode(encoded_rgb.b)};
}

glm::vec3 xyzFromLinearRec709(const glm::vec3& rgb) { return xyzFromLinearRec709T(rgb); }
glm::dvec3 xyzFromLinearRec709(const glm::dvec3& rgb) { return xyzFromLinearRec709T(rgb); }
glm::vec3 linearRec709FromXyz(const glm::vec3& xyz) { return linearRec709FromXyzT(xyz); }
glm::dvec3 linearRec709FromXyz(const glm::dvec3& xyz) { return linearRec709FromXyzT(xyz); }

glm::vec3 labFromXyz(const glm::vec3& xyz) { return labFromXyzT(xyz); }
glm::dvec3 labFromXyz(const glm::dvec3& xyz) { return labFromXyzT(xyz); }
glm::vec3 xyzFromLab(const glm::vec3& lab) { return xyzFromLabT(lab); }
glm::dvec3 xyzFromLab(const glm::dvec3& lab) { return xyzFromLabT(lab); }

}  // namespace gusuku

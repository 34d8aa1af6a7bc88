#pragma once
// The one home of colour maths for the baker, the runtime's colour match and the benchmark (docs/design.md 2, 4):
// the sRGB transfer curve, Rec.709 luminance, linear Rec.709 RGB <-> CIE XYZ <-> CIE L*a*b* (D65), the
// CIEDE2000 colour difference and the Reinhard transfer of Lab statistics. glm only; whole-image transfers
// that go through an OpenColorIO config stay in gusuku/assets/image.h and use these scalars where plain maths will do.
//
// Precision: float32 everywhere the runtime works (docs/design.md 2: never 8-bit Lab); the double overloads are
// the same formulas for CPU references and for baker code that accumulates in double. Every function here has
// a GLSL twin of the same name in shaders/include/colour.glsl (float only), held to it by tests/test_colour.cpp
// through shaders/tests/colour_probe.comp.
//
// Conventions:
// - "linear Rec.709" is scene-referred linear RGB with the Rec.709 / sRGB primaries and D65 white; values
//   above 1 (HDR) and below 0 (out of gamut) pass through every linear-domain function unclipped.
// - XYZ is scaled so that Y is relative luminance and linear white (1, 1, 1) maps to kD65WhiteXyz.
// - Lab uses white kD65WhiteXyz, epsilon 216/24389 and kappa 24389/27 (the exact CIE constants, continuous at the
//   junction); L in [0, 100] for Y in [0, 1], larger for HDR.
// - Hue angles are in radians inside CIEDE2000; nothing here takes or returns degrees.

#include <cstddef>

#include <glm/vec3.hpp>

#include "gusuku/maths/const_span.h"

namespace gusuku {

// ------------------------------------------------------------------------------------------------------------
// Constants
// ------------------------------------------------------------------------------------------------------------

/// CIE XYZ of the D65 white point with Y = 1 (the reference white of Lab here).
inline constexpr glm::dvec3 kD65WhiteXyz{0.95047, 1.0, 1.08883};
/// Lab's junction between the cube root and the linear segment, (6/29)^3 = 216/24389 (in relative X, Y, Z).
inline constexpr double kLabEpsilon = 216.0 / 24389.0;
/// Slope of Lab's linear segment: L = kappa * Y below epsilon, (29/3)^3 = 24389/27.
inline constexpr double kLabKappa = 24389.0 / 27.0;

// ------------------------------------------------------------------------------------------------------------
// sRGB transfer curve (IEC 61966-2-1), per channel
// ------------------------------------------------------------------------------------------------------------

/// Linear -> sRGB-encoded: 12.92 x at or below 0.0031308, 1.055 x^(1/2.4) - 0.055 above. Values above 1 follow
/// the power segment (encoded > 1); negative values follow the linear segment. No clamping: callers that
/// quantise clamp first.
float srgbEncode(float linear);
double srgbEncode(double linear);
/// sRGB-encoded -> linear: x / 12.92 at or below 0.04045, ((x + 0.055) / 1.055)^2.4 above. The exact inverse of
/// srgbEncode up to rounding (the standard's two thresholds differ by 6e-8: 0.0031308 * 12.92 = 0.040449936).
float srgbDecode(float encoded);
double srgbDecode(double encoded);
/// The same per channel of an RGB triple.
glm::vec3 srgbEncode(const glm::vec3& linear_rgb);
glm::vec3 srgbDecode(const glm::vec3& encoded_rgb);

// ------------------------------------------------------------------------------------------------------------
// Luminance
// ------------------------------------------------------------------------------------------------------------

/// Relative luminance of linear Rec.709 RGB with the Rec.709 / sRGB weights, Y = 0.2126 R + 0.7152 G +
/// 0.0722 B, evaluated left to right in the argument's precision (so baker code that moved here from its own
/// copies computes bit for bit what it did). The Y row of xyzFromLinearRec709 is the same to within 1e-4.
inline float luminanceRec709(const glm::vec3& rgb) { return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b; }
inline double luminanceRec709(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// ------------------------------------------------------------------------------------------------------------
// Linear Rec.709 RGB <-> CIE XYZ <-> CIE L*a*b* (D65)
// ------------------------------------------------------------------------------------------------------------

/// Linear Rec.709 RGB -> CIE XYZ, with the matrix derived from the Rec.709 primaries and the white kD65WhiteXyz
/// to 7 digits: (1, 1, 1) -> kD65WhiteXyz to 1e-7, so Lab white is (100, 0, 0) to 2e-5. linearRec709FromXyz is
/// its exact inverse (round trips exact to rounding).
glm::vec3 xyzFromLinearRec709(const glm::vec3& rgb);
glm::dvec3 xyzFromLinearRec709(const glm::dvec3& rgb);
glm::vec3 linearRec709FromXyz(const glm::vec3& xyz);
glm::dvec3 linearRec709FromXyz(const glm::dvec3& xyz);

/// CIE XYZ -> L*a*b* relative to kD65WhiteXyz, and back. Defined for all finite input: the linear segment
/// continues below 0, so negative (out-of-gamut) components give finite Lab and round-trip.
glm::vec3 labFromXyz(const glm::vec3& xyz);
glm::dvec3 labFromXyz(const glm::dvec3& xyz);
glm::vec3 xyzFromLab(const glm::vec3& lab);
glm::dvec3 xyzFromLab(const glm::dvec3& lab);

inline glm::vec3 labFromLinearRec709(const glm::vec3& rgb) { return labFromXyz(xyzFromLinearRec709(rgb)); }
inline glm::dvec3 labFromLinearRec709(const glm::dvec3& rgb) { return labFromXyz(xyzFromLinearRec709(rgb)); }
inline glm::vec3 linearRec709FromLab(const glm::vec3& lab) { return linearRec709FromXyz(xyzFromLab(lab)); }
inline glm::dvec3 linearRec709FromLab(const glm::dvec3& lab) { return linearRec709FromXyz(xyzFromLab(lab)); }

// ------------------------------------------------------------------------------------------------------------
// CIEDE2000 colour difference (colour_difference.cpp)
// ------------------------------------------------------------------------------------------------------------

/// dE00 between two Lab colours, parametric factors kL = kC = kH = 1, as in Sharma, Wu and Dalal (2005),
/// "The CIEDE2000 color-difference formula: implementation notes, supplementary test data, and mathematical
/// observations", Color Res. Appl. 30(1), equations (1)-(17), including their conventions: the hue of a
/// colour with C' = 0 is 0, and the mean hue and hue difference of a pair with C'1 C'2 = 0 follow their
/// special cases. Like the formula itself, the result is discontinuous where |h'1 - h'2| crosses 180 degrees
/// (by up to about 1.5 % there). Symmetric in its arguments except on that boundary; 0 for equal colours.
double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2);
/// The same formula evaluated in float (what colour.glsl computes), for comparing with the device.
float ciede2000(const glm::vec3& lab1, const glm::vec3& lab2);

// ------------------------------------------------------------------------------------------------------------
// Reinhard transfer of Lab statistics (colour_transfer.cpp; docs/design.md 4)
// ------------------------------------------------------------------------------------------------------------

/// Mean and standard deviation per Lab channel of a set of pixels.
struct LabStatistics {
    glm::vec3 mean{0.0f};                ///< mu per channel (L, a, b)
    glm::vec3 standard_deviation{0.0f};  ///< sigma per channel, >= 0
};

/// mu and sigma (population standard deviation, divided by the count, as in Reinhard et al. 2001) of the
/// finite pixels of lab_pixels, accumulated in double. Pixels with a non-finite channel are skipped; no finite
/// pixel at all gives mean 0 and sigma 0 (which the transfer below then handles by its sigma floor).
LabStatistics measureLabStatistics(ConstSpan<glm::vec3> lab_pixels);

/// Smallest source sigma the transfer divides by, in Lab units (a hundredth of a just-noticeable difference;
/// float rounding gives a flat channel a sigma of about 1e-5 at L = 100). Below it the source channel is flat:
/// its sigma is raised to this floor, so the gain stays finite and the gain clamp then bounds it.
inline constexpr float kLabTransferMinSourceSigma = 0.01f;
/// Default for the max_gain parameter below: the colour match may stretch or squeeze a channel's spread by
/// at most 4 times (docs/design.md 4's example needs 2).
inline constexpr float kLabTransferDefaultMaxGain = 4.0f;

/// A transfer reduced to its per-channel terms: y = (x - source_mean) * gain + target_mean.
struct LabTransfer {
    glm::vec3 source_mean{0.0f};  ///< mu_src
    glm::vec3 gain{1.0f};         ///< sigma_tgt / sigma_src after the floor and the clamp
    glm::vec3 target_mean{0.0f};  ///< mu_tgt
};

/// The Reinhard transfer that maps the source statistics onto the target's, per channel:
/// gain = clamp(sigma_tgt / max(sigma_src, kLabTransferMinSourceSigma), 1 / max_gain, max_gain).
/// The floor keeps a flat source channel (sigma_src ~ 0) from dividing by 0; the clamp keeps it from blowing
/// its noise up into visible structure, and keeps a flat target (sigma_tgt ~ 0) from collapsing every source
/// pixel onto one value. max_gain >= 1 (smaller values are taken as 1, which makes the transfer a pure shift of
/// means); +infinity disables the clamp, leaving only the floor. Statistics must be finite, sigmas >= 0.
LabTransfer makeLabTransfer(const LabStatistics& source, const LabStatistics& target,
                            float max_gain = kLabTransferDefaultMaxGain);

/// Applies a transfer to one Lab pixel: (lab - source_mean) * gain + target_mean. No clamping of the result:
/// out-of-gamut handling is the caller's (docs/design.md 4 lists it as its own failure mode).
inline glm::vec3 applyLabTransfer(const LabTransfer& transfer, const glm::vec3& lab) {
    return (lab - transfer.source_mean) * transfer.gain + transfer.target_mean;
}

}  // namespace gusuku

// The shared-exponent conversion of the Vulkan spec ("Shared Exponent"), written from its equations: N = 9
// mantissa bits, B = 15 exponent bias, E_max = 31.

#include "gusuku/maths/shared_exponent.h"

#include <algorithm>
#include <cmath>

namespace gusuku {
namespace {

constexpr int kMantissaBits = 9;
constexpr int kExponentBias = 15;

float clampedChannel(float value) {
    if (!(value > 0.0f)) return 0.0f;  // negative and NaN
    return std::min(value, kLargestSharedExponentValue);
}

}  // namespace

uint32_t packE5b9g9r9(float red, float green, float blue) {
    const float channels[3] = {clampedChannel(red), clampedChannel(green), clampedChannel(blue)};
    const float largest = std::max({channels[0], channels[1], channels[2]});
    // exp' = max(-B - 1, floor(log2(largest))) + 1 + B; floor(log2(0)) is -infinity, so 0 takes the smallest.
    int exponent = largest > 0.0f ? std::max(-kExponentBias - 1, int(std::floor(std::log2(largest)))) : -kExponentBias - 1;
    exponent += 1 + kExponentBias;
    // The largest channel's mantissa may round up to 2^N: then the exponent is one more.
    if (std::floor(double(largest) / std::ldexp(1.0, exponent - kExponentBias - kMantissaBits) + 0.5) >=
        double(1 << kMantissaBits))
        exponent += 1;
    const double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits);
    uint32_t packed = uint32_t(exponent) << 27;
    for (int channel = 0; channel < 3; ++channel) {
        const uint32_t mantissa = std::min(uint32_t(std::floor(double(channels[channel]) / step + 0.5)), 511u);
        packed |= mantissa << (kMantissaBits * channel);
    }
    return packed;
}

void unpackE5b9g9r9(uint32_t packed, float rgb[3]) {
    const int exponent = int(packed >> 27);
    const double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits);
    for (int channel = 0; channel < 3; ++channel)
        rgb[channel] = float(double((packed >> (kMantissaBits * channel)) & 511u) * step);
}

}  // namespace gusuku

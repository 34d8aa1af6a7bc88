#pragma once
// The runtime's colour match (DESIGN.md 4 and 8, pass 7 feeding pass 5): the camera frame's Lab statistics,
// their smoothing over frames, and the transfer that moves the building's colours towards the camera's. This
// header is the CPU double-precision reference of what the GPU does (gusuku_maths, glm only); the GPU side is
// shaders/runtime/colour_statistics.comp + colour_statistics_reduce.comp (recorded by the runtime's private
// ColourStatisticsPass) and shaders/include/colour_match.glsl (called by the building's fragment shader), whose
// shared state layout is shaders/include/colour_match_interface.h. tests/test_colour_match.cpp holds the GPU to
// these functions. Colour maths (sRGB, Lab, the gain's floor and clamp) comes from gusuku/colour.h.
//
// Choices, and why:
// - Sampling: pixel (offset + i stride, offset + j stride), offset = stride / 2 (the middle of each stride x
//   stride cell, so no edge row or column is favoured), for every i, j that stays inside the frame.
// - Clipped samples (any channel at 255, or all three at 0) say nothing about the scene's colour (the sensor
//   saturated or the frame is black): they are counted and left out of mu and sigma.
// - A frame is accepted when at least colourStatisticsMinValidSamples (5 % of the samples, and at least 16)
//   are valid; otherwise the smoothed statistics are kept as they were (a black frame, a lens covered, a
//   frame of blown-out sky do not pull the building's colours away).
// - Smoothing: mean and variance (sigma^2) each follow new = old + alpha (frame - old) with alpha = 1 / T, T =
//   RuntimeOptions::statistics_smoothing_frames (>= 1; 1 follows every frame). A step change of the camera
//   therefore moves the smoothed mean by exactly 1/T of the remaining jump per frame (no flash), and reaches
//   within 1/e of it after about T frames. The first accepted frame after construction or a reset is taken
//   as it is. Until then there is no target and the transfer is the identity.
// - Reduction on the GPU: one invocation per sample; each subgroup (8 lanes on lavapipe) reduces its samples
//   with subgroupAdd to (count, mean, M2) and writes them as one partial; a one-workgroup kernel combines the
//   partials (Chan et al.'s pairwise update per invocation, then the law of total variance across lanes) and
//   updates the smoothed state. No float atomics: lavapipe (Mesa 22.3.6) does offer VK_EXT_shader_atomic_float
//   (shaderBufferFloat32AtomicAdd), but an app's device need not have or enable it, their order (so the
//   result) would change from run to run, and a single pass would need sum(x^2) - n mean^2 (cancellation);
//   no shared-memory tree either (DESIGN.md 5: 82 ms against 24 ms with subgroupAdd at full 720p).
// - Cost on lavapipe (2 shared cores, fence-timed medians of 20, both dispatches): 0.6 ms at 1280 x 720 with
//   stride 8, 2.3-5.6 ms with stride 4 (the machine's load moves it), 0.18 ms at 640 x 360 with stride 8,
//   0.55 ms with stride 4 (test_colour_match's ColourStatisticsTiming prints them).
// - Transfer, kPaper: Reinhard per Lab channel, y = (x - mu_src) g + mu_tgt, g = sigma_tgt / sigma_src with
//   sigma_src floored at kLabTransferMinSourceSigma (0.01 Lab) and g clamped to [1 / gain_limit, gain_limit]
//   (colour.h makeLabTransfer / colour.glsl labTransferGain: the one definition of the floor and the clamp).
// - Transfer, kPreserve: L as in kPaper (mean and spread); a and b keep their spread (gain 1) and are shifted
//   by the camera's white balance, mu_tgt.ab - mu_src.ab, shortened to at most
//   kColourMatchMaxWhiteBalanceShift so a frame of blue sky tints the building by a bounded cast only. Then
//   the chroma is scaled towards the L axis (same L, same hue) until the colour lies inside the sRGB gamut:
//   the largest scale s in [0, 1] with linear RGB in [0, 1], by kColourMatchGamutSteps bisection steps, s
//   taken from the in-gamut side (within 2^-12 below the exact one).
// - Both modes: the input is clamped to [0, kColourMatchMaxLinear] per channel (NaN taken as 0),
//   L after the transfer is clamped to [0, 100] (the displayable range), and the linear RGB result is clamped
//   to [0, 1]: displayable, never NaN. Mode kOff, or no accepted camera frame yet: only that sanitising and
//   clamping.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "gusuku/colour.h"

namespace gusuku {

/// The transfer's mode, as the GPU state holds it (COLOUR_MATCH_MODE_* in colour_match_interface.h); the
/// runtime's API names it ColourMatch.
enum class ColourMatchMode : uint32_t { kOff = 0, kPaper = 1, kPreserve = 2 };

/// Longest shift of the a, b means in kPreserve, Lab units (about the cast of a strong white-balance error;
/// the transfer of a frame of sky, b about -30, would otherwise turn the building blue).
inline constexpr double kColourMatchMaxWhiteBalanceShift = 15.0;
/// Bisection steps of kPreserve's gamut mapping: the chroma scale is within 2^-12 of the largest in gamut.
inline constexpr int kColourMatchGamutSteps = 12;
/// Linear input is clamped to [0, this] (NaN taken as 0) before the transfer, so that Lab stays finite.
inline constexpr double kColourMatchMaxLinear = 65504.0;
/// Frames are accepted with at least this fraction of the samples valid (and at least the count below).
inline constexpr double kColourStatisticsMinValidFraction = 0.05;
inline constexpr uint32_t kColourStatisticsMinValidSamplesFloor = 16;

// ------------------------------------------------------------------------------------------------------------
// Camera statistics
// ------------------------------------------------------------------------------------------------------------

/// Which pixels are sampled (see "Sampling" above).
struct ColourStatisticsGrid {
    uint32_t stride = 1;
    uint32_t offset = 0;     ///< stride / 2
    uint32_t samples_x = 0;  ///< pixels offset + i * stride < width
    uint32_t samples_y = 0;
    uint64_t sampleCount() const { return uint64_t(samples_x) * samples_y; }
};

/// The grid for a frame; std::invalid_argument naming the value when width or height is 0 or stride is 0 or
/// larger than either side.
ColourStatisticsGrid colourStatisticsGrid(uint32_t width, uint32_t height, uint32_t stride);

/// True for a camera pixel the statistics leave out: a channel at 255 or all three at 0 (alpha ignored).
inline bool isClippedCameraPixel(uint8_t r, uint8_t g, uint8_t b) {
    return r == 255 || g == 255 || b == 255 || (r == 0 && g == 0 && b == 0);
}

/// One frame's statistics of the valid samples: population mu and sigma per Lab channel (0 when none).
struct CameraColourStatistics {
    glm::dvec3 lab_mean{0.0};
    glm::dvec3 lab_sigma{0.0};
    uint64_t valid_samples = 0;
    uint64_t clipped_samples = 0;
};

/// Reference of colour_statistics.comp + the reduce: rgba8 holds width * height pixels, 4 bytes each, RGB
/// sRGB-encoded, row 0 at the top. Decodes each sample with srgbDecode and converts with labFromLinearRec709 in
/// double, two passes (mean, then squared deviations). Cost: 2 Lab conversions per sample.
CameraColourStatistics measureCameraColourStatistics(std::span<const uint8_t> rgba8, uint32_t width, uint32_t height,
                                                     uint32_t stride);

/// Valid samples a frame of sample_count samples needs to be accepted: max(16, ceil(5 % of them)), at most
/// sample_count.
uint32_t colourStatisticsMinValidSamples(uint64_t sample_count);

/// alpha of the moving average for a time constant of smoothing_frames (values below 1, and NaN, count as 1).
double colourStatisticsSmoothingWeight(double smoothing_frames);

/// The smoothed camera statistics (what ColourMatchState holds after the reduce).
struct SmoothedColourStatistics {
    bool valid = false;         ///< a frame was accepted since construction or reset
    uint32_t frames_accepted = 0;
    glm::dvec3 lab_mean{0.0};
    glm::dvec3 lab_variance{0.0};
};

/// One frame's update (see "Smoothing" above): frame accepted when frame.valid_samples >= min_valid_samples.
/// reset: start over (the result is invalid if this frame is not accepted).
SmoothedColourStatistics smoothColourStatistics(const SmoothedColourStatistics& previous,
                                                const CameraColourStatistics& frame, uint32_t min_valid_samples,
                                                double smoothing_weight, bool reset = false);

// ------------------------------------------------------------------------------------------------------------
// Source statistics
// ------------------------------------------------------------------------------------------------------------

/// The baked appearance's statistics for blended slots: weighted means of mu and of sigma (weights need not
/// sum to 1; they are normalised; all zero gives the unweighted mean). A blend of sigmas, not of the images:
/// the statistics of a blend of two lightmaps are not a function of theirs, and this one moves smoothly with
/// the weights, so a slot switch never pops. Empty input gives mean 0, sigma 0.
LabStatistics blendLabStatistics(std::span<const LabStatistics> slots, std::span<const float> weights);

// ------------------------------------------------------------------------------------------------------------
// Transfer
// ------------------------------------------------------------------------------------------------------------

/// Everything the transfer reads (on the GPU: ColourMatchState).
struct ColourMatchParameters {
    ColourMatchMode mode = ColourMatchMode::kPreserve;
    LabStatistics source;              ///< the baked appearance's (float, as the GPU state holds it)
    SmoothedColourStatistics target;   ///< the camera's; invalid: identity
    float gain_limit = 2.0f;           ///< RuntimeOptions::colour_gain_limit
};

/// The per-channel Lab transfer of the mode, before any clamping or gamut mapping (kOff or an invalid target:
/// lab unchanged). The gains are makeLabTransfer's, in float as on the GPU; the rest is double.
glm::dvec3 colourMatchTransferLab(const glm::dvec3& lab, const ColourMatchParameters& parameters);

/// kPreserve's gamut mapping: lab with its chroma scaled towards the L axis (L clamped to [0, 100] first)
/// until linear Rec.709 lies in [0, 1] (see the choices above).
glm::dvec3 colourMatchChromaIntoGamut(const glm::dvec3& lab);

/// The whole transfer of one linear Rec.709 colour, as colour_match.glsl's applyColourMatch: sanitise, Lab,
/// transfer, L clamp, gamut mapping (kPreserve), back to linear, clamp to [0, 1]. Always finite.
glm::dvec3 applyColourMatch(const glm::dvec3& linear_rgb, const ColourMatchParameters& parameters);

}  // namespace gusuku

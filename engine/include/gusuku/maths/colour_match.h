#pragma once
// The runtime's colour match (docs/design.md 4 and 8, pass 7 feeding pass 5): the camera frame's Lab statistics,
// their smoothing over frames, and the transfer that moves the building's colours towards the camera's. This
// header is the CPU double-precision reference of what the GPU does (gusuku_maths, glm only); the GPU side is
// shaders/runtime/colour_statistics.comp + colour_statistics_reduce.comp (recorded by the runtime's private
// ColourStatisticsPass) and shaders/include/colour_match.glsl (called by the building's fragment shader), whose
// shared state layout is shaders/include/colour_match_interface.h. tests/test_colour_match.cpp holds the GPU to
// these functions. Colour maths (sRGB, Lab, the gain's floor and clamp) comes from gusuku/maths/colour.h.
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
//   no shared-memory tree either: llvmpipe runs each barrier as a switch between invocations, so the tree
//   costs more than subgroupAdd (docs/design.md 5).
// - Cost on lavapipe: test_colour_match's ColourStatisticsTiming prints it per frame size and stride (the
//   figures are in docs/measurements.md); it grows with the samples, 1 / stride^2 of the pixels.
// - Transfer, kReinhard: Reinhard per Lab channel, y = (x - mu_src) g + mu_tgt, g = sigma_tgt / sigma_src with
//   sigma_src floored at kLabTransferMinSourceSigma (0.01 Lab) and g clamped to [1 / gain_limit, gain_limit]
//   (colour.h makeLabTransfer / colour.glsl labTransferGain: the one definition of the floor and the clamp).
// - Transfer, kPreserve: L as in kReinhard (mean and spread); a and b keep their spread (gain 1) and are shifted
//   by the camera's white balance, mu_tgt.ab - mu_src.ab, shortened to at most
//   kColourMatchMaxWhiteBalanceShift so a frame of blue sky tints the building by a bounded cast only. Then
//   the chroma is scaled towards the L axis (same L, same hue) until the colour lies inside the sRGB gamut:
//   the largest scale s in [0, 1] with linear RGB in [0, 1], by kColourMatchGamutSteps bisection steps, s
//   taken from the in-gamut side (within 2^-12 below the exact one).
// - Both modes: the input is clamped to [0, kColourMatchMaxLinear] per channel (NaN taken as 0),
//   L after the transfer is clamped to [0, 100] (the displayable range), and the linear RGB result is clamped
//   to [0, 1]: displayable, never NaN. Mode kOff, or no accepted camera frame yet: only that sanitising and
//   clamping.
//
// Mode kGround compares like with like (the Lab modes above move the building's own statistics onto those of
// the whole frame, sky and grass included, which is a statistic of other content and can never be right). The
// bake set models the real site's ground (the ground grid: height, normal, E_without per slot, and the
// ground's albedo, ground_grid.albedo), so the runtime can predict what the camera should see there:
//   predicted_c = exposure albedo_c / pi (sum_k w_k E_without_k,c + E_sun_c max(0, n . s) V)
// and the camera gives observed_c (sRGB-decoded). The von Kries gain gain_c = sum observed_c / sum predicted_c
// over the same pixels undoes exposure and white balance exactly, and a tone curve to first order about the
// ground's brightness; the building's exposed linear colour is multiplied by it. Choices:
// - Pixels: the sample grid above, at groundMatchStride: the statistics stride, made finer until the frame
//   has at least kGroundMatchTargetSamples (4096) samples (every pixel of a small frame). The gain is a ratio
//   over the ground's samples alone, a fraction of the frame: on the bench's 96 x 54 frames stride 8 leaves 17
//   of them, whose texture and noise moved the gain by up to 9 %; every pixel gives 589 and 1-2 %. 4096 (640 x
//   360 at stride 7: ~3000 on the ground in the tests' view) instead of 16384 (stride 3) cut the ground
//   statistics on lavapipe from ~2.8 ms to ~0.6 ms; the bench's frames (160 x 90 and smaller) keep every pixel.
//   Each sample's ray (through the pixel's centre) is intersected with the
//   ground grid as a height field: a plane at the mean height of the cells with ground, then up to
//   kGroundMatchHeightIterations steps of "the height of the cell the ray reaches at the current height"; the
//   sample counts only if a step lands in the cell it started from (then every later step would too, so the
//   march stops there), the cell has ground and albedo, the ray goes
//   down (d.z < -1e-6) and t > 0. Nearest cell, no interpolation (the gain is a ratio of sums over hundreds of
//   cells: per-cell detail averages out).
// - V = 1: the real site's shadows are not looked up (the statistics run before the shadow maps, and on
//   storage buffers only); ground the real scene shades is predicted too bright and falls out in the trim
//   below, as do pixels of real objects standing in front of the ground (walls, people) and of clipped sensor.
// - Robust estimate: per sample r = log2(Y_observed / Y_predicted) (Rec.709 luminance); samples go into
//   kGroundMatchBins bins of 1 / kGroundMatchBinsPerStop stop from kGroundMatchLowestLog2Ratio (outside:
//   the end bins). The median bin m is the smallest with 2 cumulative count >= the total; the gain sums only
//   the bins m - kGroundMatchWindowBins .. m + kGroundMatchWindowBins (+- 0.56 stop about the median). A shadow
//   (-1.5 stops and more) or a wall does not move it; the median cannot be pulled by under half the samples.
// - Clipped samples (isClippedCameraPixel) whose ray hits the ground are counted and left out; samples whose
//   predicted luminance is below kGroundMatchMinPredicted (no light, black albedo) are left out.
// - A frame is accepted when at least colourStatisticsMinValidSamples(samples of the ground's grid) samples
//   are kept (max(16, 5 % of the grid), the Lab statistics' rule) and every channel's predicted sum is positive; otherwise the smoothed gain stays (a frame of sky keeps the last estimate, or the
//   identity before any). The gain is clamped per channel to [1 / gain_limit, gain_limit], then smoothed like
//   the Lab statistics (new = old + alpha (frame - old), the first accepted frame taken as it is).
// - Transfer: y = clamp(gain x, 0, 1), x the building's linear radiance times the frame's exposure (sanitised
//   as above). Without an accepted frame it is clamp(x, 0, 1): exactly the unmatched building.
// - A bake set without ground albedo (older bakes) cannot run kGround: the runtime throws RuntimeError
//   kInvalidFrame naming ground_grid.albedo (the C API returns that code), and the other modes still run.
// - GPU: shaders/runtime/colour_statistics_ground.comp writes each sample (observed, predicted, bin) with no
//   barrier and no shared memory; colour_statistics_ground_reduce.comp (one workgroup of 64) counts the bins
//   per lane, finds the median, sums the window per lane and combines by subgroupAdd: two passes over the
//   samples. No atomics: the same sums every run. Cost on lavapipe (2 shared cores): see the test
//   GroundMatchGpu timing print; a per-workgroup shared-memory histogram costs many times more (llvmpipe runs
//   each barrier as a switch between invocations).

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/formats/ground_grid.h"

namespace gusuku {

/// The transfer's mode, as the GPU state holds it (COLOUR_MATCH_MODE_* in colour_match_interface.h); the
/// runtime's API names it ColourMatch. kAuto is the API's default and never reaches the GPU: each frame resolves it
/// to kGround where the bake set has ground albedo and the device runs the statistics, else to kOff.
enum class ColourMatchMode : uint32_t {
    kOff = 0,
    kReinhard = 1,  ///< Reinhard et al.'s per-channel Lab transfer
    kPreserve = 2,
    kGround = 3,
    kAuto = 4,
    /// The paper's name, kept for existing code (the same value; never list both in one switch).
    kPaper = kReinhard,
};

struct BakeSetData;

/// Longest shift of the a, b means in kPreserve, Lab units (about the cast of a strong white-balance error;
/// the transfer of a frame of sky, b about -30, would otherwise turn the building blue).
inline constexpr double kColourMatchMaxWhiteBalanceShift = 15.0;
/// Bisection steps of kPreserve's gamut mapping: the chroma scale is within 2^-12 of the largest in gamut.
inline constexpr int kColourMatchGamutSteps = 12;
/// Linear input is clamped to [0, this] (NaN taken as 0) before the transfer, so that Lab stays finite.
inline constexpr double kColourMatchMaxLinear = 65504.0;
/// kPreserve's gamut test: linear values this close outside [0, 1] count as inside (float rounding of white,
/// L 100 -> 1.0000001).
inline constexpr double kColourMatchGamutTolerance = 1e-5;
/// Frames are accepted with at least this fraction of the samples valid (and at least the count below).
inline constexpr double kColourStatisticsMinValidFraction = 0.05;
inline constexpr uint32_t kColourStatisticsMinValidSamplesFloor = 16;
/// The runtime measures the camera (packs the sampled pixels and runs the statistics) on one frame in this many,
/// and always on the first frame of a mode and after a reset; the smoothing's time constant stays
/// RuntimeOptions::statistics_smoothing_frames frames (the pass smooths with T / interval measurements). Why:
/// on lavapipe each measurement costs a fixed ~0.3-0.5 ms of small dependent dispatches whatever the samples,
/// and the light and the camera's exposure change over seconds, not frames.
inline constexpr uint32_t kColourStatisticsInterval = 4;

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
CameraColourStatistics measureCameraColourStatistics(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
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
LabStatistics blendLabStatistics(ConstSpan<LabStatistics> slots, ConstSpan<float> weights);

// ------------------------------------------------------------------------------------------------------------
// Transfer
// ------------------------------------------------------------------------------------------------------------

// ------------------------------------------------------------------------------------------------------------
// Ground match (kGround; see the choices above)
// ------------------------------------------------------------------------------------------------------------

inline constexpr uint32_t kGroundMatchBins = 64;
inline constexpr double kGroundMatchBinsPerStop = 8.0;
inline constexpr double kGroundMatchLowestLog2Ratio = -4.0;
inline constexpr uint32_t kGroundMatchWindowBins = 4;
inline constexpr int kGroundMatchHeightIterations = 4;
inline constexpr double kGroundMatchMinPredicted = 1e-6;
inline constexpr uint64_t kGroundMatchTargetSamples = 4096;

/// The ground kernel's stride: the largest s <= statistics_stride (and >= 1) with (width / s) (height / s) >=
/// kGroundMatchTargetSamples, i.e. floor(sqrt(width height / target)) clamped to [1, statistics_stride]: 1280 x
/// 720 at stride 8 gives 8, 640 x 360 gives 7, 96 x 54 gives 1.
uint32_t groundMatchStride(uint32_t width, uint32_t height, uint32_t statistics_stride);

/// One ground-grid cell as the match reads it (float: what the GPU holds).
struct GroundMatchCell {
    glm::vec3 albedo{0.0f};  ///< linear base colour
    bool ground = false;     ///< the cell has ground and albedo
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float height_m = 0.0f;
};

/// The bake set's ground as the match needs it.
struct GroundMatchScene {
    GroundGrid grid;
    std::vector<GroundMatchCell> cells;                       ///< texel order (gusuku/formats/ground_grid.h)
    std::vector<std::vector<glm::vec3>> irradiance_without;  ///< per slot, per cell: E_without, bake set units
    float start_height_m = 0.0f;  ///< mean height of the cells with ground: the ray's first plane
};

/// The scene of a bake set, or nothing when it has no ground albedo (or no cell with ground).
std::optional<GroundMatchScene> groundMatchSceneFrom(const BakeSetData& bake_set);

/// Per frame: the camera (pinhole, the runtime's conventions: x right, y down, z forward; pixel centres at +0.5)
/// and the light the runtime uses for the building.
struct GroundMatchView {
    double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0;
    glm::dvec3 camera_position_enu{0.0};
    glm::dmat3 camera_to_enu{1.0};
    glm::dvec3 sun_direction_enu{0.0, 0.0, 1.0};
    bool sun_shines = false;
    glm::dvec3 sun_irradiance_rgb{0.0};  ///< E_sun after cloud cover, bake set units
    double exposure = 1.0;
    int slots[3] = {-1, -1, -1};     ///< manifest slot per blend term (-1: none)
    float weights[3] = {0.0f, 0.0f, 0.0f};
};

/// The cell (texel index) the ray through pixel centre (x + 0.5, y + 0.5) reaches on the ground, or nothing.
std::optional<size_t> groundMatchCellOfPixel(const GroundMatchScene& scene, const GroundMatchView& view,
                                             uint32_t x, uint32_t y);

/// What the camera should record at that cell, linear display values (exposure included).
glm::dvec3 groundMatchPredictedRadiance(const GroundMatchScene& scene, const GroundMatchView& view, size_t cell);

/// One frame's ground estimate (the reference of colour_statistics_ground.comp and its reduce).
struct GroundColourEstimate {
    glm::dvec3 gain{1.0};             ///< observed / predicted over the kept samples, clamped
    glm::dvec3 observed_sum{0.0};     ///< over the kept samples
    glm::dvec3 predicted_sum{0.0};
    uint64_t ground_samples = 0;      ///< samples on the ground, neither clipped nor unlit (in the bins)
    uint64_t kept_samples = 0;        ///< in the window about the median
    uint64_t clipped_samples = 0;     ///< samples on the ground left out as clipped
    int median_bin = -1;              ///< -1 when no sample
    bool accepted = false;
};

/// The log-ratio bin of a sample (see "Robust estimate").
uint32_t groundMatchBin(const glm::dvec3& observed, const glm::dvec3& predicted);

/// stride: the ground grid's (groundMatchStride); the acceptance threshold is that grid's.
GroundColourEstimate measureGroundColourGain(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
                                             uint32_t stride, const GroundMatchScene& scene,
                                             const GroundMatchView& view, float gain_limit);

/// The smoothed gain (what ColourMatchState holds for kGround).
struct SmoothedGroundGain {
    bool valid = false;
    uint32_t frames_accepted = 0;
    glm::dvec3 gain{1.0};
};

/// One frame's update; reset: start over.
SmoothedGroundGain smoothGroundGain(const SmoothedGroundGain& previous, const GroundColourEstimate& frame,
                                    double smoothing_weight, bool reset = false);

/// Everything the transfer reads (on the GPU: ColourMatchState).
struct ColourMatchParameters {
    ColourMatchMode mode = ColourMatchMode::kPreserve;
    LabStatistics source;              ///< the baked appearance's (float, as the GPU state holds it)
    SmoothedColourStatistics target;   ///< the camera's; invalid: identity
    float gain_limit = 2.0f;           ///< RuntimeOptions::colour_gain_limit
    SmoothedGroundGain ground;         ///< kGround's gain; invalid: identity
};

/// The per-channel Lab transfer of the mode, before any clamping or gamut mapping (kOff or an invalid target:
/// lab unchanged). The gains are makeLabTransfer's, in float as on the GPU; the rest is double.
glm::dvec3 colourMatchTransferLab(const glm::dvec3& lab, const ColourMatchParameters& parameters);

/// kPreserve's gamut mapping: lab with its chroma scaled towards the L axis (L clamped to [0, 100] first)
/// until linear Rec.709 lies in [0, 1] (see the choices above).
glm::dvec3 colourMatchChromaIntoGamut(const glm::dvec3& lab);

/// The whole transfer of one linear Rec.709 colour, as colour_match.glsl's applyColourMatch: sanitise, Lab,
/// transfer, L clamp, gamut mapping (kPreserve), back to linear, clamp to [0, 1]. Always finite. kGround:
/// linear_rgb is the exposed radiance, the result clamp(gain linear_rgb, 0, 1) (no Lab).
glm::dvec3 applyColourMatch(const glm::dvec3& linear_rgb, const ColourMatchParameters& parameters);

}  // namespace gusuku

#pragma once
// Weather from the camera frame alone: an estimate of cloud cover the app can hand the runtime as its Weather
// (gusuku/runtime/runtime.h: Weather::estimatedFrom), when no weather service answers. CPU, glm only (gusuku_maths);
// it allocates (arrays the size of the frame): call it now and then (every second or so), not per frame.
// Two cues a sunny frame has and an overcast one lacks:
//   - a blue sky: how much bluer the top eighth of the rows is than the ground, ln(B / R) of linear RGB at the
//     top rows' 75th percentile (so a sky that fills a quarter of those rows or more counts) minus its median
//     over the lower half. A camera's white balance scales B / R by one factor over the whole frame, so it
//     cancels: a warm and a neutral camera read the same sky (a tone curve that adds contrast still stretches it);
//   - hard shadows: sunlit and shaded ground differ by E_sun cos / E_sky + 1 (4 to 10 in clear air), an overcast
//     ground only by its albedo and its occlusion. Measured as ln(p90 / p10) of luminance over the frame's lower
//     half (where the ground is in a phone held up to a building).
// The sky cue decides when the frame shows sky (its top eighth's median luminance above the lower half's), the
// shadow cue otherwise; each is mapped linearly from its overcast value (cover 1) to its clear value (cover 0)
// and clamped. The sky constants were set from the sample site's 10:30 sunny and overcast frames through a
// neutral camera (gusuku-bench's clouds section, which then measures the estimate at other hours, covers,
// camera responses, and under photographed skies it was not set on); the shadow constants from its 12:00 frames.

#include <cstdint>
#include <vector>

namespace gusuku {

struct CloudEstimate {
    float cloud_cover = 0.0f;      ///< [0, 1]: 0 clear, 1 overcast
    float shadow_contrast = 0.0f;  ///< ln(p90 / p10) of the lower half's luminance
    float sky_blueness = 0.0f;     ///< ln(B / R): top rows' 75th percentile minus the lower half's median
    bool sky_in_view = false;      ///< the sky cue decided (else the shadow cue)
};

/// Shadow-contrast and sky-blueness values of an overcast and of a clear frame (the cue maps' ends).
inline constexpr float kOvercastShadowContrast = 0.8f;
inline constexpr float kClearShadowContrast = 2.4f;
inline constexpr float kOvercastSkyBlueness = 0.80f;
inline constexpr float kClearSkyBlueness = 1.20f;

/// The estimate for an RGBA8 frame (RGB sRGB-encoded, row 0 at the top; gusuku/runtime/runtime.h). A frame smaller
/// than 2 x 8 pixels or entirely black is taken as overcast (cover 1: no sun added is the safer error).
CloudEstimate estimateCloudCover(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height);
/// The same over width * height * 4 bytes at rgba8 (null: overcast).
CloudEstimate estimateCloudCover(const uint8_t* rgba8, uint32_t width, uint32_t height);

}  // namespace gusuku

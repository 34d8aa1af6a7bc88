#pragma once
// Weather from the camera frame alone: an estimate of cloud cover the app can hand the runtime as its Weather
// (gusuku/runtime.h: Weather::estimatedFrom), when no weather service answers. CPU, glm only (gusuku_maths);
// it allocates (two arrays the size of the frame): call it now and then (every second or so), not per frame. Two cues a sunny frame has and an overcast one lacks:
//   - hard shadows: sunlit and shaded ground differ by E_sun cos / E_sky + 1 (4 to 10 in clear air), an overcast
//     ground only by its albedo and its occlusion. Measured as ln(p90 / p10) of luminance over the frame's lower
//     half (where the ground is in a phone held up to a building), so a bright sky does not count;
//   - a blue sky: (B - R) / (B + R) of linear RGB over the top eighth of the frame's rows, at its 75th
//     percentile (so a sky that fills a quarter of those rows or more counts; a frame without sky gives the
//     ground's near-neutral or negative value and the shadow cue decides).
// Each cue is mapped linearly from its overcast value (0 clear) to its clear value (1 clear) and clamped; cover is
// 1 minus their mean. The four constants were set from the sample site's 12:00 sunny and overcast frames (the
// bench then measures the estimate at other hours, covers and camera responses). A white balance that warms
// the frame pulls the sky cue towards overcast; a tone curve with more contrast pushes the shadow cue towards
// clear: the bench reports both.

#include <cstdint>
#include <vector>

namespace gusuku {

struct CloudEstimate {
    float cloud_cover = 0.0f;      ///< [0, 1]: 0 clear, 1 overcast
    float shadow_contrast = 0.0f;  ///< ln(p90 / p10) of the lower half's luminance
    float sky_blueness = 0.0f;     ///< (B - R) / (B + R) of the top rows, 75th percentile
};

/// Shadow-contrast and sky-blueness values of an overcast and of a clear frame (the cue maps' ends).
inline constexpr float kOvercastShadowContrast = 0.8f;
inline constexpr float kClearShadowContrast = 2.4f;
inline constexpr float kOvercastSkyBlueness = 0.02f;
inline constexpr float kClearSkyBlueness = 0.30f;

/// The estimate for an RGBA8 frame (RGB sRGB-encoded, row 0 at the top; gusuku/runtime.h). A frame smaller
/// than 2 x 8 pixels or entirely black is taken as overcast (cover 1: no sun added is the safer error).
CloudEstimate estimateCloudCover(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height);
/// The same over width * height * 4 bytes at rgba8 (null: overcast).
CloudEstimate estimateCloudCover(const uint8_t* rgba8, uint32_t width, uint32_t height);

}  // namespace gusuku

#pragma once
// gusuku-render's camera frame from an image file: the runtime takes 8-bit sRGB RGBA, so every file is
// converted by what it holds (its bit depth, not its name).

#include <cstdint>
#include <string>
#include <vector>

namespace gusuku::render_cli {

/// The largest camera frame side: the runtime's (RuntimeOptions::frame_width/height, [1, 8192]).
inline constexpr int kMaxCameraSide = 8192;
/// The smallest: the runtime's colour statistics sample every statistics_stride-th pixel each way (gusuku-render
/// keeps RuntimeOptions' default of 8), so a frame needs that many pixels on each side.
inline constexpr int kMinCameraSide = 8;

struct CameraImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> srgb_rgba8;  ///< width * height * 4 bytes, sRGB-encoded colour, linear alpha
};

/// Reads `path` as a camera frame: 8- and 16-bit integer files are taken as sRGB-encoded, float files (OpenEXR,
/// Radiance HDR) as linear (encoded to sRGB here; reading them as sRGB would darken them twice), grey as RGB,
/// a missing alpha as opaque; values are clamped to [0, 1]. InputError (gusuku/assets/image.h's) on a bad file,
/// and on one larger than kMaxCameraSide or smaller than kMinCameraSide on a side, refused from its header before
/// it is decoded.
CameraImage readCameraImage(const std::string& path);

}  // namespace gusuku::render_cli

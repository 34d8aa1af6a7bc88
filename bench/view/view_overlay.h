#pragma once
// gusuku-view's overlay: a few lines of text (the sun, the slot weights, the weather's source, the frame time per
// pass) drawn on the CPU in a 5 x 7 font into a small opaque box, which the frame loop copies onto the top-left of
// each presented image (view_frame_loop.h). Grey levels only, so the bytes are the same in RGBA and BGRA swapchains.

#include <cstdint>
#include <string>
#include <vector>

namespace gusuku::view {

/// One glyph's cell is 6 x 9 font pixels (5 x 7 and the gaps); each font pixel is `scale` x `scale` image pixels.
inline constexpr uint32_t kGlyphAdvance = 6, kLinePitch = 9, kOverlayPadding = 3;
/// The text's grey level and the box's, as 8-bit codes (sRGB): readable over sky and over shadow alike.
inline constexpr uint8_t kOverlayInk = 235, kOverlayPaper = 24;

struct OverlayImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;  ///< width x height x 4, row 0 at the top
};

/// `lines` drawn at `scale` (1 or more): letters are drawn upper case; a character the font lacks is drawn as '?'.
/// The box is (longest line x kGlyphAdvance + 2 kOverlayPadding) x (lines x kLinePitch + 2 kOverlayPadding) font
/// pixels; no lines give an empty image.
OverlayImage rasteriseOverlay(const std::vector<std::string>& lines, uint32_t scale);

}  // namespace gusuku::view

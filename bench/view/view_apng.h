#pragma once
// An animated PNG (APNG: PNG plus the acTL, fcTL and fdAT chunks, which a plain PNG reader skips, showing the
// first frame) assembled from PNG files of one size and format, without decoding them: each file's IDAT data
// becomes one frame. gusuku-view --render OUT.png writes one.

#include <cstdint>
#include <string>
#include <vector>

namespace gusuku::view {

/// The frame rate of gusuku-view --render's animated PNG: 4 frames a second, the README animation's.
inline constexpr uint16_t kApngDelayNumerator = 1, kApngDelayDenominator = 4;

/// Writes `frame_pngs` (written by writePngRgba8: the same IHDR) as one looping APNG at `out_path`, atomically.
/// InputError(frame, "", ...) when a file is not a PNG or its IHDR differs from the first's.
void writeApng(const std::vector<std::string>& frame_pngs, const std::string& out_path,
               uint16_t delay_numerator = kApngDelayNumerator, uint16_t delay_denominator = kApngDelayDenominator);

}  // namespace gusuku::view

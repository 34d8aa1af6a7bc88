#pragma once
// gusuku-bench's accuracy metrics: how far a frame is from the truth, per pixel and summed over a region.
//
// Frames are what the runtime writes and the truth is turned into: RGBA8, RGB sRGB-encoded, row 0 at the top
// (gusuku/runtime/runtime.h's image convention); alpha is ignored. A pixel's colour difference is CIEDE2000 (gusuku/
// colour.h) between the CIE Lab (D65) of the two decoded pixels, in double. A region is a mask of one byte per
// pixel (non-zero: in); an empty mask is the whole frame.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gusuku/maths/percentile.h"

#include <glm/vec3.hpp>

namespace gusuku::bench {

/// CIE Lab (D65) of an sRGB-encoded 8-bit colour: decoded with srgbDecode, then labFromLinearRec709.
glm::dvec3 labOfSrgb8(uint8_t red, uint8_t green, uint8_t blue);

/// CIEDE2000 of each pixel of two RGBA8 frames of the same size (std::invalid_argument otherwise): one value
/// per pixel, row-major. Colours repeat a lot in 8-bit frames, but a frame is quick enough without a cache.
std::vector<double> ciede2000PerPixel(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth);

/// Percentiles: gusuku/maths/percentile.h, shared with the runtime's weather estimate.
using gusuku::percentile;

/// Peak signal-to-noise ratio of the RGB bytes (alpha ignored) over the mask's pixels: 10 log10(255^2 / MSE),
/// MSE the mean of the squared byte differences over 3 x pixels. +infinity when the pixels are equal (or the
/// mask is empty).
double psnrDb(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth, const std::vector<uint8_t>& mask);

/// Accuracy of a frame over a region.
struct ErrorSummary {
    double mean_de00 = 0.0;  ///< mean CIEDE2000 over the region's pixels
    double p95_de00 = 0.0;   ///< 95th percentile of CIEDE2000 (percentile() above)
    double psnr_db = 0.0;    ///< psnrDb over the region (+infinity when equal)
    size_t pixel_count = 0;  ///< pixels in the region
};

/// The summary of per-pixel CIEDE2000 values (ciede2000PerPixel) and PSNR over a mask (empty: every pixel).
/// std::invalid_argument when the sizes disagree.
ErrorSummary summariseError(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                            const std::vector<uint8_t>& mask = {});
/// The same from per-pixel CIEDE2000 values already computed (psnr_db is left 0: it needs the bytes).
ErrorSummary summariseDifferences(const std::vector<double>& de00_per_pixel, const std::vector<uint8_t>& mask = {});

/// The frame 3 x 3 box-filtered in linear light (sRGB decoded, averaged over the pixels of the 3 x 3 window that lie
/// in the frame, encoded, rounded to 8 bits; alpha kept). Both images low-passed so, their difference is the
/// light's error without the per-pixel part (aliasing, texture detail, a pixel's shift) that the runtime and the
/// truth share by construction (issue 44 item 6).
std::vector<uint8_t> lowPass3x3Linear(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height);

/// A mean error with the truth's own noise taken out: sqrt(max(0, error^2 - noise^2 / 2)), where
/// noise_between_seeds is the mean error between two independently seeded truths, which holds the noise of both
/// (sqrt 2 times one truth's, the two being independent). Subtracting in quadrature treats the noise as
/// independent of the method's error: a first-order correction, exact for Gaussian per-pixel errors, that keeps the
/// reading from crediting a method with the truth's own grain.
double withoutTruthNoise(double mean_de00, double noise_between_seeds_de00);

/// The pixels the building or its shadow (or its bounce light) changes: those where the site with the building
/// and the site without it differ by more than threshold_de00 (1: about a just-noticeable difference).
/// Rendered with the same seed, the two differ only where a path met the building, so noise does not leak in.
std::vector<uint8_t> changedPixelMask(const std::vector<uint8_t>& with_building,
                                      const std::vector<uint8_t>& without_building, double threshold_de00 = 1.0);

}  // namespace gusuku::bench

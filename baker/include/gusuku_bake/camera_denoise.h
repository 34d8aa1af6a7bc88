#pragma once
// An edge-keeping filter for path-traced camera frames: the a-trous wavelet filter of the lightmaps
// (Dammertz et al. 2010) moved to image space. It smooths the irradiance each pixel's surface receives, never
// its texture: each pixel's radiance is demodulated by its first-hit albedo (minus its emission), filtered with
// weights that stop at geometric edges and at large relative changes of irradiance (a shadow's edge), and
// remodulated. Guided by the first hit of each pixel's centre ray (CameraGuides): normal, distance (through the
// distance of a neighbour's hit point from the pixel's tangent plane, measured in pixel footprints, which holds
// at grazing angles where raw depth differences would not), albedo and the direct sun's share (so a shadow's
// edge stays sharp even where the noise is larger than the step in irradiance). Sky pixels are exact (the sky map is
// looked up, not estimated) and are neither changed nor used, nor are pixels on the back of a surface or on a
// near-black albedo (below 1 %, whose irradiance cannot be recovered).

#include <cstdint>

#include "gusuku/assets/image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_bake/camera_tracer.h"

namespace gusuku::bake {

struct CameraDenoiseOptions {
    int iterations = 2;                       ///< a-trous passes with steps of 1, 2, 4, ... pixels
    float plane_distance_sigma_pixels = 2.0f; ///< off-plane distance, in pixel footprints x step, at weight e^-1/2
    float normal_power = 64.0f;               ///< weight (n_p . n_q)^power
    float relative_luminance_sigma = 0.2f;    ///< |Y_p - Y_q| / (Y_p + Y_q) of irradiance at weight e^-1/2
    float sun_share_sigma = 0.05f;            ///< difference of the direct sun's share max(0, n . s) V at e^-1/2
};

/// Options for a render of `samples_per_pixel` samples: the irradiance edge-stop is 0.4 / sqrt(samples)
/// (clamped to [0.01, 0.25]), two passes up to 64 samples, one above, so a converged frame is left nearly as it
/// is instead of blurred (measured: camera_denoise.cpp).
CameraDenoiseOptions cameraDenoiseOptionsForSamples(uint32_t samples_per_pixel);

/// The filtered copy of render.radiance (intrinsics and pose: those it was rendered with, to place each pixel's
/// hit in the world). O(iterations x 25 x pixels), on one core.
ImageRGBA denoiseCameraFrame(const CameraRender& render, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                             const CameraDenoiseOptions& options);

}  // namespace gusuku::bake

#pragma once
// The camera frame for a site without a photograph (the bundled sample): the site WITHOUT the building,
// path-traced from the view and denoised by the bench's TruthRenderer (one home for the sunny, overcast and
// partly cloudy frames: their blend is linear in radiance, as the runtime blends its slots), then exposed and
// encoded as the runtime's RGBA8 sRGB input.

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/gpu/gpu_device.h"
#include "truth_renderer.h"

namespace gusuku::render_cli {

struct SampleCameraFrame {
    std::vector<uint8_t> rgba8;  ///< width * height * 4, sRGB, row 0 at the top
    float exposure = 1.0f;       ///< display value per unit radiance used to encode it
    double trace_seconds = 0.0;  ///< path tracing and denoising, all conditions
};

/// Renders the frame. exposure <= 0 picks middle grey of the linear frame (middleGreyExposure). Errors:
/// InputError for the site's files, std::invalid_argument for the view.
SampleCameraFrame renderSampleCameraFrame(const GpuDevice& gpu, const std::string& site_json,
                                          const bench::BenchView& view, uint32_t width, uint32_t height,
                                          const bench::BenchCondition& condition, uint32_t samples_per_pixel,
                                          float exposure);

}  // namespace gusuku::render_cli

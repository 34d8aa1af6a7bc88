// The path-traced camera frame of a site (see sample_camera.h).

#include "sample_camera.h"

#include "gusuku/assets/site.h"
#include "gusuku_bake/camera_frame.h"

namespace gusuku::render_cli {

SampleCameraFrame renderSampleCameraFrame(const GpuDevice& gpu, const std::string& site_json,
                                          const bench::BenchView& view, uint32_t width, uint32_t height,
                                          const bench::BenchCondition& condition, uint32_t samples_per_pixel,
                                          float exposure) {
    bench::TruthRenderer renderer(gpu, loadSiteConfig(site_json), /*cache_folder=*/"", /*context_hash=*/"");
    const bench::TracedFrameRequest request =
        bench::siteCameraRequest(view, width, height, condition, samples_per_pixel);
    const bench::TracedFrame traced = renderer.render(request, /*use_cache=*/false);
    SampleCameraFrame frame;
    frame.trace_seconds = traced.trace_seconds + traced.denoise_seconds;
    frame.exposure = exposure > 0.0f ? exposure : bake::middleGreyExposure(traced.denoised);
    frame.rgba8 = bake::packRgba8Srgb(traced.denoised, frame.exposure);
    return frame;
}

}  // namespace gusuku::render_cli

// gusuku-view's camera background (see view_background.h).

#include "view_background.h"

#include <chrono>

#include "camera_image.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/camera_frame.h"

namespace gusuku::view {

namespace {
// Traced frames kept in memory: 32 at 960 x 540 are 66 MB.
constexpr size_t kCachedFrames = 32;
}  // namespace

std::unique_ptr<Background> Background::traced(const std::string& site_json, uint32_t width, uint32_t height,
                                               uint32_t samples, float exposure) {
    std::unique_ptr<Background> background(new Background());
    background->width_ = width;
    background->height_ = height;
    background->samples_ = samples;
    background->exposure_ = exposure;
    background->context_ = std::make_unique<VulkanContext>(vulkanOptionsFromEnvironment());
    background->renderer_ = std::make_unique<bench::TruthRenderer>(*background->context_, loadSiteConfig(site_json),
                                                                   /*cache_folder=*/"", /*context_hash=*/"");
    return background;
}

std::unique_ptr<Background> Background::photo(const std::string& path, float exposure) {
    render_cli::CameraImage image = render_cli::readCameraImage(path);
    std::unique_ptr<Background> background(new Background());
    background->width_ = image.width;
    background->height_ = image.height;
    background->exposure_ = exposure > 0.0f ? exposure : 1.0f;  // gusuku-render's for an IMAGE
    background->photo_ = std::move(image.srgb_rgba8);
    return background;
}

Background::~Background() = default;

const std::vector<uint8_t>& Background::frameFor(const bench::BenchView& view, const bench::BenchCondition& condition,
                                                 double& seconds) {
    seconds = 0.0;
    if (!renderer_) return photo_;
    const Key key{view.position_enu.x, view.position_enu.y, view.position_enu.z, view.look_at_enu.x,
                  view.look_at_enu.y,  view.look_at_enu.z,  view.horizontal_fov_deg, condition.utc_seconds,
                  condition.cloud_cover};
    if (const auto found = cache_.find(key); found != cache_.end()) return found->second;
    // As gusuku-render's renderSampleCameraFrame (bench/render/sample_camera.cpp), on a renderer kept open.
    const bench::TracedFrame traced =
        renderer_->render(bench::siteCameraRequest(view, width_, height_, condition, samples_), /*use_cache=*/false);
    seconds = traced.trace_seconds + traced.denoise_seconds;
    if (exposure_ <= 0.0f) exposure_ = bake::middleGreyExposure(traced.denoised);
    if (cache_.size() >= kCachedFrames) cache_.erase(cache_.begin());
    return cache_[key] = bake::packRgba8Srgb(traced.denoised, exposure_);
}

}  // namespace gusuku::view

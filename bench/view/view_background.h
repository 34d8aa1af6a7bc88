#pragma once
// gusuku-view's camera background: a photo, or the site WITHOUT the building path-traced from the view (the
// bench's TruthRenderer, denoised, exactly as gusuku-render's `--camera sample` makes it, so a screenshot can be
// held to gusuku-render's composite of the same pose and instant). Traced frames are kept in memory by view,
// instant and cloud cover, so returning to a view costs nothing. The tracing runs on a headless device of its own
// (vulkan_context.h): it is the tool's, not part of the app's frame the window shows.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "gusuku/gpu/vulkan_context.h"
#include "truth_renderer.h"

namespace gusuku::view {

class Background {
public:
    /// A traced background of `site_json`, width x height, `samples` a pixel; exposure <= 0: the first frame's
    /// middle grey, kept for every later frame (so the picture does not pump as the view moves).
    static std::unique_ptr<Background> traced(const std::string& site_json, uint32_t width, uint32_t height,
                                              uint32_t samples, float exposure);
    /// A photo (gusuku-render's camera reader: its own size, sRGB bytes); exposure <= 0: 1.
    static std::unique_ptr<Background> photo(const std::string& path, float exposure);
    ~Background();

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    /// The runtime's exposure for this background (display value per unit radiance).
    float exposure() const { return exposure_; }
    bool isTraced() const { return static_cast<bool>(renderer_); }

    /// The background for this view, instant and cover: the photo as it is, or a traced frame (from the cache
    /// when it holds it). `seconds` is what the tracing took (0 from the cache or for a photo).
    const std::vector<uint8_t>& frameFor(const bench::BenchView& view, const bench::BenchCondition& condition,
                                         double& seconds);

private:
    Background() = default;
    uint32_t width_ = 0, height_ = 0, samples_ = 0;
    float exposure_ = 1.0f;
    std::vector<uint8_t> photo_;
    std::unique_ptr<VulkanContext> context_;
    std::unique_ptr<bench::TruthRenderer> renderer_;
    using Key = std::tuple<double, double, double, double, double, double, double, double, float>;
    std::map<Key, std::vector<uint8_t>> cache_;
};

}  // namespace gusuku::view

#pragma once
// The bench's path-traced frames of the site (gusuku_bake/camera_tracer.h), with a cache on disk:
//   - WITH the building: the truth, and the path tracer's own modes;
//   - WITHOUT the building: the camera frame the runtime receives.
// A condition is an instant and a cloud cover: the sunny sky with the SPA sun at that instant, the overcast sky,
// or (partial cover c) their blend (1 - c) sunny + c overcast, linear in radiance, as gusuku-render makes its
// camera frames and as the runtime blends its slots. The scene is loaded and uploaded once.
//
// Cached frames are keyed by everything that changes their bits: the view and size, the instant, the cover, the
// samples, the seed, with or without the building, raw or denoised, and a hash of the site (site.json, the
// skies' paths) and of the bake set's manifest; a key's file holds the key itself and is checked on reading,
// so a hash collision or a stale file is rendered afresh, never used.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/assets/image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/assets/site.h"

namespace gusuku::bench {

/// Where the camera stands and looks, and its horizontal field of view.
struct BenchView {
    glm::dvec3 position_enu{0.0, -25.0, 6.0};
    glm::dvec3 look_at_enu{0.0, 0.0, 2.0};
    double horizontal_fov_deg = 60.0;
};

struct BenchCondition {
    double utc_seconds = 0.0;
    float cloud_cover = 0.0f;  ///< 0 sunny, 1 overcast
    /// The field's skies that one cover cannot say (issue 41 item 4), applied to the sunny part only: E_sun times
    /// sun_scale (0: the sun behind a cloud with blue sky around it; 1/3: thin cloud) and the sunny sky's radiance
    /// times sky_scale (thin cloud scatters the beam's loss into a brighter sky).
    float sun_scale = 1.0f;
    float sky_scale = 1.0f;
};

struct TracedFrameRequest {
    BenchView view;
    uint32_t width = 320, height = 180;
    BenchCondition condition;
    uint32_t samples_per_pixel = 256;
    uint32_t seed = 1;
    bool include_building = true;
    bool denoise = false;  ///< also return the filtered frame (gusuku_bake/camera_denoise.h)
};

/// The truth's request (the building in) for this view, size, condition, samples and seed: seed 2 is the
/// second estimate that measures the truth's own noise.
inline TracedFrameRequest truthRequest(const BenchView& view, uint32_t width, uint32_t height,
                                       const BenchCondition& condition, uint32_t samples, uint32_t seed) {
    TracedFrameRequest request;
    request.view = view;
    request.width = width;
    request.height = height;
    request.condition = condition;
    request.samples_per_pixel = samples;
    request.seed = seed;
    request.include_building = true;
    return request;
}

/// A camera frame of the site as it stands, without the building and denoised: the background gusuku-render's
/// --camera sample and gusuku-view draw the building into (the truth's request, seed 1, the building out).
inline TracedFrameRequest siteCameraRequest(const BenchView& view, uint32_t width, uint32_t height,
                                            const BenchCondition& condition, uint32_t samples_per_pixel) {
    TracedFrameRequest request = truthRequest(view, width, height, condition, samples_per_pixel, 1);
    request.include_building = false;
    request.denoise = true;
    return request;
}

struct TracedFrame {
    ImageRGBA linear;            ///< the raw estimate: linear Rec.709 radiance, row 0 at the top
    ImageRGBA denoised;          ///< the filtered estimate when asked for, else empty
    double trace_seconds = 0.0;  ///< tracing (guides included); 0 when it came from the cache
    double denoise_seconds = 0.0;
    bool from_cache = false;
};

class TruthRenderer {
public:
    /// Loads the site (InputError for its files) and uploads it. cache_folder empty: no cache. `context_hash`
    /// is mixed into every key (the bake set's manifest, so a new bake makes new truths).
    TruthRenderer(const GpuDevice& gpu, const SiteConfig& site, std::string cache_folder, std::string context_hash);
    ~TruthRenderer();

    /// The frame, from the cache when it holds the key (use_cache), else traced (and stored).
    TracedFrame render(const TracedFrameRequest& request, bool use_cache = true);

    size_t triangleCount() const;
    const SiteConfig& site() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace gusuku::bench

// The bench's path-traced frames and their cache (see truth_renderer.h).

#include "truth_renderer.h"

#include <chrono>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "camera_view.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku_bake/camera_denoise.h"
#include "gusuku_bake/camera_frame.h"
#include "gusuku_bake/camera_tracer.h"
#include "gusuku_bake/content_hash.h"

namespace gusuku::bench {

struct TruthRenderer::State {
    const GpuDevice& gpu;
    SiteConfig site;
    bake::CameraSite camera_site;
    std::unique_ptr<bake::CameraTracer> tracer;
    std::optional<bake::SlotLighting> overcast;
    std::string cache_folder;
    std::string context_hash;
};

TruthRenderer::TruthRenderer(const GpuDevice& gpu, const SiteConfig& site, std::string cache_folder,
                             std::string context_hash)
    : state_(new State{gpu, site, bake::loadCameraSite(site), nullptr, std::nullopt, std::move(cache_folder),
                       std::move(context_hash)}) {
    state_->tracer = std::make_unique<bake::CameraTracer>(gpu, state_->camera_site.scene);
    if (state_->camera_site.overcast)
        state_->overcast = bake::lightCameraCondition(state_->site, state_->camera_site, bake::overcastCondition());
}

TruthRenderer::~TruthRenderer() = default;

size_t TruthRenderer::triangleCount() const { return state_->tracer->triangleCount(); }
const SiteConfig& TruthRenderer::site() const { return state_->site; }

namespace {

constexpr char kCacheMagic[8] = {'G', 'S', 'K', 'T', 'R', 'U', 'T', '1'};

std::string keyOf(const TracedFrameRequest& request, const std::string& context_hash) {
    std::ostringstream key;
    key.precision(17);
    key << "view " << request.view.position_enu.x << ',' << request.view.position_enu.y << ','
        << request.view.position_enu.z << " at " << request.view.look_at_enu.x << ',' << request.view.look_at_enu.y
        << ',' << request.view.look_at_enu.z << " fov " << request.view.horizontal_fov_deg << " size "
        << request.width << 'x' << request.height << " utc " << request.condition.utc_seconds << " cover "
        << request.condition.cloud_cover;
    // Only a field condition names its scales, so the caches of every earlier condition keep their keys.
    if (request.condition.sun_scale != 1.0f || request.condition.sky_scale != 1.0f)
        key << " sun " << request.condition.sun_scale << " sky " << request.condition.sky_scale;
    key << " spp " << request.samples_per_pixel << " seed " << request.seed
        << " building " << request.include_building << " denoise " << request.denoise << " context "
        << context_hash;
    return key.str();
}

std::optional<ImageRGBA> readCached(const std::string& path, const std::string& key, uint32_t width,
                                    uint32_t height) {
    if (!std::filesystem::exists(path)) return std::nullopt;
    const std::string bytes = readWholeFile(path);
    const size_t texel_bytes = size_t(width) * height * 4 * sizeof(float);
    const size_t header = sizeof kCacheMagic + sizeof(uint32_t) + key.size();
    if (bytes.size() != header + texel_bytes || std::memcmp(bytes.data(), kCacheMagic, sizeof kCacheMagic) != 0)
        return std::nullopt;
    uint32_t key_size = 0;
    std::memcpy(&key_size, bytes.data() + sizeof kCacheMagic, sizeof key_size);
    if (key_size != key.size() || bytes.compare(sizeof kCacheMagic + sizeof key_size, key.size(), key) != 0)
        return std::nullopt;
    ImageRGBA image;
    image.width = int(width);
    image.height = int(height);
    image.texels.resize(size_t(width) * height * 4);
    std::memcpy(image.texels.data(), bytes.data() + header, texel_bytes);
    return image;
}

void writeCached(const std::string& path, const std::string& key, const ImageRGBA& image) {
    std::string bytes(kCacheMagic, sizeof kCacheMagic);
    const uint32_t key_size = uint32_t(key.size());
    bytes.append(reinterpret_cast<const char*>(&key_size), sizeof key_size);
    bytes += key;
    bytes.append(reinterpret_cast<const char*>(image.texels.data()), image.texels.size() * sizeof(float));
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

}  // namespace

TracedFrame TruthRenderer::render(const TracedFrameRequest& request, bool use_cache) {
    const std::string key = keyOf(request, state_->context_hash);
    const std::string path =
        state_->cache_folder.empty() ? std::string() : state_->cache_folder + "/" + bake::ContentHash().addBytes(key.data(), key.size()).hex() + ".frame";
    const std::string denoised_path = path.empty() ? path : path.substr(0, path.size() - 6) + ".filtered.frame";
    TracedFrame frame;
    if (use_cache && !path.empty())
        if (std::optional<ImageRGBA> cached = readCached(path, key, request.width, request.height)) {
            std::optional<ImageRGBA> denoised;
            if (request.denoise) denoised = readCached(denoised_path, key + " filtered", request.width, request.height);
            if (!request.denoise || denoised) {
                frame.linear = std::move(*cached);
                if (denoised) frame.denoised = std::move(*denoised);
                frame.from_cache = true;
                return frame;
            }
        }

    const CameraIntrinsics intrinsics =
        CameraIntrinsics::fromFieldOfView(request.width, request.height, request.view.horizontal_fov_deg);
    const CameraPose pose = bench_common::lookAtPose(request.view.position_enu, request.view.look_at_enu);
    bake::CameraRenderOptions options;
    options.samples_per_pixel = request.samples_per_pixel;
    options.max_bounces = uint32_t(state_->site.bake.max_bounces);
    options.seed = request.seed;
    options.include_building = request.include_building;

    using Clock = std::chrono::steady_clock;
    auto seconds = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };
    // Adds weight x (the raw and the filtered estimate under this light) to the frame.
    auto addLight = [&](const bake::SlotLighting& lighting, float weight, double sun_scale) {
        Clock::time_point start = Clock::now();
        bake::CameraLight light = bake::cameraLightOf(lighting);
        light.sun.irradiance_rgb *= sun_scale;
        if (!(sun_scale > 0.0)) light.sun.present = false;
        const bake::CameraRender render = state_->tracer->render(light, intrinsics, pose, options);
        frame.trace_seconds += seconds(start);
        auto accumulate = [weight](ImageRGBA& sum, const ImageRGBA& image) {
            if (sum.texels.empty()) {
                sum = image;
                for (size_t i = 0; i < sum.texels.size(); ++i) sum.texels[i] *= i % 4 == 3 ? 1.0f : weight;
            } else {
                for (size_t i = 0; i < sum.texels.size(); ++i)
                    if (i % 4 != 3) sum.texels[i] += weight * image.texels[i];
            }
        };
        accumulate(frame.linear, render.radiance);
        if (request.denoise) {
            start = Clock::now();
            accumulate(frame.denoised,
                       bake::denoiseCameraFrame(render, intrinsics, pose,
                                                bake::cameraDenoiseOptionsForSamples(request.samples_per_pixel)));
            frame.denoise_seconds += seconds(start);
        }
    };
    const float cover = request.condition.cloud_cover;
    const float sky_scale = request.condition.sky_scale, sun_scale = request.condition.sun_scale;
    if (!(sky_scale > 0.0f) || !(sun_scale >= 0.0f))
        throw std::invalid_argument("TruthRenderer: a condition's sky_scale must be > 0 and its sun_scale >= 0");
    // One trace of the sunny light with weight (1 - cover) sky_scale: its sky scaled so, its sun by sun_scale
    // (E_sun pre-divided by sky_scale, which the weight puts back).
    if (cover < 1.0f)
        addLight(bake::lightCameraCondition(state_->site, state_->camera_site,
                                            bake::sunnyConditionAt(request.condition.utc_seconds)),
                 (1.0f - cover) * sky_scale, double(sun_scale) / double(sky_scale));
    if (cover > 0.0f) {
        if (!state_->overcast)
            throw std::invalid_argument(state_->site.file + ": /skies/overcast: a cloudy frame needs an overcast sky");
        addLight(*state_->overcast, cover, 1.0);
    }
    if (!path.empty()) {
        writeCached(path, key, frame.linear);
        if (request.denoise) writeCached(denoised_path, key + " filtered", frame.denoised);
    }
    return frame;
}

}  // namespace gusuku::bench

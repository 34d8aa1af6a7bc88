#include "gusuku_bake/camera_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gusuku/maths/colour.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/formats/input_error.h"
#include "bake_geometry.h"
#include "gusuku_bake/camera_denoise.h"
#include "gusuku_bake/ground_grid.h"

namespace gusuku::bake {

CameraSite loadCameraSite(const SiteConfig& site, int max_texture_size) {
    CameraSite camera_site;
    GltfLoadOptions building_options;
    building_options.enu_from_model = site.building.enuFromModel(site.site.reference);
    building_options.max_texture_size = max_texture_size;
    const TriangleMesh building = loadGltf(site.building.path, building_options, &camera_site.warnings);
    const TriangleMesh site_mesh = loadSiteMeshOrStandIn(site, meshBounds(building), max_texture_size,
                                                         camera_site.warnings, camera_site.site_mesh_is_stand_in);
    camera_site.scene = makeTraceScene(building, &site_mesh);
    camera_site.sunny = prepareSky(site.sunny_sky);
    if (site.overcast_sky) camera_site.overcast = prepareSky(*site.overcast_sky);
    return camera_site;
}

BakeSlot findSiteSlot(const SiteConfig& site, const std::string& name) {
    std::string names;
    for (const BakeSlot& slot : site.bake.slots) {
        if (slot.name == name) return slot;
        names += (names.empty() ? "" : ", ") + slot.name;
    }
    throw InputError(site.file, "/bake/slots", "no slot named '" + name + "' (slots: " + names + ")");
}

BakeSlot sunnyConditionAt(double utc_unix_seconds) {
    BakeSlot slot;
    slot.name = "sunny";
    slot.sky = SlotSky::Sunny;
    slot.utc_seconds = utc_unix_seconds;
    return slot;
}

BakeSlot overcastCondition() {
    BakeSlot slot;
    slot.name = "overcast";
    slot.sky = SlotSky::Overcast;
    return slot;
}

SlotLighting lightCameraCondition(const SiteConfig& site, const CameraSite& camera_site, const BakeSlot& condition) {
    if (condition.sky == SlotSky::Overcast && !camera_site.overcast)
        throw InputError(site.file, "/skies/overcast", "an overcast frame needs an overcast sky");
    return lightSlot(site, condition, camera_site.sunny, camera_site.overcast ? &*camera_site.overcast : nullptr);
}

CameraLight cameraLightOf(const SlotLighting& lighting) { return CameraLight{&lighting.sky->tables, lighting.sun}; }

SiteCameraFrame renderSiteCameraFrame(const GpuDevice& gpu, const SiteConfig& site, const BakeSlot& condition,
                                      const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                      uint32_t samples_per_pixel, const SiteCameraOptions& options) {
    SiteCameraFrame frame;
    const CameraSite camera_site = loadCameraSite(site, options.max_texture_size);
    const SlotLighting lighting = lightCameraCondition(site, camera_site, condition);
    frame.warnings = camera_site.warnings;
    frame.warnings.insert(frame.warnings.end(), lighting.warnings.begin(), lighting.warnings.end());
    frame.sun = lighting.sun;
    frame.sun_irradiance_source = lighting.sun_irradiance_source;

    CameraTracer tracer(gpu, camera_site.scene, options.max_texture_size);
    CameraRenderOptions render_options;
    render_options.samples_per_pixel = samples_per_pixel;
    render_options.max_bounces = uint32_t(site.bake.max_bounces);
    render_options.seed = options.seed;
    render_options.include_building = options.include_building;
    render_options.progress = options.progress;
    frame.render = tracer.render(cameraLightOf(lighting), intrinsics, pose, render_options);
    if (options.denoise) {
        const auto start = std::chrono::steady_clock::now();
        frame.denoised = denoiseCameraFrame(frame.render, intrinsics, pose,
                                            cameraDenoiseOptionsForSamples(samples_per_pixel));
        frame.denoise_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return frame;
}

std::vector<uint8_t> packRgba8Srgb(const ImageRGBA& linear, float exposure) {
    const size_t pixel_count = size_t(linear.width) * size_t(linear.height);
    std::vector<uint8_t> bytes(pixel_count * 4);
    for (size_t i = 0; i < pixel_count; ++i) {
        for (int channel = 0; channel < 3; ++channel) {
            // NaN fails every comparison: std::clamp would pass it through, so test it first.
            const float value = linear.texels[4 * i + channel] * exposure;
            const float clamped = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
            bytes[4 * i + channel] = uint8_t(std::lround(srgbEncode(clamped) * 255.0f));
        }
        bytes[4 * i + 3] = 255;
    }
    return bytes;
}

float middleGreyExposure(const ImageRGBA& linear) {
    const size_t pixel_count = size_t(linear.width) * size_t(linear.height);
    if (pixel_count == 0) return 1.0f;
    // The log-average with a small floor (Reinhard et al. 2002), in double: a 1280 x 720 sum.
    constexpr double kFloor = 1e-6;
    double log_sum = 0.0;
    double max_luminance = 0.0;
    for (size_t i = 0; i < pixel_count; ++i) {
        const glm::dvec3 rgb(linear.texels[4 * i], linear.texels[4 * i + 1], linear.texels[4 * i + 2]);
        const double luminance = std::max(0.0, luminanceRec709(rgb));
        max_luminance = std::max(max_luminance, luminance);
        log_sum += std::log(kFloor + luminance);
    }
    if (!(max_luminance > 0.0)) return 1.0f;
    return float(0.18 / std::exp(log_sum / double(pixel_count)));
}

void writeCameraPng(const std::string& path, const ImageRGBA& linear, float exposure) {
    ImageRGBA exposed = linear;
    for (size_t i = 0; i < exposed.texels.size(); ++i)
        if (i % 4 != 3) exposed.texels[i] *= exposure;
    writePngSrgb(path, exposed, false);
}

}  // namespace gusuku::bake

// The path-traced camera frame of a site (see sample_camera.h).

#include "sample_camera.h"

#include "gusuku/site.h"
#include "gusuku_bake/camera_frame.h"

namespace gusuku::render_cli {

SampleCameraFrame renderSampleCameraFrame(const GpuDevice& gpu, const std::string& site_json, double utc_seconds,
                                          float cloud_cover, const CameraIntrinsics& intrinsics,
                                          const CameraPose& pose, uint32_t samples_per_pixel, float exposure) {
    const SiteConfig site = loadSiteConfig(site_json);
    SampleCameraFrame frame;
    ImageRGBA blended;
    auto add = [&](const BakeSlot& condition, float weight) {
        if (weight <= 0.0f) return;
        const bake::SiteCameraFrame rendered =
            bake::renderSiteCameraFrame(gpu, site, condition, intrinsics, pose, samples_per_pixel);
        frame.trace_seconds += rendered.render.trace_seconds + rendered.denoise_seconds;
        frame.rays_traced += rendered.render.rays_traced;
        const ImageRGBA& image = rendered.denoised.texels.empty() ? rendered.render.radiance : rendered.denoised;
        if (blended.texels.empty()) {
            blended = image;
            for (float& value : blended.texels) value *= weight;
        } else {
            for (size_t index = 0; index < blended.texels.size(); ++index)
                blended.texels[index] += weight * image.texels[index];
        }
    };
    add(bake::sunnyConditionAt(utc_seconds), 1.0f - cloud_cover);
    add(bake::overcastCondition(), cloud_cover);
    for (size_t texel = 3; texel < blended.texels.size(); texel += 4) blended.texels[texel] = 1.0f;
    frame.exposure = exposure > 0.0f ? exposure : bake::middleGreyExposure(blended);
    frame.rgba8 = bake::packRgba8Srgb(blended, frame.exposure);
    return frame;
}

}  // namespace gusuku::render_cli

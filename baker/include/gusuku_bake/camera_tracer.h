#pragma once
// A path-traced pinhole camera on the baker's tracer: the sample site's camera frame (the site without the
// building, as a phone would film it) and the benchmark's ground truth (the site with the building).
//
// What a pixel holds: linear Rec.709 radiance in the sky map's units, the mean over the pixel's area (jittered
// samples, a box filter). A ray that escapes shows the sky map with its sun disc removed (as the bake removes it,
// so the sun is seen only by next-event estimation and never twice); a ray that reaches a surface of albedo rho
// shows rho / pi * (E_sun + E_ind) + emission there, E_sun and E_ind estimated by the bake's own path code
// (shaders/include/irradiance_paths.glsl), so where the bake and this camera should agree they do by
// construction; the back of a one-sided surface is black. Camera conventions are gusuku/runtime/runtime.h's (x right,
// y down, z forward; u = fx X / Z + cx, v = fy Y / Z + cy; pixel (0, 0)'s centre at (0.5, 0.5)).
//
// Cost: the camera ray, then the bake's path from its hit (a sun ray and a bounce ray per vertex, one more where
// the sky is uneven); the guides add one ray per pixel, and up to 8 more when the sun shines (a 2 x 2 grid of camera and
// shadow rays). A render is deterministic: the same scene, light, view, options and seed give the same bits,
// however the samples were split into dispatches.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/assets/image.h"
#include "gusuku/runtime/runtime.h"  // CameraIntrinsics, CameraPose: the runtime's camera, used as is
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

/// The light of one condition: a sky map with its sun disc removed (its sampling tables), and the sun.
struct CameraLight {
    const SkySamplingTables* sky = nullptr;  ///< must stay alive during render()
    SunLight sun;                            ///< absent for an overcast sky
};

struct CameraRenderOptions {
    uint32_t samples_per_pixel = 64;
    uint32_t max_bounces = 3;       ///< of the irradiance paths from the first hit (site.json bake.max_bounces)
    uint32_t seed = 1;              ///< another seed, another noise; the same seed, the same bits
    bool include_building = false;  ///< false: the site as it stands today (the camera frame)
    SkySampling sky_sampling = SkySampling::Automatic;  ///< as the bake: resolved per sky
    float ray_offset_m = 1e-3f;     ///< how far rays start off their surface (the bake's)
    /// Called after every dispatch with the samples per pixel done so far (progress bars). May be empty.
    std::function<void(uint32_t samples_done, uint32_t samples_total)> progress;
};

/// The first hit of each pixel's centre ray: what the denoiser is guided by.
struct CameraGuides {
    int width = 0;
    int height = 0;
    /// CAMERA_GUIDE_VEC4S_PER_PIXEL (3) per pixel, row 0 at the top: [0] shading normal xyz (ENU, facing the
    /// camera), w hit distance in metres (-1: sky); [1] albedo rgb, w 1 on a lit side (0: sky, or the back of a
    /// one-sided surface); [2] emitted radiance rgb, w the direct sun's share: the mean over a 2 x 2 grid of
    /// rays in the pixel of max(0, n . s) where the sun's centre is visible from their hit, else 0.
    std::vector<glm::vec4> texels;

    const glm::vec4& normalDistance(int x, int y) const { return texels[3 * (size_t(y) * size_t(width) + size_t(x))]; }
    const glm::vec4& albedoLit(int x, int y) const { return texels[3 * (size_t(y) * size_t(width) + size_t(x)) + 1]; }
    const glm::vec4& emissionSunShare(int x, int y) const { return texels[3 * (size_t(y) * size_t(width) + size_t(x)) + 2]; }
};

struct CameraRender {
    ImageRGBA radiance;     ///< the raw estimate: linear Rec.709, row 0 at the top, alpha 1
    CameraGuides guides;
    uint32_t samples_per_pixel = 0;
    uint64_t rays_traced = 0;    ///< guide rays included
    double trace_seconds = 0.0;  ///< wall time of the dispatches (guide pass included)
};

/// Uploads a scene once and renders any number of views of it under any light. Not thread-safe.
class CameraTracer {
public:
    /// Builds the BVH over scene.mesh and uploads it with the scene's materials and textures, each texture
    /// box-downsampled to at most max_texture_size (a camera sees the detail a bake does not need: the default
    /// keeps 2048; the whole texture buffer must fit the device's maxStorageBufferRange, 128 MiB on lavapipe).
    /// `gpu` must outlive the tracer. Cost: the BVH build (O(n log n), bvh.h), plus the upload.
    CameraTracer(const GpuDevice& gpu, const TraceScene& scene, int max_texture_size = 2048);
    ~CameraTracer();
    CameraTracer(const CameraTracer&) = delete;
    CameraTracer& operator=(const CameraTracer&) = delete;

    /// Renders intrinsics.width x intrinsics.height pixels. Throws std::invalid_argument (one line naming the
    /// field) for a zero or non-finite focal length, a non-finite principal point or pose, a rotation that is
    /// not orthonormal (to 1e-3), an empty image, zero samples or a null sky, and for more pixels than the device
    /// allows: the guides (48 bytes a pixel) must fit maxStorageBufferRange and the pixels one row of
    /// workgroups (64 x maxComputeWorkGroupCount[0]); on lavapipe 2.79 M pixels (1920 x 1080 fits).
    CameraRender render(const CameraLight& light, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                        const CameraRenderOptions& options);

    size_t triangleCount() const { return scene_.triangle_count; }

private:
    const GpuDevice& gpu_;
    std::unique_ptr<GpuSubmitter> submitter_;
    std::unique_ptr<ComputePipeline> trace_pipeline_;       ///< camera_trace.comp: one path per invocation
    std::unique_ptr<ComputePipeline> accumulate_pipeline_;  ///< bake_accumulate.comp: ordered sums per pixel
    TraceSceneGpu scene_;  ///< bindings 0-4
    SkyTablesGpu sky_;     ///< bindings 5-6, the light's of the last render
    GpuBuffer ray_counter_;
    GpuBuffer sample_estimates_;  ///< one chunk's per-sample radiance, grown as needed
};

}  // namespace gusuku::bake

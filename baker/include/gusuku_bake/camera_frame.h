#pragma once
// Camera frames of a site, for gusuku-render (the sample site has no photograph, so its camera frame is
// path-traced: the site WITHOUT the building, from the pose) and for the benchmark (the site WITH the building:
// the ground truth). One call loads site.json's site, lights it for a condition and renders; the parts are
// public too, so a tool rendering many frames loads the site and uploads the scene once.
//
// Units: linear Rec.709 radiance in the sky map's units, the bake set's (a baked irradiance E shows on an
// albedo rho as rho E / pi in the same units); sRGB only at the very end (packRgba8Srgb, writeCameraPng).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/assets/image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/camera_tracer.h"
#include "gusuku_bake/slot_lighting.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

/// A site loaded for the camera: the bake's trace scene (building triangles flagged kTriangleFlagBuilding, so
/// one upload serves frames with and without it) and its skies with the sun discs removed, as the bake
/// prepares them (prepareSky).
struct CameraSite {
    TraceScene scene;
    PreparedSky sunny;
    std::optional<PreparedSky> overcast;
    bool site_mesh_is_stand_in = false;  ///< no sfm_mesh: the bake's flat grey stand-in ground
    std::vector<std::string> warnings;
};

/// Loads the building (placed as site.json says) and the SfM mesh (or the bake's flat stand-in when site.json
/// names none, sized as the bake sizes it) with textures up to max_texture_size, and prepares the skies. Bad
/// input throws InputError naming the file.
CameraSite loadCameraSite(const SiteConfig& site, int max_texture_size = 2048);

/// site.json's slot of this name; InputError(site.file, "/bake/slots", ...) listing the names when none.
BakeSlot findSiteSlot(const SiteConfig& site, const std::string& name);
/// A sunny condition at any instant (not one of site.json's slots): the sunny sky, the sun placed by SPA.
BakeSlot sunnyConditionAt(double utc_unix_seconds);
/// The overcast condition: the overcast sky, no sun.
BakeSlot overcastCondition();

/// The light of a condition exactly as the bake lights a slot (lightSlot: SPA sun, E_sun from the map's disc or
/// the clear-sky model). InputError(site.file, "/skies/overcast", ...) for an overcast condition on a site with
/// no overcast sky. The result points into `camera_site`.
SlotLighting lightCameraCondition(const SiteConfig& site, const CameraSite& camera_site, const BakeSlot& condition);

/// The tracer's view of that light.
CameraLight cameraLightOf(const SlotLighting& lighting);

struct SiteCameraOptions {
    bool include_building = false;  ///< false: the camera frame; true: the benchmark's truth
    bool denoise = true;            ///< also return the filtered frame (camera_denoise.h)
    uint32_t seed = 1;
    /// Textures are kept up to this size for the camera (the bake traces at 512: albedo is all it needs).
    int max_texture_size = 2048;
    std::function<void(uint32_t samples_done, uint32_t samples_total)> progress;
};

struct SiteCameraFrame {
    CameraRender render;               ///< the raw estimate (render.radiance), guides, rays and time
    ImageRGBA denoised;                ///< the filtered frame; empty when options.denoise is false
    double denoise_seconds = 0.0;
    SunLight sun;                      ///< the sun that lit the frame (absent when overcast or set)
    std::string sun_irradiance_source; ///< as the manifest records it
    std::vector<std::string> warnings; ///< from loading and lighting
};

/// The one call: loads `site`, lights it for `condition` (a site.json slot, sunnyConditionAt or
/// overcastCondition), renders samples_per_pixel samples of every pixel with site.json's bake.max_bounces, and
/// filters. Errors: InputError for the site's files, std::invalid_argument for the view (CameraTracer::render).
SiteCameraFrame renderSiteCameraFrame(const GpuDevice& gpu, const SiteConfig& site, const BakeSlot& condition,
                                      const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                      uint32_t samples_per_pixel, const SiteCameraOptions& options = {});

/// The runtime's camera input from a linear frame: RGBA8, RGB sRGB-encoded (gusuku/maths/colour.h's srgbEncode) after
/// multiplying by `exposure` and clamping to [0, 1], rounded to nearest; alpha 255; row 0 at the top, width * 4
/// bytes a row (gusuku/runtime/runtime.h's image convention).
std::vector<uint8_t> packRgba8Srgb(const ImageRGBA& linear, float exposure = 1.0f);

/// An exposure that puts the frame's log-average luminance at middle grey (0.18; Reinhard et al. 2002's key),
/// sky and surfaces alike. 1 for a black frame.
float middleGreyExposure(const ImageRGBA& linear);

/// Writes the frame times `exposure` as an 8-bit sRGB PNG (gusuku/assets/image.h's writePngSrgb: atomic, clamped).
void writeCameraPng(const std::string& path, const ImageRGBA& linear, float exposure = 1.0f);

}  // namespace gusuku::bake

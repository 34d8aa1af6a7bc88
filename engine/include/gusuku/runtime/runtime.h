#pragma once
// gusuku_runtime: draws a lost building into the camera frame with baked global illumination, a real-time sun
// and its shadow on the real ground, and matches its colour to the camera (docs/design.md 3, 4 and 8).
//
// What an AR app links: Vulkan and glm only. It opens on the app's own Vulkan device (GpuDevice, gpu_device.h:
// the runtime copies the description and creates nothing global, only its own pools, buffers, images and
// pipelines on that device) and holds the bake set in GPU memory. Per frame it takes the camera (host pixels or
// the app's VkImage, in the platform's format), intrinsics, pose, UTC time, position and weather, and draws the
// composite on the GPU; it reads the composite back only when the caller asks for bytes. Everything a frame
// needs is allocated when the runtime opens: a frame allocates nothing on the host or the device
// (tests/test_runtime_allocations.cpp counts), except a view the first time it meets an app camera image.
//
// Device requirements, checked when the runtime opens (RuntimeError kDevice naming what is missing; docs/runtime.md
// "Device requirements"): Vulkan 1.0; a queue with graphics and compute; optimal-tiling R8G8B8A8_SRGB as a blended
// colour attachment, sampled and a transfer source; D32_SFLOAT as a depth attachment and a sampled image;
// D32_SFLOAT_S8_UINT or D24_UNORM_S8_UINT as a depth-stencil attachment (the main pass); R16G16B16A16_SFLOAT and
// the lightmap format (E5B9G9R9_UFLOAT_PACK32 under the default kAuto) sampled with linear filtering; the camera
// format's plane formats sampled (R8G8B8A8_SRGB, B8G8R8A8_SRGB, or R8_UNORM and R8G8_UNORM);
// RuntimeOptions::msaa_samples among the framebuffer colour and depth sample counts; the frame size within
// maxImageDimension2D and maxFramebufferWidth/Height and, where the colour matches run, its 4 bytes a pixel within
// maxStorageBufferRange (lavapipe's 128 MiB: 2^25 pixels). Timeline semaphores in FrameSync only if the app
// enabled them on its device. The colour matches
// (FrameInput::colour_match kReinhard, kPreserve, kGround) also need a Vulkan 1.1 instance
// (GpuDevice::instance_api_version) and subgroup arithmetic in compute shaders; without them the runtime opens and
// refuses only those frames (the default, kAuto, is then off).
// The zero-copy camera (RuntimeOptions::camera_ycbcr_image) needs the Vulkan 1.1 feature samplerYcbcrConversion and
// G8_B8R8_2PLANE_420_UNORM sampled with midpoint or cosited chroma. Nothing else: no extension, no other optional
// feature.
//
// Threads and lifetimes: one Runtime is used from one thread at a time (its calls are not synchronised with
// each other); several runtimes may run on several threads on one device, and share its queue when the
// GpuDevice names the queue mutex the app holds around its own submissions. The app's instance, device and
// queue outlive the runtime; destroying the runtime waits for its frames on the GPU. A FrameInput's pointers are
// read during renderFrame only; compositeImage() belongs to the runtime and is rewritten frames_in_flight frames
// later. The static helpers (projectToPixel, lookingAt, fromFieldOfView, estimatedFrom) are pure and thread-safe.
//
// Conventions, pinned by tests (tests/test_runtime.cpp: RuntimeCamera.ProjectionConventionIsPinned and
// RuntimeTest.RendersTheBuildingWherePinholeProjectionPutsIt; tests/test_frame_preparation.cpp for the clip matrix):
//   - World: the site's east-north-up frame, metres (the bake set's).
//   - Camera frame: x right, y down, z forward (the OpenCV / photogrammetry convention). CameraPose holds the
//     camera's centre in ENU and the rotation whose columns are the camera's x, y and z axes in ENU.
//   - Pixels: (0, 0) is the top-left corner of the top-left pixel, whose centre is (0.5, 0.5). A point at
//     camera coordinates (X, Y, Z), Z > 0, lands at u = fx X / Z + cx, v = fy Y / Z + cy.
//   - Images: RGBA8, RGB sRGB-encoded, row 0 at the top, width * 4 bytes per row, no padding. Alpha passes
//     through the camera's, 255 on the building.
//
// Errors: every call of this header that can fail throws gusuku::RuntimeError (a code plus a one-line message
// naming the input and the field), and nothing else: device failures are kDevice, host memory kOutOfMemory. The
// C API (gusuku.h) turns every error into a code and a message and never lets an exception out.

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/gpu/gpu_device.h"

namespace gusuku {

enum class RuntimeErrorCode {
    kInvalidBakeSet = 1,  ///< the bake set is inconsistent (sizes, NaN texels, a slot with no images, ...)
    kInvalidFrame = 2,    ///< a frame input is invalid (NaN pose, zero focal length, wrong image size, ...)
    kDevice = 3,          ///< the Vulkan device lacks something the runtime needs, or a Vulkan call failed
    kOutOfMemory = 4,
};

class RuntimeError : public std::runtime_error {
public:
    RuntimeError(RuntimeErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    RuntimeErrorCode code() const { return code_; }

private:
    RuntimeErrorCode code_;
};

/// Pinhole intrinsics in pixels (see the pixel convention above). The frame's images are width x height.
struct CameraIntrinsics {
    double fx = 0.0, fy = 0.0;  ///< focal lengths, pixels, > 0
    double cx = 0.0, cy = 0.0;  ///< principal point, pixels
    uint32_t width = 0, height = 0;

    /// A width x height frame with this horizontal field of view (degrees, (0, 180)), square pixels, the principal
    /// point at the centre. RuntimeError kInvalidFrame for an empty frame or a field of view outside (0, 180).
    static CameraIntrinsics fromFieldOfView(uint32_t width, uint32_t height, double horizontal_fov_deg);
};

/// Where the camera is and where it looks, in the site's ENU frame (see the camera convention above).
struct CameraPose {
    glm::dvec3 position_enu{0.0};
    glm::dmat3 camera_to_enu{1.0};  ///< columns: camera x (right), y (down), z (forward) in ENU; orthonormal

    /// A camera at `position_enu` looking at `target_enu`, the image's up towards ENU +z (towards north when it
    /// looks straight down). RuntimeError kInvalidFrame when the two points coincide.
    static CameraPose lookingAt(const glm::dvec3& position_enu, const glm::dvec3& target_enu);
};

/// A GPS fix. The sun is computed here; the camera pose stays in the site's frame.
struct GeoPosition {
    double latitude_deg = 0.0;   ///< [-90, 90]
    double longitude_deg = 0.0;  ///< [-180, 180]
    double height_m = 0.0;       ///< above the WGS84 ellipsoid
};

/// The weather: cloud cover from 0 (clear: the sunny slots and the real-time sun) to 1 (overcast: the overcast
/// slot, no sun). Between, the baked light blends linearly and, unless sun_scale says otherwise, the direct sun
/// fades with (1 - cover).
struct Weather {
    float cloud_cover = 0.0f;
    /// The sun apart from the sky (gusuku/maths/sun_visibility.h): E_sun and the sun's shadow scaled by this, the
    /// sun's visibility times its strength, in [0, kMaxSunScale], while cloud_cover still blends the slots. Under
    /// broken cloud the real sun is either out (1: a full, hard shadow) or behind a cloud (0), never the quarter sun
    /// that (1 - cover) draws for 6 oktas; a SunVisibilityFilter's sun_visibility * sun_strength is what to pass.
    /// Negative (the default): 1 - cloud_cover, the single-cover model.
    float sun_scale = -1.0f;
    static constexpr float kMaxSunScale = 2.0f;
    static Weather sunny() { return {0.0f}; }
    static Weather overcast() { return {1.0f}; }
    /// The weather read off the camera frame alone (RGBA8 as FrameInput's), for when no weather service
    /// answers: the cover of gusuku/maths/weather_estimate.h (hard shadows on the lower half, a blue sky on the top
    /// rows). Allocates two frame-sized arrays: call it every second or so, not per frame. gusuku-bench measures
    /// how often it picks the better weather.
    static Weather estimatedFrom(const uint8_t* camera_rgba8, uint32_t width, uint32_t height);
};

/// The colour match of a frame, one enum with the GPU state's (gusuku/maths/colour_match.h):
///   kOff       no colour match;
///   kReinhard  Reinhard per-channel Lab transfer: source the baked appearance (manifest colour_statistics),
///              target the camera frame (the seed paper's method);
///   kPreserve  moves lightness and white balance towards the camera but keeps the building's chroma spread (the
///              saturation the paper reports losing);
///   kGround    compares like with like: the camera's pixels of the real ground against what the bake set
///              predicts there (ground albedo x baked and sun irradiance x exposure); the per-channel gain
///              observed / predicted multiplies the building's exposed colour (undoes exposure and white balance,
///              a tone curve to first order). Needs a bake set with ground_grid.albedo: with an older one a
///              frame asking for it throws RuntimeError kInvalidFrame.
///   kAuto      the default: kGround where the bake set has ground albedo and the device has subgroup arithmetic,
///              else kOff; resolved each frame, so it never makes a frame fail.
using ColourMatch = ColourMatchMode;

enum class RenderMode {
    /// gusuku's frame: the bake set's baked indirect light (E_ind) + the real-time sun with a shadow map, the
    /// ground ratio and the colour match
    kBakedLight = 0,
    kDirectOnly = 1,  ///< what AR apps draw today: albedo x (ambient + shadowed sun), a fixed shadow darkening
    /// The paper's name, kept for existing code (the same value; never list both in one switch).
    kProposed = kBakedLight,
};

/// The camera's pixel format, fixed when the runtime opens (RuntimeOptions::camera_format): what the platform
/// delivers, taken as it comes (docs/runtime.md, "Camera formats"). R'G'B' is taken as sRGB-encoded.
enum class CameraFormat {
    kRgba8 = 0,  ///< 4 bytes a pixel, R G B A (Android's RGBA_8888, most desktop sources)
    kBgra8 = 1,  ///< 4 bytes a pixel, B G R A (ARKit/AVFoundation's kCVPixelFormatType_32BGRA)
    kNv12 = 2,   ///< two-plane Y'CbCr 4:2:0: a Y' plane, then interleaved Cb Cr at half size (ARKit's 420f/420v)
    kNv21 = 3,   ///< the same with Cr Cb interleaved (ARCore's / Android camera's YUV_420_888 as NV21)
};
/// Y'CbCr matrix of a kNv12 / kNv21 camera.
enum class YcbcrModel { kBt601 = 0, kBt709 = 1 };
/// Y'CbCr range: narrow (studio: Y' 16-235, Cb Cr 16-240) or full (0-255).
enum class YcbcrRange { kNarrow = 0, kFull = 1 };

/// How the runtime holds the building's lightmaps on the GPU (docs/runtime.md, "Lightmap formats"). The RGB is
/// all the shaders read; the bake set's validity alpha stays on the CPU. Each value but kAuto is a lightmap row of
/// gusuku/formats/format_table.h (its c_enum), which says its Vulkan format, encoder and device feature.
enum class LightmapFormat {
    kE5b9g9r9 = 0,  ///< shared exponent, 4 bytes a texel; every Vulkan device samples and filters it
    kRgba16f = 1,   ///< half floats, 8 bytes a texel (the runtime's format before kE5b9g9r9)
    kRgba32f = 2,   ///< float32, 16 bytes a texel: the reference; needs linear filtering of R32G32B32A32_SFLOAT
    /// ASTC 4x4 HDR (VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK), 1 byte a texel: the bake set's building_blocks (the
    /// runtime pack's, encoded at bake time) as they are. Needs RuntimeOptions::texture_compression_astc_hdr.
    kAstc4x4Hdr = 3,
    /// kAstc4x4Hdr where the app enabled textureCompressionASTC_HDR (texture_compression_astc_hdr), the device
    /// samples and filters the format, and the bake set carries the blocks at the runtime's irradiance scale;
    /// else kE5b9g9r9 (the default). Runtime::lightmapFormat() says which.
    kAuto = 4,
    /// ASTC 6x6 HDR (VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK), 0.44 bytes a texel: as kAstc4x4Hdr, from the pack's
    /// _astc6x6.ktx2 blocks; never chosen by kAuto (more error than 4x4 for its 2.25x less memory).
    kAstc6x6Hdr = 5,
};

/// Options fixed when the runtime opens.
/// Every option is range-checked when the runtime opens: one outside its range (NaN included) is a RuntimeError
/// kInvalidFrame naming it, "options.NAME: VALUE is outside [MIN, MAX]".
struct RuntimeOptions {
    uint32_t frame_width = 1280;   ///< every frame's images must have this size
    uint32_t frame_height = 720;
    /// Shadow map side, texels. Fitted to the building (and the ground it can shade) as seen from the sun, so
    /// 1024 gives about bounds / 1024 per texel. Cost grows with its area (docs/design.md 5).
    uint32_t shadow_map_size = 1024;
    /// Depth bias of the shadow test, in shadow-map texels (slope-scaled by the receiver's normal). [0, 64].
    float shadow_bias_texels = 1.5f;
    /// The building's shadow: r >= 1 gives the sun's disc as the penumbra, searched for blockers up to 2 + r texels
    /// out (so at most 1 + r texels of penumbra radius; runtime_shadow.glsl); 0 gives hard shadows, one bilinear
    /// compare tap (the cheapest). [0, 3].
    uint32_t shadow_pcf_radius = 1;
    /// The shadow maps are drawn for the sun's azimuth and elevation rounded to this step (degrees) and redrawn
    /// only when the rounded sun moves: every 12 s or so at 0.05 degrees, which shifts a 10 m shadow by 9 mm.
    /// The building and the site are static, so nothing else can change them. 0: redraw every frame. [0, 10].
    float shadow_sun_step_deg = 0.05f;
    /// Colour statistics are gathered on every n-th pixel in x and y of the camera frame (docs/design.md 5).
    uint32_t statistics_stride = 8;
    /// Frames for the exponential smoothing of the camera's colour statistics (time constant), [1, 1e6].
    float statistics_smoothing_frames = 8.0f;
    /// Per-channel gain limit of the colour transfer (sigma_target / sigma_source clamped to [1/g, g]), [1, 100].
    float colour_gain_limit = 2.0f;
    /// Ground cells whose baked irradiance with the building differs from without it by more than this
    /// (relative, any channel of any slot) get the ratio pass even where the building casts no shadow this frame;
    /// below it the building's bounce and sky occlusion are taken as no change and the camera pixel is left.
    /// 1/255 moves the brightest pixel by under one 8-bit step. [0, 1].
    float ground_change_threshold = 1.0f / 255.0f;
    /// Direct-only mode: the constant ambient irradiance, as a fraction of the mean baked E_ind over the
    /// building of the frame's slots (one colour for the whole building: what an AR platform's ambient light
    /// estimate gives an app today). [0, 100].
    float direct_only_ambient_fraction = 1.0f;
    /// Direct-only mode: the camera pixel in the building's shadow is multiplied by this. [0, 1].
    float direct_only_shadow_darkening = 0.6f;
    /// The camera's pixel format, for host pixels and the app's VkImage alike. kNv12 / kNv21 need an even
    /// frame width and height.
    CameraFormat camera_format = CameraFormat::kRgba8;
    YcbcrModel camera_ycbcr_model = YcbcrModel::kBt601;  ///< kNv12 / kNv21 only
    YcbcrRange camera_ycbcr_range = YcbcrRange::kNarrow;  ///< kNv12 / kNv21 only
    /// The platform's zero-copy camera (docs/runtime.md, "The zero-copy camera"): true takes a kNv12 / kNv21
    /// camera as the app's two-plane Y'CbCr VkImage (FrameInput::camera_image in VK_FORMAT_G8_B8R8_2PLANE_420_UNORM,
    /// what an imported AHardwareBuffer or CVPixelBuffer gives), sampled in place through a sampler Y'CbCr
    /// conversion: no copy, no staging, no plane images of the runtime's; host planes are then refused. Needs the
    /// samplerYcbcrConversion feature (Vulkan 1.1) enabled on the app's device (openHeadless's own device enables it
    /// where the device has it) and the format's chroma siting among its features: else open() throws kDevice
    /// naming what is missing.
    bool camera_ycbcr_image = false;
    /// The app's own conversion for camera_ycbcr_image (the platform's: on Android made from
    /// vkGetAndroidHardwareBufferPropertiesANDROID's suggested model, range and chroma offsets), made for
    /// G8_B8R8_2PLANE_420_UNORM; it outlives the runtime. The runtime's views of the camera images and its
    /// immutable sampler use it, and camera_ycbcr_model / range and the kNv12 / kNv21 order are then the
    /// conversion's. VK_NULL_HANDLE (the default): the runtime makes one from camera_ycbcr_model / range and
    /// camera_format with nearest chroma, which gives the host planes' composite.
    VkSamplerYcbcrConversion camera_ycbcr_conversion = VK_NULL_HANDLE;
    /// The chromaFilter camera_ycbcr_conversion was made with, VK_FILTER_NEAREST or VK_FILTER_LINEAR: the runtime's
    /// sampler filters with it, as Vulkan asks of a sampler with a conversion. Ignored without that conversion.
    VkFilter camera_ycbcr_chroma_filter = VK_FILTER_NEAREST;
    /// Anisotropic filtering of the building's base-colour textures (which are mipmapped and sampled
    /// trilinearly): the largest anisotropy, [1, 16], clamped to the device's maxSamplerAnisotropy. 1 is off.
    /// Above 1 only when the app enabled samplerAnisotropy on its device (the runtime cannot know: a device
    /// created without it makes a sampler with anisotropy invalid). openHeadless's own device enables the
    /// feature where it exists, and sets this to 1 where it does not.
    float max_anisotropy = 1.0f;
    /// Frames the GPU may work on while the app records the next, [1, 3]. Each has its own composite, command
    /// buffer, fence and host-visible staging; a frame waits only when it would reuse one still in flight.
    uint32_t frames_in_flight = 2;
    /// Samples per pixel of the main pass (anti-aliasing of the occluder, building and ground-ratio draws):
    /// 1, 2, 4 or 8. Above 1 the pass draws into a multisampled colour and depth attachment (shared by the
    /// frame slots) and resolves into the composite at its end; the camera-in draw writes every sample, so
    /// camera pixels nothing else touches resolve to the camera's own bytes. The device must support the count
    /// for colour and depth framebuffers (limits framebufferColorSampleCounts and
    /// framebufferDepthSampleCounts; lavapipe has 1 and 4), else open() throws kDevice naming msaa_samples.
    /// 1: one sample per pixel and no resolve, the runtime's path before this option.
    uint32_t msaa_samples = 4;
    /// The lightmaps' GPU format; kAuto chooses (above). A format forced here that the device cannot sample and
    /// filter (kRgba32f or kAstc4x4Hdr can lack it) fails open() with kDevice naming lightmap_format, as does
    /// kAstc4x4Hdr without texture_compression_astc_hdr; kAstc4x4Hdr on a bake set without its blocks (or with
    /// blocks at another scale than the runtime's) fails with kInvalidBakeSet.
    LightmapFormat lightmap_format = LightmapFormat::kAuto;
    /// True when the app enabled textureCompressionASTC_HDR on its device (VkPhysicalDeviceTextureCompression-
    /// ASTCHDRFeatures of VK_EXT_texture_compression_astc_hdr, or VkPhysicalDeviceVulkan13Features): the runtime
    /// cannot ask a device which features it was created with. openHeadless's own device does not enable it
    /// (and sets this false).
    bool texture_compression_astc_hdr = false;
    /// True when the app enabled textureCompressionASTC_LDR on its device (VkPhysicalDeviceFeatures; every
    /// Vulkan phone GPU has it, desktop GPUs and lavapipe do not). The building's base-colour textures are then
    /// drawn from the bake set's ASTC 6x6 sRGB blocks (the runtime pack's, their mip chains made at bake time:
    /// 3.56 bits a texel against RGBA8's 32) where it has them and the device samples and filters
    /// VK_FORMAT_ASTC_6x6_SRGB_BLOCK; else as RGBA8 with the chains made at load. A texture the bake set holds
    /// only as blocks (a pack whose RGBA8 files were left out) that cannot be drawn so fails open() with
    /// kInvalidBakeSet naming the texture. Runtime::baseColourTextureFormat() says which. openHeadless's own
    /// device does not enable it (and sets this false).
    bool texture_compression_astc_ldr = false;
};

/// Semaphores a frame waits on before it reads the camera, and signals when its composite is written. Binary
/// semaphores, or timeline ones with their values (the app enabled timelineSemaphore on its device; a binary
/// semaphore's value is ignored). The arrays are read during renderFrame only.
struct FrameSync {
    uint32_t wait_count = 0;
    const VkSemaphore* wait_semaphores = nullptr;
    const uint64_t* wait_values = nullptr;             ///< null: all binary
    const VkPipelineStageFlags* wait_stages = nullptr;  ///< null: VK_PIPELINE_STAGE_ALL_COMMANDS_BIT each
    uint32_t signal_count = 0;
    const VkSemaphore* signal_semaphores = nullptr;
    const uint64_t* signal_values = nullptr;           ///< null: all binary
};

/// One frame's input. Exactly one camera source is set: host pixels (camera_rgba8, or camera_luma and
/// camera_chroma) or the app's VkImage (camera_image), in RuntimeOptions::camera_format.
struct FrameInput {
    /// Host pixels of a kRgba8 or kBgra8 camera: frame_width x frame_height, 4 bytes a pixel, rows
    /// camera_row_bytes apart (0: packed, width * 4). Copied into the runtime's staging buffer during the call.
    const uint8_t* camera_rgba8 = nullptr;
    uint32_t camera_row_bytes = 0;
    /// Host planes of a kNv12 / kNv21 camera: Y' (width x height bytes) and the interleaved chroma (width/2 x
    /// height/2 pairs), rows camera_luma_row_bytes and camera_chroma_row_bytes apart (0: packed). Android's
    /// YUV_420_888 with a pixel stride of 2 is this layout: pass its Y plane and the V (NV21) or U (NV12) plane.
    const uint8_t* camera_luma = nullptr;
    const uint8_t* camera_chroma = nullptr;
    uint32_t camera_luma_row_bytes = 0;
    uint32_t camera_chroma_row_bytes = 0;
    /// Or the app's VkImage, sampled in place (never copied): frame size, one mip level and layer, usage
    /// SAMPLED, on the runtime's queue family, in camera_image_layout: SHADER_READ_ONLY_OPTIMAL or GENERAL (read
    /// as they are), or TRANSFER_SRC_OPTIMAL (moved to SHADER_READ_ONLY_OPTIMAL for the frame and back after it).
    /// camera_image_format: kRgba8 takes R8G8B8A8_UNORM or _SRGB, kBgra8 B8G8R8A8_UNORM or _SRGB (the bytes
    /// are sRGB either way); a kNv12 / kNv21 camera comes as host planes, or, with
    /// RuntimeOptions::camera_ycbcr_image, only as a G8_B8R8_2PLANE_420_UNORM image (docs/platforms.md says why).
    /// The runtime keeps a view of each image it meets (up to 8, the least recently used let go): call
    /// Runtime::forgetCameraImage before destroying an image it has seen. The app's writes must be complete
    /// before the frame reads: a wait semaphore in `sync`, or a submission earlier on the same queue.
    VkImage camera_image = VK_NULL_HANDLE;
    VkImageLayout camera_image_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkFormat camera_image_format = VK_FORMAT_R8G8B8A8_UNORM;
    FrameSync sync;
    CameraIntrinsics intrinsics;
    CameraPose pose;
    double utc_unix_seconds = 0.0;           ///< the instant, seconds since 1970-01-01T00:00:00Z
    std::optional<GeoPosition> position;     ///< a GPS fix; nothing: the bake set's site reference point
    Weather weather;
    /// The camera's exposure: display-linear value per unit of the bake set's radiance. Used when the colour
    /// match is off or has no camera statistics yet (and in direct-only mode); the match replaces it otherwise.
    /// From EV100 or the platform's light estimate (ARCore, ARKit): gusuku/maths/exposure.h and
    /// docs/platform-light.md; ColourMatch::kGround estimates it from the frame when the platform gives nothing.
    float exposure = 1.0f;
    RenderMode mode = RenderMode::kBakedLight;
    /// kAuto by default: the ground match where the bake set and the device allow it (it undoes an unknown
    /// exposure and white balance, and leaves a known one nearly as it is), else off. kOff for a camera whose
    /// exposure is known exactly (a rendered camera); gusuku-bench measures when each match helps and hurts.
    ColourMatch colour_match = ColourMatch::kAuto;
    bool blend_slots = true;   ///< blend the two sunny slots whose suns are nearest (false: the nearest alone)
    bool ground_ratio = true;  ///< apply the shadow-catcher ratio to the camera pixels (false: leave them)
};

/// What the frame computed on the CPU, for the app and for tests.
struct FrameInfo {
    double sun_azimuth_deg = 0.0;
    double sun_apparent_elevation_deg = 0.0;
    bool sun_above_horizon = false;
    glm::dvec3 sun_direction_enu{0.0, 0.0, 1.0};
    glm::dvec3 sun_irradiance_rgb{0.0};  ///< E_sun used this frame (after cloud cover), bake set units
    int slot_a = -1, slot_b = -1;        ///< manifest slot indices blended (sunny ones; -1 none)
    float slot_b_weight = 0.0f;          ///< weight of slot_b; slot_a has 1 - weight
    int overcast_slot = -1;
    float overcast_weight = 0.0f;        ///< cloud cover applied to the overcast slot
    uint32_t ground_quads_drawn = 0;     ///< ground-grid quads the ratio pass drew (the rest were not touched)
    uint32_t ground_quads_total = 0;     ///< quads in the grid
};

/// Per-pass time of one frame in profiling mode, milliseconds of wall time (each pass submitted and waited on
/// alone, which works around lavapipe's timestamps: docs/design.md 5).
struct PassTimings {
    double upload_ms = 0.0;      ///< camera image into the frame
    double shadow_ms = 0.0;      ///< shadow maps
    double occluder_ms = 0.0;    ///< site mesh into depth
    double building_ms = 0.0;    ///< the building
    double ground_ms = 0.0;      ///< the ground ratio
    double statistics_ms = 0.0;  ///< the camera's colour statistics
    double readback_ms = 0.0;    ///< the composite out to the host
    double total_ms = 0.0;
};

class Runtime {
public:
    /// Opens a runtime on the app's device (gpu must outlive the runtime; see gpu_device.h). Checks the bake
    /// set (RuntimeError kInvalidBakeSet naming the field), uploads it, builds the pipelines and every per-frame
    /// resource. The device must support graphics on gpu.queue and the formats the runtime uses.
    static std::unique_ptr<Runtime> open(const GpuDevice& gpu, const BakeSetData& bake_set,
                                         const RuntimeOptions& options = {});
    /// Opens a runtime on a headless Vulkan device of its own (a GPU if there is one, else lavapipe; the
    /// environment's GUSUKU_VALIDATION and GUSUKU_DEVICE apply, vulkan_context.h), which it owns and destroys.
    /// For tools and tests; an AR app hands in its own device with open().
    static std::unique_ptr<Runtime> openHeadless(const BakeSetData& bake_set, const RuntimeOptions& options = {});
    virtual ~Runtime() = default;

    /// Renders one frame. With output_rgba8 null (the GPU-resident path) it records and submits the frame and
    /// returns: nothing is read back, and the calling thread blocks only when all frames_in_flight frames are
    /// still on the GPU (on the oldest one's fence). The composite is then compositeImage(); the app orders its
    /// use after the frame with a signal semaphore in frame.sync, or a later submission on the same queue. With
    /// output_rgba8 set (frame_width * frame_height * 4 bytes, the host-bytes path for tools and tests) it also
    /// reads the composite back and waits for it. Throws RuntimeError kInvalidFrame for bad input, never writes
    /// a NaN pixel. A sun below the horizon gives a defined frame: no direct sun, the sunny slots' baked light
    /// fading to the overcast slot's (twilight) as the sun sets.
    virtual FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) = 0;

    /// The same frame with each pass submitted and timed alone (slower in total; for the breakdown only).
    virtual FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) = 0;

    /// The composite of the last frame submitted, as a VkImage the app may present, copy or sample
    /// (R8G8B8A8_SRGB, frame size, usage TRANSFER_SRC | SAMPLED | COLOR_ATTACHMENT, left in
    /// VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL). Each frame in flight has its own: this one is rewritten by the
    /// frame frames_in_flight frames later, which waits for the GPU work submitted before it on the queue (the
    /// app's reads on the same queue included), but not for work the app submits on another queue.
    virtual VkImage compositeImage() const = 0;

    /// Blocks until every frame submitted has finished on the GPU (then compositeImage() is complete).
    virtual void waitIdle() = 0;

    /// Lets go of the view the runtime keeps of an app camera image (FrameInput::camera_image), waiting for the
    /// frames in flight that read it. Call it before destroying or re-creating such an image. Unknown: no-op.
    virtual void forgetCameraImage(VkImage image) = 0;

    /// Forgets the smoothed colour statistics (a cut in the camera feed).
    virtual void resetColourStatistics() = 0;

    /// Makes the next frame re-render the shadow maps even if the sun has not moved a step (for profiling).
    virtual void invalidateShadowMaps() = 0;

    /// Device memory the runtime holds, bytes (buffers and images, all allocated at open).
    virtual uint64_t deviceMemoryBytes() const = 0;

    /// The format the lightmaps are held in: RuntimeOptions::lightmap_format, kAuto resolved.
    virtual LightmapFormat lightmapFormat() const = 0;

    /// How many of the building's base-colour textures are drawn from the bake set's ASTC 6x6 blocks
    /// (RuntimeOptions::texture_compression_astc_ldr); the others are RGBA8.
    virtual uint32_t astcTextureCount() const = 0;

    /// Where an ENU point lands in the frame for these intrinsics and pose (the camera convention above);
    /// nothing when it is behind the camera. Pure maths, for apps and tests.
    static std::optional<glm::dvec2> projectToPixel(const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                                    const glm::dvec3& point_enu);
};

}  // namespace gusuku

/* gusuku.h: the C API of gusuku_runtime, for apps (and languages) that do not take C++. C99; include it from C or
 * C++. It wraps gusuku/runtime/runtime.h one to one (every option, frame field, frame counter and helper): read
 * that header for what the runtime draws and how.
 *
 * Use:
 *     gusuku_bakeset* set;    gusuku_bakeset_create(&desc, &set)     (or gusuku_bakeset_load, gusuku_loader.h)
 *     gusuku_runtime* rt;     gusuku_runtime_open(&device, set, &options, &rt)     (or _open_headless)
 *     gusuku_bakeset_free(set);                                      (the runtime keeps no pointer into it)
 *     per frame:              gusuku_runtime_render(rt, &frame, output_rgba8, &info)
 *     gusuku_runtime_close(rt);
 *
 * Versions and struct sizes: GUSUKU_API_VERSION counts the releases that changed this header (0 was gusuku 0.1.0,
 * 6 is this one); gusuku_api_version() is the linked library's. Every struct an app passes by pointer, to fill
 * in or to receive (gusuku_vulkan_device, gusuku_bakeset_desc, gusuku_runtime_options, gusuku_frame_input,
 * gusuku_frame_info, gusuku_pass_timings), starts with uint32_t struct_size, which the app sets to sizeof the
 * struct as its own header declares it: gusuku_runtime_options_default and gusuku_frame_input_default set it and
 * the defaults; the others are zeroed and given their size (every default there is 0). The rule:
 *   - new fields are only ever appended (each struct marks what each API version added), never moved, removed or
 *     retyped, so an app built against an older header keeps working with a newer library;
 *   - the library reads (for frame_info and pass_timings: writes) only the fields of the layout struct_size names
 *     and takes today's defaults for the fields after them; bytes past them are never touched;
 *   - struct_size must be the sizeof of a layout some release published: any other value is refused with
 *     GUSUKU_ERROR_INVALID_ARGUMENT, "FUNCTION: ARGUMENT.struct_size: N is not ..." listing the sizes accepted.
 *     That includes 0 (an unset size) and a size larger than this library knows (an app built against a newer
 *     header: link that version's library). The extra bytes of a larger struct are never read, even when zero.
 *   - gusuku 0.1.0's structs had no struct_size, so an app built against 0.1.0 is rebuilt once; the smallest
 *     layout accepted is 0.1.0's fields behind struct_size (tests/test_c_api_versions.cpp freezes each layout).
 * The small structs held inside these (gusuku_intrinsics, gusuku_pose, gusuku_geo_position, gusuku_weather,
 * gusuku_image, gusuku_texture, gusuku_material, gusuku_slot) never change: a version that needs more appends a
 * field to the struct that holds them.
 *
 * Errors: every function that can fail returns a gusuku_result; GUSUKU_OK (0) is success and leaves every output
 * parameter written, any other code leaves them untouched (an out handle is set to NULL). No exception ever
 * leaves this API; a NULL handle or pointer where one is required is GUSUKU_ERROR_INVALID_ARGUMENT, never a crash.
 * A failure's message, one line "FUNCTION: FIELD: PROBLEM" naming the offending field by the C structs' names
 * ("gusuku_runtime_render: frame: pose.position_enu: not finite"), is kept in two places until the next failure:
 *   - gusuku_last_error_message(): the last failure of any gusuku call on the calling thread (thread-local); the
 *     one place to read why an open or a create failed, when there is no handle yet;
 *   - gusuku_runtime_last_error(rt): the last failure of a call on that runtime, whichever thread made it.
 * Messages are at most GUSUKU_MESSAGE_CAPACITY - 1 bytes (longer ones are cut); a success does not clear them.
 *
 * Threads:
 *   - A runtime is used from one thread at a time: calls on one gusuku_runtime must not overlap (the app
 *     serialises them, and may move the runtime between threads). gusuku_runtime_last_error(rt) is such a call.
 *   - Different runtimes may be called concurrently, except that runtimes opened on one VkQueue must not be: each
 *     submits to it, and Vulkan requires the queue's submissions to be externally synchronised. Likewise the app
 *     must not submit to the queue it handed in while a gusuku call on it runs (the C++ API can take the app's
 *     queue mutex instead; this one cannot).
 *   - A bake set is read-only once created: several threads may open runtimes from one bake set at once; freeing
 *     it must not overlap any call that uses it.
 *   - The functions without a handle (gusuku_result_name, gusuku_version, gusuku_api_version, the *_default
 *     functions, gusuku_last_error_message, gusuku_pose_looking_at, gusuku_intrinsics_from_field_of_view,
 *     gusuku_project_to_pixel, gusuku_weather_estimate) may run on any thread at any time.
 *
 * Lifetimes, and who frees what:
 *   - The app's VkInstance, VkPhysicalDevice, VkDevice and VkQueue (gusuku_vulkan_device) must outlive every
 *     runtime opened on them; gusuku never destroys them. The gusuku_vulkan_device struct itself need not.
 *   - A bake set need not outlive the runtime: gusuku_runtime_open copies what it draws into the GPU and keeps no
 *     pointer into it. gusuku_bakeset_free frees it (from either source); the app frees its own desc arrays
 *     whenever it likes after gusuku_bakeset_create returns.
 *   - gusuku_runtime_close frees the runtime, everything it created on the device and, for a headless runtime,
 *     the device itself. The VkImage of gusuku_runtime_composite_image belongs to the runtime.
 *   - Returned strings (messages, names, the version) belong to gusuku: never free them.
 *
 * Conventions (those of runtime.h, pinned by its tests): world = the site's east-north-up frame, metres; camera x
 * right, y down, z forward (OpenCV); pixel (0, 0) is the top-left corner of the top-left pixel; images RGBA8, RGB
 * sRGB-encoded, row 0 at the top, width * 4 bytes per row, no padding. Irradiance per linear Rec.709 channel in
 * the bake set's units. Matrices are row-major: m[3 * row + column].
 *
 * Memory: gusuku_bakeset_create copies the arrays it is given into a host-memory bake set (so the app may free
 * its own at once); gusuku_runtime_open uploads that to the GPU and allocates every buffer, image and pipeline a
 * frame needs; gusuku_runtime_render allocates nothing, on the host or the device.
 */
#ifndef GUSUKU_GUSUKU_H
#define GUSUKU_GUSUKU_H

#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------------------ */
/* Results and messages                                                                                          */

typedef enum gusuku_result {
    GUSUKU_OK = 0,
    GUSUKU_ERROR_INVALID_BAKE_SET = 1,    /* the bake set is inconsistent or unreadable (sizes, NaN texels, files) */
    GUSUKU_ERROR_INVALID_FRAME = 2,       /* a frame input or an open option is invalid (NaN pose, zero focal) */
    GUSUKU_ERROR_DEVICE = 3,              /* the Vulkan device lacks something, or a Vulkan call failed */
    GUSUKU_ERROR_OUT_OF_MEMORY = 4,       /* host or device memory ran out */
    GUSUKU_ERROR_INVALID_ARGUMENT = 5,    /* a NULL handle or pointer, or a NULL array with a non-zero count */
    GUSUKU_ERROR_INTERNAL = 6             /* an unexpected failure inside gusuku (a bug: please report it) */
} gusuku_result;

/* Bytes of the buffers that hold a message, with its terminating zero. */
#define GUSUKU_MESSAGE_CAPACITY 512

/* The code's name ("GUSUKU_ERROR_INVALID_FRAME"); "GUSUKU_UNKNOWN_RESULT" for other values. Static string, O(1). */
const char* gusuku_result_name(gusuku_result result);

/* The last failure's one-line message on the calling thread ("" if none yet). Valid until the thread's next
 * failing gusuku call; never NULL. O(1). */
const char* gusuku_last_error_message(void);

/* "major.minor.patch" of gusuku_runtime. Static string, O(1). */
const char* gusuku_version(void);

/* This header's API version (see "Versions and struct sizes" above): raised by one in each release that appends
 * fields or functions. */
#define GUSUKU_API_VERSION 6u

/* The linked library's API version: an app compiled against GUSUKU_API_VERSION N runs on any library whose
 * gusuku_api_version() is N or more. O(1). */
uint32_t gusuku_api_version(void);

/* ------------------------------------------------------------------------------------------------------------ */
/* The bake set in memory (mirrors gusuku/formats/bakeset_data.h, keeping only what the runtime draws from)               */

/* A float RGBA image: width * height * 4 floats, row 0 at the top. */
typedef struct gusuku_image {
    int32_t width;
    int32_t height;
    const float* rgba;
} gusuku_image;

/* An 8-bit texture: width * height * 4 bytes, RGB sRGB-encoded, A linear, row 0 at the top. */
typedef struct gusuku_texture {
    int32_t width;
    int32_t height;
    const uint8_t* rgba8;
} gusuku_texture;

typedef struct gusuku_material {
    float base_color_factor[4];   /* linear RGBA, multiplies the texture */
    int32_t base_color_texture;   /* index into the desc's textures, -1 for none */
} gusuku_material;

typedef enum gusuku_sky { GUSUKU_SKY_SUNNY = 0, GUSUKU_SKY_OVERCAST = 1 } gusuku_sky;

/* One slot's baked light and, for a sunny slot, where its sun stood. building: lightmap_resolution^2 texels, RGB =
 * E_ind, A = 1 on traced texels; ground_with / ground_without: the ground grid's columns x rows, RGB = irradiance
 * with and without the building, A = 1 where there is ground. */
typedef struct gusuku_slot {
    gusuku_sky sky;
    /* Sunny slots: the sun at the slot's instant (SPA), azimuth east of north and apparent elevation, degrees; its
     * direction is (cos e sin A, cos e cos A, sin e). Ignored for overcast slots. */
    double sun_azimuth_deg;
    double sun_apparent_elevation_deg;
    int32_t sun_present;              /* non-zero: a sunny slot with the sun above the horizon, E_sun below holds */
    double sun_irradiance_rgb[3];     /* E_sun on a plane facing the sun at that elevation, >= 0 */
    int32_t has_colour_statistics;    /* non-zero: the two below hold (the colour match's source side) */
    double lab_mean[3];               /* CIE Lab (D65) of the baked appearance over the valid lightmap texels */
    double lab_sigma[3];
    gusuku_image building;
    gusuku_image ground_with;
    gusuku_image ground_without;
} gusuku_slot;

/* Everything the runtime needs, as pointers and counts (the app keeps ownership; gusuku_bakeset_create copies).
 * Zero it, then set struct_size = sizeof(gusuku_bakeset_desc): every field's default is zero. */
typedef struct gusuku_bakeset_desc {
    uint32_t struct_size;             /* sizeof(gusuku_bakeset_desc) as the app's header declares it */

    /* The site's reference point: the sun is computed here when a frame has no GPS fix. */
    double latitude_deg;
    double longitude_deg;
    double height_m;                  /* above the WGS84 ellipsoid */

    /* The building: ENU metres, counter-clockwise front faces, one material per triangle. */
    const float* positions;           /* 3 per vertex */
    const float* normals;             /* 3 per vertex, unit */
    const float* uv0;                 /* 2 per vertex: base colour texture coordinates */
    const float* uv1;                 /* 2 per vertex: lightmap coordinates in [0, 1] */
    uint32_t vertex_count;
    const uint32_t* indices;          /* 3 per triangle */
    uint32_t index_count;
    const uint32_t* triangle_material;  /* index_count / 3 entries */
    const gusuku_material* materials;
    uint32_t material_count;
    const gusuku_texture* textures;
    uint32_t texture_count;
    int32_t lightmap_resolution;      /* the slots' building lightmaps are this square */

    /* The real site's surfaces, depth only (may be empty: positions NULL, counts 0). ENU metres. */
    const float* occluder_positions;  /* 3 per vertex */
    uint32_t occluder_vertex_count;
    const uint32_t* occluder_indices; /* 3 per triangle */
    uint32_t occluder_index_count;

    /* The ground grid (gusuku/formats/ground_grid.h): column 0 west, row 0 north, square cells. */
    double ground_origin_enu_m[2];    /* south-west corner, ENU x and y */
    double ground_cell_m;
    int32_t ground_columns;
    int32_t ground_rows;
    gusuku_image ground_geometry;     /* columns x rows: RGB unit normal (ENU), A height (ENU z, metres) */

    const gusuku_slot* slots;
    uint32_t slot_count;

    /* API version 1: */
    /* The ground's linear albedo, columns x rows: RGB albedo, A 1 where there is ground. Needed by
     * GUSUKU_COLOUR_MATCH_GROUND only; may be empty (0 x 0, rgba NULL): such a bake set refuses that match. */
    gusuku_image ground_albedo;

    /* API version 2: */
    /* Alpha-masked materials (glTF alphaMode MASK): one cutoff per material, or NULL for all opaque. A value >= 0
     * masks that material (fragments whose base colour alpha, factor times texture, is below it are holes in the
     * building and its shadow); a negative value keeps it opaque; above 1 or NaN: INVALID_BAKE_SET. */
    const float* material_alpha_cutoffs;
} gusuku_bakeset_desc;

/* A bake set held in host memory, made by gusuku_bakeset_create or gusuku_bakeset_load (gusuku_loader.h). */
typedef struct gusuku_bakeset gusuku_bakeset;

/* Copies desc into a new bake set and checks it. A NULL array with a non-zero count: INVALID_ARGUMENT naming the
 * desc's field ("desc.normals: NULL with vertex_count 24"); bad data (every size, index and texel is checked):
 * INVALID_BAKE_SET naming the field as gusuku/formats/bakeset_data.h does (desc.indices is building.indices, desc.slots[i]
 * .building is slots[i].building: "bake set: slots[2].building: texel (4, 0) channel R is NaN"). O(data size)
 * time and host memory; the app may free its arrays when it returns. */
gusuku_result gusuku_bakeset_create(const gusuku_bakeset_desc* desc, gusuku_bakeset** out_bake_set);

/* Frees a bake set from either source; NULL is a no-op (GUSUKU_OK). A runtime opened from it stays valid. */
gusuku_result gusuku_bakeset_free(gusuku_bakeset* bake_set);

/* ------------------------------------------------------------------------------------------------------------ */
/* The runtime                                                                                                   */

/* The app's Vulkan device (see gpu_device.h's contract): the four handles outlive the runtime (this struct need
 * not); the device was created on queue_family_index and queue supports graphics and compute. gusuku creates its
 * own pools, fences, buffers, images and pipelines on it, nothing global. Zero it, set struct_size. */
typedef struct gusuku_vulkan_device {
    uint32_t struct_size;             /* sizeof(gusuku_vulkan_device) as the app's header declares it */
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family_index;

    /* API version 1: */
    uint32_t reserved_zero;           /* set 0 (keeps the 0.1 layout's tail padding unused) */
    uint32_t instance_api_version;    /* VkApplicationInfo::apiVersion the instance was created with; 0: 1.1 or
                                         later. Below 1.1 the colour matches are off (runtime.h, "Device
                                         requirements") */
} gusuku_vulkan_device;

/* Fixed when the runtime opens; start from gusuku_runtime_options_default. Meanings as in runtime.h's
   RuntimeOptions. Every field is range-checked at open (NaN refused): GUSUKU_ERROR_INVALID_FRAME, the message
   naming "options.FIELD". */
/* The camera's pixel format (runtime.h's CameraFormat), fixed when the runtime opens. */
typedef enum gusuku_camera_format {
    GUSUKU_CAMERA_RGBA8 = 0,  /* 4 bytes a pixel, R G B A */
    GUSUKU_CAMERA_BGRA8 = 1,  /* 4 bytes a pixel, B G R A (kCVPixelFormatType_32BGRA) */
    GUSUKU_CAMERA_NV12 = 2,   /* Y' plane, then interleaved Cb Cr at half size */
    GUSUKU_CAMERA_NV21 = 3    /* Y' plane, then interleaved Cr Cb at half size (Android's YUV_420_888) */
} gusuku_camera_format;
typedef enum gusuku_ycbcr_model { GUSUKU_YCBCR_BT601 = 0, GUSUKU_YCBCR_BT709 = 1 } gusuku_ycbcr_model;
typedef enum gusuku_ycbcr_range { GUSUKU_YCBCR_NARROW = 0, GUSUKU_YCBCR_FULL = 1 } gusuku_ycbcr_range;
/* How the runtime holds the lightmaps on the GPU (runtime.h's LightmapFormat; docs/runtime.md "Lightmap formats"). */
typedef enum gusuku_lightmap_format {
    GUSUKU_LIGHTMAP_E5B9G9R9 = 0,      /* shared exponent, 4 bytes a texel, sampled and filtered everywhere */
    GUSUKU_LIGHTMAP_RGBA16F = 1,       /* 8 bytes a texel */
    GUSUKU_LIGHTMAP_RGBA32F = 2,       /* 16 bytes a texel, the reference (needs linear filtering of it) */
    GUSUKU_LIGHTMAP_ASTC_4X4_HDR = 3,  /* 1 byte a texel, the bake's blocks; needs texture_compression_astc_hdr */
    GUSUKU_LIGHTMAP_AUTO = 4,          /* the default: ASTC_4X4_HDR where the app enabled it and the device and the
                                          bake set have it, else E5B9G9R9 (gusuku_runtime_lightmap_format says) */
    GUSUKU_LIGHTMAP_ASTC_6X6_HDR = 5   /* 0.44 bytes a texel, the bake's 6x6 blocks; needs texture_compression_astc_hdr */
} gusuku_lightmap_format;

typedef struct gusuku_runtime_options {
    uint32_t struct_size;                 /* sizeof(gusuku_runtime_options) as the app's header declares it */
    uint32_t frame_width;                 /* every frame's images are this size, [1, 8192]; default 1280 x 720 */
    uint32_t frame_height;                /* a size the device cannot hold (its image and framebuffer sides, and
                                             the colour statistics' 4-byte-a-pixel storage buffer: lavapipe's
                                             128 MiB take 2^25 pixels, not 8192 x 8192): GUSUKU_ERROR_DEVICE
                                             naming options.frame_width/height and the limit */
    uint32_t shadow_map_size;             /* texels per side, [64, 8192]; default 1024 */
    float shadow_bias_texels;             /* [0, 64]; default 1.5 */
    uint32_t shadow_pcf_radius;           /* [0, 3]; default 1; 0 hard shadows, else the sun's penumbra */
    uint32_t statistics_stride;           /* colour statistics on every n-th pixel; default 8 */
    float statistics_smoothing_frames;    /* [1, 1e6]; default 8 */
    float colour_gain_limit;              /* [1, 100]; default 2 */
    float direct_only_ambient_fraction;   /* of the slots' mean baked E_ind over the building, [0, 100]; default 1 */
    float direct_only_shadow_darkening;   /* [0, 1]; default 0.6 */

    /* API version 1: */
    float shadow_sun_step_deg;            /* shadow maps redrawn when the sun moves this far, [0, 10] (0: every
                                             frame); default 0.05 */
    float ground_change_threshold;        /* relative change of a ground cell's baked light with the building
                                             above which it gets the ratio pass, [0, 1]; default 1/255 */
    gusuku_camera_format camera_format;   /* default GUSUKU_CAMERA_RGBA8; NV12 / NV21 need an even size */
    gusuku_ycbcr_model camera_ycbcr_model;  /* NV12 / NV21 only; default BT601 */
    gusuku_ycbcr_range camera_ycbcr_range;  /* NV12 / NV21 only; default NARROW */
    uint32_t frames_in_flight;            /* frames the GPU may hold while the app records the next, [1, 3];
                                             default 2 */
    uint32_t msaa_samples;                /* samples a pixel of the building, occluder and ground-ratio draws
                                             (anti-aliasing), 1, 2, 4 or 8 and supported by the device
                                             (else GUSUKU_ERROR_DEVICE); 1 turns it off; default 4 */
    float max_anisotropy;                 /* anisotropic filtering of textures, [1, 16] (1: off; above 1 the app
                                             enabled samplerAnisotropy on its device); default 1 */

    /* API version 2: */
    gusuku_lightmap_format lightmap_format;  /* default GUSUKU_LIGHTMAP_AUTO; a format the device cannot sample
                                                and filter: GUSUKU_ERROR_DEVICE naming options.lightmap_format */
    uint32_t texture_compression_astc_hdr;   /* nonzero: the app enabled textureCompressionASTC_HDR on its device
                                                (VK_EXT_texture_compression_astc_hdr or Vulkan 1.3); default 0 */

    /* API version 3: */
    uint32_t texture_compression_astc_ldr;   /* nonzero: the app enabled textureCompressionASTC_LDR on its device
                                                (every Vulkan phone GPU has it): the building's base-colour
                                                textures are drawn from the runtime pack's ASTC 6x6 blocks where
                                                the device samples them, else RGBA8; default 0 */

    /* API version 6 (runtime.h's RuntimeOptions and docs/runtime.md, "The zero-copy camera", say more): */
    uint32_t camera_ycbcr_image;             /* nonzero: an NV12 / NV21 camera comes as the app's
                                                G8_B8R8_2PLANE_420_UNORM VkImage (an imported AHardwareBuffer or
                                                CVPixelBuffer: frame.camera_image, camera_image_format), sampled
                                                in place through a sampler Y'CbCr conversion, no copy; host planes
                                                are then refused. The app enabled samplerYcbcrConversion (Vulkan
                                                1.1) on its device; a device without it: GUSUKU_ERROR_DEVICE
                                                naming it; default 0 */
    VkFilter camera_ycbcr_chroma_filter;     /* the chromaFilter camera_ycbcr_conversion was made with, NEAREST or
                                                LINEAR; default VK_FILTER_NEAREST */
    VkSamplerYcbcrConversion camera_ycbcr_conversion;  /* the app's own conversion (the platform's suggested
                                                model, range and chroma offsets), made for G8_B8R8_2PLANE_420_UNORM,
                                                outliving the runtime; VK_NULL_HANDLE (default): the runtime makes
                                                one from camera_format, camera_ycbcr_model and _range */
} gusuku_runtime_options;

typedef struct gusuku_runtime gusuku_runtime;

typedef enum gusuku_render_mode {
    GUSUKU_MODE_BAKED_LIGHT = 0,  /* baked E_ind + real-time sun with shadow map, ground ratio, colour match */
    GUSUKU_MODE_DIRECT_ONLY = 1,  /* what AR apps draw today: ambient + shadowed sun, fixed shadow darkening */
    GUSUKU_MODE_PROPOSED = GUSUKU_MODE_BAKED_LIGHT  /* the paper's name, kept for existing code */
} gusuku_render_mode;

typedef enum gusuku_colour_match {
    GUSUKU_COLOUR_MATCH_OFF = 0,
    GUSUKU_COLOUR_MATCH_REINHARD = 1,  /* Reinhard per-channel Lab transfer */
    GUSUKU_COLOUR_MATCH_PRESERVE = 2,  /* lightness and white balance towards the camera, chroma spread kept */
    GUSUKU_COLOUR_MATCH_GROUND = 3,    /* per-channel gain that takes the bake set's predicted ground to the
                                          camera's (needs a bake set with ground albedo: else the frame fails
                                          with GUSUKU_ERROR_INVALID_FRAME) */
    GUSUKU_COLOUR_MATCH_AUTO = 4,      /* the default: GROUND where the bake set has ground albedo and the device
                                          runs the statistics, else OFF; never fails a frame */
    GUSUKU_COLOUR_MATCH_PAPER = GUSUKU_COLOUR_MATCH_REINHARD  /* the paper's name, kept for existing code */
} gusuku_colour_match;

/* gusuku_frame_input.flags */
#define GUSUKU_FRAME_BLEND_SLOTS 0x1u   /* blend the two nearest sunny slots (off: the nearest alone) */
#define GUSUKU_FRAME_GROUND_RATIO 0x2u  /* apply the shadow-catcher ratio to the camera's ground pixels */

/* Pinhole intrinsics, pixels. width and height must be the runtime's frame size. */
typedef struct gusuku_intrinsics {
    double fx, fy;   /* focal lengths, > 0 */
    double cx, cy;   /* principal point */
    uint32_t width, height;
} gusuku_intrinsics;

/* Where the camera is and where it looks, site ENU. camera_to_enu is row-major R with enu = R cam + position_enu:
 * its columns are the camera's x (right), y (down) and z (forward) axes in ENU; orthonormal, determinant +1. */
typedef struct gusuku_pose {
    double position_enu[3];
    double camera_to_enu[9];
} gusuku_pose;

typedef struct gusuku_geo_position {
    double latitude_deg;    /* [-90, 90] */
    double longitude_deg;   /* [-180, 180] */
    double height_m;        /* above the WGS84 ellipsoid */
} gusuku_geo_position;

typedef struct gusuku_weather {
    float cloud_cover;      /* 0 clear (sunny slots, real-time sun) to 1 overcast (overcast slot, no sun) */
} gusuku_weather;

/* One frame's input; start from gusuku_frame_input_default. Exactly one of camera_rgba8, camera_luma and
 * camera_image (only camera_image with options.camera_ycbcr_image).
 * Fields appended here start on an 8-byte boundary (after a uint32_t pad where needed): the 0.1 layout ends in
 * 4 bytes of padding that an older app leaves unset, which the library never reads. */
typedef struct gusuku_frame_input {
    uint32_t struct_size;               /* sizeof(gusuku_frame_input) as the app's header declares it */
    const uint8_t* camera_rgba8;        /* host RGBA8 or BGRA8 (options.camera_format), frame_width x frame_height */
    VkImage camera_image;               /* or the app's image, sampled in place (runtime.h's FrameInput): usage
                                           SAMPLED, R8G8B8A8 or B8G8R8A8 (camera_image_format), or
                                           G8_B8R8_2PLANE_420_UNORM with options.camera_ycbcr_image */
    VkImageLayout camera_image_layout;  /* SHADER_READ_ONLY_OPTIMAL (default), GENERAL or TRANSFER_SRC_OPTIMAL */
    gusuku_intrinsics intrinsics;
    gusuku_pose pose;
    double utc_unix_seconds;            /* the instant, seconds since 1970-01-01T00:00:00Z */
    int32_t has_position;               /* non-zero: position is a GPS fix; zero: the bake set's reference point */
    gusuku_geo_position position;
    gusuku_weather weather;
    float exposure;                     /* display-linear value per unit radiance, > 0; default 1 */
    gusuku_render_mode mode;            /* default GUSUKU_MODE_BAKED_LIGHT */
    gusuku_colour_match colour_match;   /* default GUSUKU_COLOUR_MATCH_AUTO (ground where possible, else off) */
    uint32_t flags;                     /* GUSUKU_FRAME_*; default BLEND_SLOTS | GROUND_RATIO */

    /* API version 1 (runtime.h's FrameInput and FrameSync say more): */
    const uint8_t* camera_luma;         /* or host Y'CbCr planes (NV12 / NV21): Y', frame size */
    const uint8_t* camera_chroma;       /* the interleaved chroma, half size */
    uint32_t camera_row_bytes;          /* rows apart in camera_rgba8 (0: packed, width * 4) */
    uint32_t camera_luma_row_bytes;     /* rows apart in camera_luma (0: packed, width) */
    uint32_t camera_chroma_row_bytes;   /* rows apart in camera_chroma (0: packed, width) */
    VkFormat camera_image_format;       /* camera_image's format, _UNORM or _SRGB; default R8G8B8A8_UNORM */
    uint32_t wait_semaphore_count;      /* semaphores the frame waits on before it reads the camera, <= 8 */
    uint32_t signal_semaphore_count;    /* semaphores it signals when the composite is written, <= 8 */
    const VkSemaphore* wait_semaphores;
    const uint64_t* wait_values;        /* timeline values (NULL: binary semaphores) */
    const VkPipelineStageFlags* wait_stages;  /* NULL: ALL_COMMANDS each */
    const VkSemaphore* signal_semaphores;
    const uint64_t* signal_values;      /* timeline values (NULL: binary semaphores) */

    /* API version 4: */
    float sun_scale;                    /* the sun apart from the sky (runtime.h's Weather::sun_scale): E_sun and
                                           its shadow scaled by this, in [0, 2], while weather.cloud_cover blends
                                           the slots; negative (default -1): 1 - weather.cloud_cover */
} gusuku_frame_input;

/* What the frame computed (runtime.h's FrameInfo). Zero it and set struct_size; the library writes the fields of
 * that layout. */
typedef struct gusuku_frame_info {
    uint32_t struct_size;               /* sizeof(gusuku_frame_info) as the app's header declares it */
    double sun_azimuth_deg;             /* east of north */
    double sun_apparent_elevation_deg;  /* refracted */
    int32_t sun_above_horizon;
    double sun_direction_enu[3];        /* unit, towards the sun */
    double sun_irradiance_rgb[3];       /* E_sun used this frame (after cloud cover), bake set units */
    int32_t slot_a, slot_b;             /* sunny slots blended (-1: none) */
    float slot_b_weight;                /* slot_a has 1 - slot_b_weight */
    int32_t overcast_slot;              /* -1: none */
    float overcast_weight;

    /* API version 1: */
    uint32_t ground_quads_drawn;        /* ground-grid quads the ratio pass drew (the rest were left untouched) */
    uint32_t ground_quads_total;        /* quads in the grid */
} gusuku_frame_info;

/* Each pass's time in one profiled frame (gusuku_runtime_render_profiled), milliseconds of wall time: each pass
 * submitted and waited on alone (runtime.h's PassTimings). Zero it and set struct_size.
 * API version 1 (the first layout). */
typedef struct gusuku_pass_timings {
    uint32_t struct_size;               /* sizeof(gusuku_pass_timings) as the app's header declares it */
    double upload_ms;                   /* the camera image into the frame */
    double shadow_ms;                   /* shadow maps */
    double occluder_ms;                 /* the site's mesh into depth */
    double building_ms;                 /* the building */
    double ground_ms;                   /* the ground ratio */
    double statistics_ms;               /* the camera's colour statistics */
    double readback_ms;                 /* the composite out to the host */
    double total_ms;
} gusuku_pass_timings;

/* Fills the defaults above for the fields of the layout options->struct_size names (set it first; the inline
 * gusuku_runtime_options_default below does). A bad struct_size: GUSUKU_ERROR_INVALID_ARGUMENT. O(1). For
 * bindings that cannot call an inline function. */
gusuku_result gusuku_runtime_options_fill_defaults(gusuku_runtime_options* options);

/* The same for a frame: no camera, zero intrinsics (to be set), identity pose at the origin, time 0, no GPS fix,
 * cloud cover 0, exposure 1, PROPOSED, colour match AUTO (ground where the bake set and device allow it, else
 * off), flags BLEND_SLOTS | GROUND_RATIO. O(1). */
gusuku_result gusuku_frame_input_fill_defaults(gusuku_frame_input* frame);

/* Sets struct_size to this header's sizeof and fills the defaults: the way to start options and frames. Inline,
 * so the size is the one the app was compiled with. NULL: GUSUKU_ERROR_INVALID_ARGUMENT. O(1). */
static inline gusuku_result gusuku_runtime_options_default(gusuku_runtime_options* options) {
    if (options != NULL) options->struct_size = (uint32_t)sizeof *options;
    return gusuku_runtime_options_fill_defaults(options);
}

static inline gusuku_result gusuku_frame_input_default(gusuku_frame_input* frame) {
    if (frame != NULL) frame->struct_size = (uint32_t)sizeof *frame;
    return gusuku_frame_input_fill_defaults(frame);
}

/* Opens a runtime on the app's device: checks the bake set and options, uploads the bake set, builds pipelines and
 * every per-frame resource (all device memory it will ever use). options NULL: the defaults. Milliseconds to
 * seconds (pipeline compilation). The bake set may be freed afterwards. */
gusuku_result gusuku_runtime_open(const gusuku_vulkan_device* device, const gusuku_bakeset* bake_set,
                                  const gusuku_runtime_options* options, gusuku_runtime** out_runtime);

/* The same on a headless Vulkan device the runtime creates and owns (a GPU if there is one, else lavapipe;
 * GUSUKU_VALIDATION and GUSUKU_DEVICE from the environment apply). For tools and tests. */
gusuku_result gusuku_runtime_open_headless(const gusuku_bakeset* bake_set, const gusuku_runtime_options* options,
                                           gusuku_runtime** out_runtime);

/* Renders one frame; the CPU-side facts into info (NULL: none). With output_rgba8 NULL (the GPU-resident path)
 * it submits the frame and returns, blocking only when frames_in_flight frames are all still on the GPU: the app
 * takes gusuku_runtime_composite_image after the frame's signal semaphores. With output_rgba8 set (frame_width *
 * frame_height * 4 bytes) it also reads the composite back and waits for it. One frame of GPU work, no
 * allocation. Bad input is GUSUKU_ERROR_INVALID_FRAME naming the field. */
gusuku_result gusuku_runtime_render(gusuku_runtime* runtime, const gusuku_frame_input* frame, uint8_t* output_rgba8,
                                    gusuku_frame_info* info);

/* The same frame with each pass submitted and timed alone into timings (required), for the breakdown only: slower
 * in total. The composite and info are those of gusuku_runtime_render. */
gusuku_result gusuku_runtime_render_profiled(gusuku_runtime* runtime, const gusuku_frame_input* frame,
                                             uint8_t* output_rgba8, gusuku_frame_info* info,
                                             gusuku_pass_timings* timings);

/* The last frame's composite as a VkImage (R8G8B8A8_SRGB, frame size, TRANSFER_SRC_OPTIMAL), rewritten
 * frames_in_flight frames later. O(1). */
gusuku_result gusuku_runtime_composite_image(const gusuku_runtime* runtime, VkImage* out_image);

/* Blocks until every frame submitted has finished on the GPU. */
gusuku_result gusuku_runtime_wait_idle(gusuku_runtime* runtime);

/* Lets go of the view the runtime keeps of an app camera image; call before destroying the image. */
gusuku_result gusuku_runtime_forget_camera_image(gusuku_runtime* runtime, VkImage image);

/* Forgets the smoothed colour statistics (a cut in the camera feed). O(1). */
gusuku_result gusuku_runtime_reset_colour_statistics(gusuku_runtime* runtime);

/* Makes the next frame redraw the shadow maps even if the sun has not moved a step (for profiling). O(1). */
gusuku_result gusuku_runtime_invalidate_shadow_maps(gusuku_runtime* runtime);

/* The format the lightmaps are held in: options.lightmap_format with AUTO resolved at open (API version 2). O(1). */
gusuku_result gusuku_runtime_lightmap_format(const gusuku_runtime* runtime, gusuku_lightmap_format* out_format);

/* How many of the building's base-colour textures are drawn from ASTC 6x6 blocks
 * (options.texture_compression_astc_ldr; the others are RGBA8) (API version 3). O(1). */
gusuku_result gusuku_runtime_astc_texture_count(const gusuku_runtime* runtime, uint32_t* out_count);

/* Device memory the runtime holds, bytes (buffers and images, all allocated at open). O(1). */
gusuku_result gusuku_runtime_device_memory_bytes(const gusuku_runtime* runtime, uint64_t* out_bytes);

/* The last failure of a call on this runtime ("" if none); valid until its next failure or close; "" for NULL. */
const char* gusuku_runtime_last_error(const gusuku_runtime* runtime);

/* Waits for the runtime's GPU work, destroys everything it created (and a headless device). NULL: no-op. */
gusuku_result gusuku_runtime_close(gusuku_runtime* runtime);

/* The sun read from the real site's own shadows in the camera frame (API version 5; the C++ API's
 * latestSunEvidence, gusuku/runtime/runtime_sun_evidence.h; docs/platform-light.md, "The sun from the frame"): the
 * runtime compares, on the GPU within the frames its ground colour match measures, the camera's ground pixels that
 * the site shadows with those it leaves in sun. Feed sun_out_probability, confidence and sun_strength to
 * gusuku_sun_filter_update (gusuku_weather.h) as its gusuku_sun_evidence, and the filter's sun_visibility *
 * sun_strength to the next frame's sun_scale. */
typedef struct gusuku_sun_evidence_reading {
    uint32_t struct_size;           /* sizeof(gusuku_sun_evidence_reading), set by the app */
    int32_t measured;               /* 1: a measurement has finished; 0: none yet (or the runtime cannot measure:
                                       no ground albedo, no site occluder, colour match off): the rest is zero */
    float sun_out_probability;      /* [0, 1] */
    float confidence;               /* [0, 1]: 0 no shadow boundary in view (cue 0 or 2), the prior decides */
    float sun_strength;             /* E_sun / E_sky now over the bake's, where the sun is out; else -1 */
    uint32_t cue;                   /* 0 none in view, 1 the site's shadow boundary on the ground, 2 the metered
                                       ground (no boundary: the lit ground against the frame's exposure; its
                                       confidence 0 here, gusuku_sun_evidence_choose weighs it) */
    uint32_t shadowed_samples;      /* ground samples the site shadows, and lit ones, behind the reading */
    uint32_t lit_samples;
    float shade_log2_ratio;         /* log2 of the camera's gain on the shadowed ground against the bake */
    float strength;                 /* the strength measured (also when the sun is judged in) */
    float strength_standard_error;
    uint32_t reserved;              /* 0 */
    uint64_t frame_index;           /* the frame measured: 1 for the runtime's first render */
    double utc_unix_seconds;        /* that frame's utc_unix_seconds */
} gusuku_sun_evidence_reading;

/* The newest finished measurement, never waiting on the GPU (it lags the frame by up to frames_in_flight frames;
 * none on the host-bytes path): out_reading->measured 0 before the first. Allocates nothing; call it every frame.
 * out_reading->struct_size must be sizeof(gusuku_sun_evidence_reading) (API version 5's), else
 * GUSUKU_ERROR_INVALID_ARGUMENT. O(1). */
gusuku_result gusuku_runtime_sun_evidence(gusuku_runtime* runtime, gusuku_sun_evidence_reading* out_reading);

/* The cue that decides the frame, and the evidence to feed gusuku_sun_filter_update (API version 6; the C++ API's
 * sunEvidenceForFilter, gusuku/maths/sun_cue_choice.h): out_reading is reading with sun_out_probability,
 * confidence, sun_strength and cue those of the cue chosen: the site's shadow boundary (cue 1) as read; the metered
 * ground (cue 2) only when exposure_is_metered is 1 (the frame's exposure is the camera's own metered one, EV100
 * from its ISO, shutter and aperture), at half the boundary's confidence; else cue 0, confidence 0,
 * probability 0.5 and strength -1 (the filter's prior decides). The counts, medians, frame_index and
 * utc_unix_seconds are copied. reading and out_reading may be the same struct. NULL, or a struct_size not
 * sizeof(gusuku_sun_evidence_reading): GUSUKU_ERROR_INVALID_ARGUMENT. Allocates nothing; O(1). */
gusuku_result gusuku_sun_evidence_choose(const gusuku_sun_evidence_reading* reading, int32_t exposure_is_metered,
                                         gusuku_sun_evidence_reading* out_reading);

/* ------------------------------------------------------------------------------------------------------------ */
/* Cameras and weather (pure CPU, no runtime needed; runtime.h's helpers)                                        */
/* Numbers: each helper refuses a NaN or infinite argument, and any finite one whose result would not be finite
 * (a sum or product past a double's 1.8e308, a quotient by a denormal), with GUSUKU_ERROR_INVALID_ARGUMENT and
 * "FUNCTION: ARGUMENT: PROBLEM" naming the argument: GUSUKU_OK never comes with a NaN or an infinity in an
 * output (out_pixel's NaN for a point behind the camera, documented below, excepted). Results are computed in
 * double, scaled where that keeps finite answers finite (a target 1e308 away still gives a rotation). */

/* The pose of a camera at position_enu looking at target_enu, the image's up towards ENU +z (towards north when
 * it looks straight up or down): CameraPose::lookingAt. A coordinate not finite, a target within 1 um of the
 * position, or one whose offset from it overflows a double: GUSUKU_ERROR_INVALID_ARGUMENT naming it. O(1). */
gusuku_result gusuku_pose_looking_at(const double position_enu[3], const double target_enu[3], gusuku_pose* out_pose);

/* Intrinsics of a width x height frame with this horizontal field of view, square pixels, the principal point at
 * the centre: CameraIntrinsics::fromFieldOfView. width and height in [1, 65536], the angle in (0, 180) degrees
 * and not so small (a denormal) that the focal length overflows, else GUSUKU_ERROR_INVALID_ARGUMENT naming it.
 * O(1). */
gusuku_result gusuku_intrinsics_from_field_of_view(uint32_t width, uint32_t height, double horizontal_fov_deg,
                                                   gusuku_intrinsics* out_intrinsics);

/* Where the ENU point lands in the frame (the pixel convention above): Runtime::projectToPixel. In front of the
 * camera (camera z > 0): out_pixel = (u, v) and *out_in_front = 1; else out_pixel = (NaN, NaN), *out_in_front 0.
 * The intrinsics and pose are checked as a frame's are (focal lengths finite and positive, a rotation), their
 * width and height excepted; a problem is GUSUKU_ERROR_INVALID_ARGUMENT naming the field. So is a point_enu not
 * finite, one whose offset from the pose's position overflows a double, and one in front whose pixel would not be
 * finite (nearly in the camera's plane z = 0, or intrinsics near 1e308). O(1). */
gusuku_result gusuku_project_to_pixel(const gusuku_intrinsics* intrinsics, const gusuku_pose* pose,
                                      const double point_enu[3], double out_pixel[2], int32_t* out_in_front);

/* The weather read off an RGBA8 camera frame (the image convention, width * height * 4 bytes) when no weather
 * service answers: Weather::estimatedFrom (hard shadows in the lower half, a blue sky in the top rows; a frame
 * under 2 x 8 pixels or all black reads as overcast). NULL pixels, a zero side or more than 2^28 pixels:
 * GUSUKU_ERROR_INVALID_ARGUMENT. Allocates two frame-sized arrays: call it every second or so, not per frame. */
gusuku_result gusuku_weather_estimate(const uint8_t* camera_rgba8, uint32_t width, uint32_t height,
                                      gusuku_weather* out_weather);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_H */

/* gusuku.h: the C API of gusuku_runtime, for apps (and languages) that do not take C++. C99; include it from C or
 * C++. It wraps gusuku/runtime/runtime.h one to one: read that header for what the runtime draws and how.
 *
 * Use:
 *     gusuku_bakeset* set;    gusuku_bakeset_create(&desc, &set)     (or gusuku_bakeset_load, gusuku_loader.h)
 *     gusuku_runtime* rt;     gusuku_runtime_open(&device, set, &options, &rt)     (or _open_headless)
 *     gusuku_bakeset_free(set);                                      (the runtime keeps no pointer into it)
 *     per frame:              gusuku_runtime_render(rt, &frame, output_rgba8, &info)
 *     gusuku_runtime_close(rt);
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
 * Threads: calls on one runtime must not overlap (the app serialises them); different runtimes and bake sets are
 * independent. On the app's device, the app must not submit to the queue it handed in while a gusuku call runs
 * (the C++ API also takes a queue mutex; this one does not).
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

/* ------------------------------------------------------------------------------------------------------------ */
/* The bake set in memory (mirrors gusuku/maths/bakeset_data.h, keeping only what the runtime draws from)               */

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

/* Everything the runtime needs, as pointers and counts (the app keeps ownership; gusuku_bakeset_create copies). */
typedef struct gusuku_bakeset_desc {
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

    /* The ground grid (gusuku/maths/ground_grid.h): column 0 west, row 0 north, square cells. */
    double ground_origin_enu_m[2];    /* south-west corner, ENU x and y */
    double ground_cell_m;
    int32_t ground_columns;
    int32_t ground_rows;
    gusuku_image ground_geometry;     /* columns x rows: RGB unit normal (ENU), A height (ENU z, metres) */

    const gusuku_slot* slots;
    uint32_t slot_count;
} gusuku_bakeset_desc;

/* A bake set held in host memory, made by gusuku_bakeset_create or gusuku_bakeset_load (gusuku_loader.h). */
typedef struct gusuku_bakeset gusuku_bakeset;

/* Copies desc into a new bake set and checks it. A NULL array with a non-zero count: INVALID_ARGUMENT naming the
 * desc's field ("desc.normals: NULL with vertex_count 24"); bad data (every size, index and texel is checked):
 * INVALID_BAKE_SET naming the field as gusuku/maths/bakeset_data.h does (desc.indices is building.indices, desc.slots[i]
 * .building is slots[i].building: "bake set: slots[2].building: texel (4, 0) channel R is NaN"). O(data size)
 * time and host memory; the app may free its arrays when it returns. */
gusuku_result gusuku_bakeset_create(const gusuku_bakeset_desc* desc, gusuku_bakeset** out_bake_set);

/* Frees a bake set from either source; NULL is a no-op (GUSUKU_OK). A runtime opened from it stays valid. */
gusuku_result gusuku_bakeset_free(gusuku_bakeset* bake_set);

/* ------------------------------------------------------------------------------------------------------------ */
/* The runtime                                                                                                   */

/* The app's Vulkan device (see gpu_device.h's contract): all five outlive the runtime; the device was created on
 * queue_family_index and queue supports graphics and compute. gusuku creates its own pools, fences, buffers,
 * images and pipelines on it, nothing global. */
typedef struct gusuku_vulkan_device {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family_index;
} gusuku_vulkan_device;

/* Fixed when the runtime opens; start from gusuku_runtime_options_default. Meanings as in runtime.h. Every field
   is range-checked at open (NaN refused): GUSUKU_ERROR_INVALID_FRAME, the message naming "options.FIELD". */
typedef struct gusuku_runtime_options {
    uint32_t frame_width;                 /* every frame's images are this size, [1, 8192]; default 1280 x 720 */
    uint32_t frame_height;
    uint32_t shadow_map_size;             /* texels per side, [64, 8192]; default 1024 */
    float shadow_bias_texels;             /* [0, 64]; default 1.5 */
    uint32_t shadow_pcf_radius;           /* [0, 3]; default 1 */
    uint32_t statistics_stride;           /* colour statistics on every n-th pixel; default 8 */
    float statistics_smoothing_frames;    /* [1, 1e6]; default 8 */
    float colour_gain_limit;              /* [1, 100]; default 2 */
    float direct_only_ambient_fraction;   /* of the slots' mean baked E_ind over the building, [0, 100]; default 1 */
    float direct_only_shadow_darkening;   /* [0, 1]; default 0.6 */
} gusuku_runtime_options;

typedef struct gusuku_runtime gusuku_runtime;

typedef enum gusuku_render_mode {
    GUSUKU_MODE_PROPOSED = 0,     /* baked E_ind + real-time sun with shadow map, ground ratio, colour match */
    GUSUKU_MODE_DIRECT_ONLY = 1   /* what AR apps draw today: ambient + shadowed sun, fixed shadow darkening */
} gusuku_render_mode;

typedef enum gusuku_colour_match {
    GUSUKU_COLOUR_MATCH_OFF = 0,
    GUSUKU_COLOUR_MATCH_PAPER = 1,     /* Reinhard per-channel Lab transfer */
    GUSUKU_COLOUR_MATCH_PRESERVE = 2,  /* lightness and white balance towards the camera, chroma spread kept */
    GUSUKU_COLOUR_MATCH_GROUND = 3     /* per-channel gain that takes the bake set's predicted ground to the
                                          camera's (needs a bake set with ground albedo: else the frame fails
                                          with GUSUKU_ERROR_INVALID_FRAME) */
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

/* One frame's input; start from gusuku_frame_input_default. Exactly one of camera_rgba8 and camera_image. */
typedef struct gusuku_frame_input {
    const uint8_t* camera_rgba8;        /* host RGBA8, frame_width x frame_height (the image convention) */
    VkImage camera_image;               /* or the app's image: R8G8B8A8 holding sRGB bytes, usage TRANSFER_SRC */
    VkImageLayout camera_image_layout;  /* TRANSFER_SRC_OPTIMAL (default) or SHADER_READ_ONLY_OPTIMAL */
    gusuku_intrinsics intrinsics;
    gusuku_pose pose;
    double utc_unix_seconds;            /* the instant, seconds since 1970-01-01T00:00:00Z */
    int32_t has_position;               /* non-zero: position is a GPS fix; zero: the bake set's reference point */
    gusuku_geo_position position;
    gusuku_weather weather;
    float exposure;                     /* display-linear value per unit radiance, > 0; default 1 */
    gusuku_render_mode mode;            /* default GUSUKU_MODE_PROPOSED */
    gusuku_colour_match colour_match;   /* default GUSUKU_COLOUR_MATCH_OFF (exposure given) */
    uint32_t flags;                     /* GUSUKU_FRAME_*; default BLEND_SLOTS | GROUND_RATIO */
} gusuku_frame_input;

/* What the frame computed on the CPU. */
typedef struct gusuku_frame_info {
    double sun_azimuth_deg;             /* east of north */
    double sun_apparent_elevation_deg;  /* refracted */
    int32_t sun_above_horizon;
    double sun_direction_enu[3];        /* unit, towards the sun */
    double sun_irradiance_rgb[3];       /* E_sun used this frame (after cloud cover), bake set units */
    int32_t slot_a, slot_b;             /* sunny slots blended (-1: none) */
    float slot_b_weight;                /* slot_a has 1 - slot_b_weight */
    int32_t overcast_slot;              /* -1: none */
    float overcast_weight;
} gusuku_frame_info;

/* Fills the defaults above. Never fails for a non-NULL pointer; O(1). */
gusuku_result gusuku_runtime_options_default(gusuku_runtime_options* options);

/* Fills the defaults above: no camera, zero intrinsics (to be set), identity pose at the origin, time 0, no GPS
 * fix, cloud cover 0. O(1). */
gusuku_result gusuku_frame_input_default(gusuku_frame_input* frame);

/* Opens a runtime on the app's device: checks the bake set and options, uploads the bake set, builds pipelines and
 * every per-frame resource (all device memory it will ever use). options NULL: the defaults. Milliseconds to
 * seconds (pipeline compilation). The bake set may be freed afterwards. */
gusuku_result gusuku_runtime_open(const gusuku_vulkan_device* device, const gusuku_bakeset* bake_set,
                                  const gusuku_runtime_options* options, gusuku_runtime** out_runtime);

/* The same on a headless Vulkan device the runtime creates and owns (a GPU if there is one, else lavapipe;
 * GUSUKU_VALIDATION and GUSUKU_DEVICE from the environment apply). For tools and tests. */
gusuku_result gusuku_runtime_open_headless(const gusuku_bakeset* bake_set, const gusuku_runtime_options* options,
                                           gusuku_runtime** out_runtime);

/* Renders one frame: the composite, frame_width * frame_height * 4 bytes, into output_rgba8 (NULL: none, e.g.
 * when the app uses gusuku_runtime_composite_image); the CPU-side facts into info (NULL: none). Synchronous (waits
 * on a fence); one frame of GPU work, no allocation. Bad input is GUSUKU_ERROR_INVALID_FRAME naming the field. */
gusuku_result gusuku_runtime_render(gusuku_runtime* runtime, const gusuku_frame_input* frame, uint8_t* output_rgba8,
                                    gusuku_frame_info* info);

/* The last frame's composite as a VkImage (R8G8B8A8_SRGB, frame size, TRANSFER_SRC_OPTIMAL), valid until the next
 * frame or close. O(1). */
gusuku_result gusuku_runtime_composite_image(const gusuku_runtime* runtime, VkImage* out_image);

/* Forgets the smoothed colour statistics (a cut in the camera feed). O(1). */
gusuku_result gusuku_runtime_reset_colour_statistics(gusuku_runtime* runtime);

/* Device memory the runtime holds, bytes (buffers and images, all allocated at open). O(1). */
gusuku_result gusuku_runtime_device_memory_bytes(const gusuku_runtime* runtime, uint64_t* out_bytes);

/* The last failure of a call on this runtime ("" if none); valid until its next failure or close; "" for NULL. */
const char* gusuku_runtime_last_error(const gusuku_runtime* runtime);

/* Waits for the runtime's GPU work, destroys everything it created (and a headless device). NULL: no-op. */
gusuku_result gusuku_runtime_close(gusuku_runtime* runtime);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_H */

/* The C API (gusuku.h) from C99, on a headless runtime (lavapipe, validation on: CTest fails the test on any
 * "Vulkan validation" line). The bake set is built here in C: a 2 m box on a flat ground grid, a sunny and an
 * overcast slot of constant baked light. Checked against numbers computed here, not by gusuku:
 *   - under full cloud cover the sun is gone and the overcast slot alone lights the building, so a pixel of its
 *     south face is sRGB(albedo / pi * E_ind_overcast * exposure), with the sRGB curve written out below;
 *   - a sky pixel (above the horizon, beside nothing) comes through bit for bit;
 *   - bad input (NaN pose, zero focal length, a NaN texel, a NULL array) gets the right code and a message naming
 *     the field, the runtime stays usable, and NULL handles never crash. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gusuku/runtime/gusuku.h"

static int g_failures = 0;

#define CHECK(condition)                                                                                          \
    do {                                                                                                          \
        if (!(condition)) {                                                                                       \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition);                         \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

#define CHECK_RESULT(call, expected)                                                                              \
    do {                                                                                                          \
        gusuku_result result_ = (call);                                                                           \
        if (result_ != (expected)) {                                                                              \
            fprintf(stderr, "%s:%d: %s returned %s, expected %s (%s)\n", __FILE__, __LINE__, #call,               \
                    gusuku_result_name(result_), gusuku_result_name(expected), gusuku_last_error_message());      \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

#define CHECK_MESSAGE_HAS(message, text)                                                                          \
    do {                                                                                                          \
        const char* message_ = (message);                                                                         \
        if (message_ == NULL || strstr(message_, (text)) == NULL) {                                               \
            fprintf(stderr, "%s:%d: message \"%s\" does not name \"%s\"\n", __FILE__, __LINE__,                   \
                    message_ ? message_ : "(NULL)", (text));                                                      \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

enum { kWidth = 64, kHeight = 48, kLightmap = 8, kCells = 16 };
static const double kFocal = 60.0;
static const float kAlbedo = 0.5f;
static const float kSunnyIndirect = 0.4f, kOvercastIndirect = 1.2f, kGroundIrradiance = 2.0f;
static const float kExposure = 1.0f;

/* Everything the desc points at, kept alive while the bake set is created. */
typedef struct BoxScene {
    float positions[24 * 3], normals[24 * 3], uv0[24 * 2], uv1[24 * 2];
    uint32_t indices[36], triangle_material[12];
    gusuku_material material;
    float ground_geometry[kCells * kCells * 4];
    float lightmap_sunny[kLightmap * kLightmap * 4], lightmap_overcast[kLightmap * kLightmap * 4];
    float ground[kCells * kCells * 4];
    gusuku_slot slots[2];
    gusuku_bakeset_desc desc;
} BoxScene;

static void fill(float* rgba, int texels, float rgb, float alpha) {
    int i;
    for (i = 0; i < texels; ++i) {
        rgba[4 * i + 0] = rgba[4 * i + 1] = rgba[4 * i + 2] = rgb;
        rgba[4 * i + 3] = alpha;
    }
}

/* The box [-1, 1] x [-1, 1] x [0, 3] m, six outward quads, each in its own sixth of the lightmap. */
static void buildBox(BoxScene* scene) {
    static const float corners[8][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
                                        {-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}};
    static const int faces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}, {3, 2, 1, 0}};
    static const float normals[6][3] = {{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
    static const float quad_uv[4][2] = {{0.15f, 0.15f}, {0.85f, 0.15f}, {0.85f, 0.85f}, {0.15f, 0.85f}};
    static const uint32_t quad_indices[6] = {0, 1, 2, 0, 2, 3};
    int face, corner, i;
    for (face = 0; face < 6; ++face) {
        for (corner = 0; corner < 4; ++corner) {
            const int vertex = face * 4 + corner;
            for (i = 0; i < 3; ++i) {
                scene->positions[3 * vertex + i] = corners[faces[face][corner]][i];
                scene->normals[3 * vertex + i] = normals[face][i];
            }
            scene->uv0[2 * vertex + 0] = quad_uv[corner][0];
            scene->uv0[2 * vertex + 1] = quad_uv[corner][1];
            scene->uv1[2 * vertex + 0] = (float)(face % 3) / 3.0f + quad_uv[corner][0] / 3.0f;
            scene->uv1[2 * vertex + 1] = (float)(face / 3) / 2.0f + quad_uv[corner][1] / 2.0f;
        }
        for (i = 0; i < 6; ++i) scene->indices[face * 6 + i] = (uint32_t)(face * 4) + quad_indices[i];
        scene->triangle_material[2 * face] = scene->triangle_material[2 * face + 1] = 0;
    }
    scene->material.base_color_factor[0] = scene->material.base_color_factor[1] =
        scene->material.base_color_factor[2] = kAlbedo;
    scene->material.base_color_factor[3] = 1.0f;
    scene->material.base_color_texture = -1;
}

static void buildBakeSet(BoxScene* scene) {
    gusuku_bakeset_desc* desc = &scene->desc;
    int s, i;
    memset(scene, 0, sizeof *scene);
    buildBox(scene);
    /* Flat ground at z = 0: normal up, height 0. */
    fill(scene->ground_geometry, kCells * kCells, 0.0f, 0.0f);
    for (i = 0; i < kCells * kCells; ++i) scene->ground_geometry[4 * i + 2] = 1.0f;
    fill(scene->lightmap_sunny, kLightmap * kLightmap, kSunnyIndirect, 1.0f);
    fill(scene->lightmap_overcast, kLightmap * kLightmap, kOvercastIndirect, 1.0f);
    fill(scene->ground, kCells * kCells, kGroundIrradiance, 1.0f);

    for (s = 0; s < 2; ++s) {
        gusuku_slot* slot = &scene->slots[s];
        slot->sky = s == 0 ? GUSUKU_SKY_SUNNY : GUSUKU_SKY_OVERCAST;
        slot->sun_azimuth_deg = 90.0;
        slot->sun_apparent_elevation_deg = 45.0;
        slot->sun_present = s == 0;
        slot->sun_irradiance_rgb[0] = slot->sun_irradiance_rgb[1] = slot->sun_irradiance_rgb[2] = 5.0;
        slot->has_colour_statistics = 1;
        slot->lab_mean[0] = 50.0;
        slot->lab_sigma[0] = 10.0;
        slot->lab_sigma[1] = slot->lab_sigma[2] = 2.0;
        slot->building.width = slot->building.height = kLightmap;
        slot->building.rgba = s == 0 ? scene->lightmap_sunny : scene->lightmap_overcast;
        slot->ground_with.width = slot->ground_with.height = kCells;
        slot->ground_with.rgba = scene->ground;
        slot->ground_without = slot->ground_with;
    }

    desc->latitude_deg = 26.2856;
    desc->longitude_deg = 127.8008;
    desc->height_m = 160.0;
    desc->positions = scene->positions;
    desc->normals = scene->normals;
    desc->uv0 = scene->uv0;
    desc->uv1 = scene->uv1;
    desc->vertex_count = 24;
    desc->indices = scene->indices;
    desc->index_count = 36;
    desc->triangle_material = scene->triangle_material;
    desc->materials = &scene->material;
    desc->material_count = 1;
    desc->lightmap_resolution = kLightmap;
    desc->ground_origin_enu_m[0] = desc->ground_origin_enu_m[1] = -8.0;
    desc->ground_cell_m = 1.0;
    desc->ground_columns = desc->ground_rows = kCells;
    desc->ground_geometry.width = desc->ground_geometry.height = kCells;
    desc->ground_geometry.rgba = scene->ground_geometry;
    desc->slots = scene->slots;
    desc->slot_count = 2;
}

/* sRGB encoding (IEC 61966-2-1), written out here rather than taken from gusuku. */
static double srgbEncode(double linear) {
    if (linear <= 0.0031308) return 12.92 * linear;
    return 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

/* A camera 12 m south of the box at 1.5 m, looking north: x right = east, y down = -up, z forward = north. */
static void setCamera(gusuku_frame_input* frame) {
    static const double camera_to_enu[9] = {1, 0, 0, /**/ 0, 0, 1, /**/ 0, -1, 0};
    frame->intrinsics.fx = frame->intrinsics.fy = kFocal;
    frame->intrinsics.cx = kWidth / 2.0;
    frame->intrinsics.cy = kHeight / 2.0;
    frame->intrinsics.width = kWidth;
    frame->intrinsics.height = kHeight;
    frame->pose.position_enu[0] = 0.0;
    frame->pose.position_enu[1] = -12.0;
    frame->pose.position_enu[2] = 1.5;
    memcpy(frame->pose.camera_to_enu, camera_to_enu, sizeof camera_to_enu);
}

static void testNullHandlesNeverCrash(void) {
    gusuku_runtime* runtime = (gusuku_runtime*)&g_failures; /* poisoned: must be overwritten with NULL */
    gusuku_bakeset* bake_set = (gusuku_bakeset*)&g_failures;
    gusuku_frame_input frame;
    uint64_t bytes = 0;
    VkImage image = VK_NULL_HANDLE;
    CHECK_RESULT(gusuku_frame_input_default(&frame), GUSUKU_OK);
    CHECK_RESULT(gusuku_runtime_open_headless(NULL, NULL, &runtime), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(runtime == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "bake_set");
    CHECK_RESULT(gusuku_runtime_open(NULL, NULL, NULL, &runtime), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_open_headless(NULL, NULL, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_bakeset_create(NULL, &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(bake_set == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "desc");
    CHECK_RESULT(gusuku_bakeset_create(NULL, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_render(NULL, &frame, NULL, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "runtime: is NULL");
    CHECK_RESULT(gusuku_runtime_device_memory_bytes(NULL, &bytes), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_composite_image(NULL, &image), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_reset_colour_statistics(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_options_default(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_frame_input_default(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(strcmp(gusuku_runtime_last_error(NULL), "") == 0);
    CHECK_RESULT(gusuku_runtime_close(NULL), GUSUKU_OK);
    CHECK_RESULT(gusuku_bakeset_free(NULL), GUSUKU_OK);
    CHECK(strcmp(gusuku_result_name(GUSUKU_ERROR_INVALID_FRAME), "GUSUKU_ERROR_INVALID_FRAME") == 0);
    CHECK(strcmp(gusuku_result_name((gusuku_result)99), "GUSUKU_UNKNOWN_RESULT") == 0);
}

static void testBadBakeSetsAreRefusedNamingTheField(void) {
    BoxScene* scene = (BoxScene*)malloc(sizeof(BoxScene));
    gusuku_bakeset* bake_set = NULL;
    buildBakeSet(scene);
    /* A NaN texel in the overcast slot's lightmap, texel (3, 1). */
    scene->lightmap_overcast[4 * (1 * kLightmap + 3) + 1] = NAN;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
    CHECK(bake_set == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "slots[1].building: texel (3, 1) channel G is NaN");
    scene->lightmap_overcast[4 * (1 * kLightmap + 3) + 1] = kOvercastIndirect;
    /* A NULL array with a count. */
    scene->desc.normals = NULL;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "desc.normals: NULL with vertex_count 24");
    scene->desc.normals = scene->normals;
    /* An image too large to count its bytes safely. */
    scene->slots[0].ground_with.width = 70000;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "desc.slots[0].ground_with: 70000 x 16 texels");
    scene->slots[0].ground_with.width = kCells;
    /* No slot: the runtime would have no lightmap layer to upload. */
    scene->desc.slot_count = 0;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
    CHECK(bake_set == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "manifest.slots: empty");
    scene->desc.slot_count = 2;
    /* An index out of range. */
    scene->indices[7] = 24;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "building.indices[7]");
    free(scene);
}

static void testRendersAndRefusesBadFrames(void) {
    BoxScene* scene = (BoxScene*)malloc(sizeof(BoxScene));
    gusuku_bakeset* bake_set = NULL;
    gusuku_runtime* runtime = NULL;
    gusuku_runtime_options options;
    gusuku_frame_input frame;
    gusuku_frame_info info;
    uint8_t* camera = (uint8_t*)malloc(kWidth * kHeight * 4);
    uint8_t* output = (uint8_t*)malloc(kWidth * kHeight * 4);
    uint64_t device_bytes = 0;
    size_t i;
    int channel, x;

    buildBakeSet(scene);
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_OK);
    free(scene); /* the bake set holds its own copy */
    CHECK_RESULT(gusuku_runtime_options_default(&options), GUSUKU_OK);
    CHECK(options.frame_width == 1280 && options.shadow_map_size == 1024);
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    {
        /* Every option out of range (NaN included) is refused at open, naming it; its edge values open. */
        struct {
            float* field;
            float bad;
            const char* name;
        } bad_options[] = {
            {&options.shadow_bias_texels, NAN, "options.shadow_bias_texels"},
            {&options.shadow_bias_texels, -1.0f, "options.shadow_bias_texels"},
            {&options.statistics_smoothing_frames, 0.5f, "options.statistics_smoothing_frames"},
            {&options.statistics_smoothing_frames, INFINITY, "options.statistics_smoothing_frames"},
            {&options.colour_gain_limit, NAN, "options.colour_gain_limit"},
            {&options.colour_gain_limit, -2.0f, "options.colour_gain_limit"},
            {&options.direct_only_ambient_fraction, NAN, "options.direct_only_ambient_fraction"},
            {&options.direct_only_shadow_darkening, 2.0f, "options.direct_only_shadow_darkening"},
            {&options.direct_only_shadow_darkening, NAN, "options.direct_only_shadow_darkening"},
        };
        size_t b;
        for (b = 0; b < sizeof bad_options / sizeof bad_options[0]; ++b) {
            const float kept = *bad_options[b].field;
            gusuku_runtime* refused = NULL;
            *bad_options[b].field = bad_options[b].bad;
            CHECK_RESULT(gusuku_runtime_open_headless(bake_set, &options, &refused), GUSUKU_ERROR_INVALID_FRAME);
            CHECK(refused == NULL);
            CHECK_MESSAGE_HAS(gusuku_last_error_message(), bad_options[b].name);
            *bad_options[b].field = kept;
        }
        options.statistics_smoothing_frames = 1.0f; /* the edge itself is in range */
    }
    CHECK_RESULT(gusuku_runtime_open_headless(bake_set, &options, &runtime), GUSUKU_OK);
    CHECK_RESULT(gusuku_bakeset_free(bake_set), GUSUKU_OK); /* the runtime keeps no pointer into it */
    if (runtime == NULL) {
        fprintf(stderr, "open failed: %s\n", gusuku_last_error_message());
        ++g_failures;
        free(camera);
        free(output);
        return;
    }
    CHECK_RESULT(gusuku_runtime_device_memory_bytes(runtime, &device_bytes), GUSUKU_OK);
    /* At least the composite target and its readback buffer, and the 256^2 shadow map of 2+ bytes per texel. */
    CHECK(device_bytes >= 2u * kWidth * kHeight * 4 + 256u * 256u * 2);

    for (i = 0; i < (size_t)kWidth * kHeight * 4; ++i) camera[i] = (uint8_t)(i % 4 == 3 ? 255 : 40 + (i * 7) % 160);
    CHECK_RESULT(gusuku_frame_input_default(&frame), GUSUKU_OK);
    CHECK(frame.exposure == 1.0f && frame.flags == (GUSUKU_FRAME_BLEND_SLOTS | GUSUKU_FRAME_GROUND_RATIO));
    setCamera(&frame);
    frame.camera_rgba8 = camera;
    frame.utc_unix_seconds = 1782000000.0; /* 2026-06-21T00:00:00Z, 09:00 at the site */
    frame.weather.cloud_cover = 1.0f;
    frame.exposure = kExposure;
    frame.colour_match = GUSUKU_COLOUR_MATCH_OFF;
    memset(&info, 0, sizeof info);
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_OK);
    CHECK(info.overcast_slot == 1 && info.overcast_weight == 1.0f);
    CHECK(info.sun_irradiance_rgb[0] == 0.0); /* full cloud: no direct sun */
    CHECK(fabs(info.sun_direction_enu[0] * info.sun_direction_enu[0] + info.sun_direction_enu[1] *
               info.sun_direction_enu[1] + info.sun_direction_enu[2] * info.sun_direction_enu[2] - 1.0) < 1e-9);
    {
        /* The south face's centre (0, -1, 1.5) is 11 m straight ahead: the image centre. */
        const size_t at = ((size_t)(kHeight / 2) * kWidth + kWidth / 2) * 4;
        const double linear = kAlbedo / 3.14159265358979323846 * kOvercastIndirect * kExposure;
        const double expected = 255.0 * srgbEncode(linear);
        for (channel = 0; channel < 3; ++channel) {
            if (fabs(output[at + channel] - expected) > 1.5) {
                fprintf(stderr, "building pixel channel %d: %d, expected %.2f\n", channel, output[at + channel],
                        expected);
                ++g_failures;
            }
        }
        CHECK(output[at + 3] == 255);
        printf("building pixel %d %d %d, expected %.2f; %llu bytes of device memory\n", output[at], output[at + 1],
               output[at + 2], expected, (unsigned long long)device_bytes);
        /* Row 0 looks 21 degrees up, above the 3 m box at 11 m (14 degrees) and above the horizon. */
        for (x = 0; x < kWidth * 4; ++x) CHECK(output[x] == camera[x]);
    }

    /* Bad frames: the right code, a message naming the field, per runtime and per thread; no pixel written. */
    frame.pose.position_enu[0] = NAN;
    memset(output, 7, kWidth * kHeight * 4);
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_ERROR_INVALID_FRAME);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "pose.position_enu");
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "pose.position_enu");
    CHECK(output[0] == 7 && output[kWidth * kHeight * 4 - 1] == 7);
    setCamera(&frame);
    frame.intrinsics.fx = 0.0;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_ERROR_INVALID_FRAME);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "intrinsics");
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "fx");
    setCamera(&frame);
    frame.mode = (gusuku_render_mode)5;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_ERROR_INVALID_FRAME);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "mode");
    frame.mode = GUSUKU_MODE_PROPOSED;
    CHECK_RESULT(gusuku_runtime_render(runtime, NULL, output, &info), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "frame: is NULL");
    /* Still usable after the errors, and the same frame gives the same bytes. */
    {
        uint8_t* again = (uint8_t*)malloc(kWidth * kHeight * 4);
        uint8_t* first = (uint8_t*)malloc(kWidth * kHeight * 4);
        CHECK_RESULT(gusuku_runtime_render(runtime, &frame, first, NULL), GUSUKU_OK);
        CHECK_RESULT(gusuku_runtime_render(runtime, &frame, again, NULL), GUSUKU_OK);
        CHECK(memcmp(first, again, kWidth * kHeight * 4) == 0);
        free(again);
        free(first);
    }
    CHECK_RESULT(gusuku_runtime_close(runtime), GUSUKU_OK);
    free(camera);
    free(output);
}

int main(void) {
    printf("gusuku %s, C API test\n", gusuku_version());
    testNullHandlesNeverCrash();
    testBadBakeSetsAreRefusedNamingTheField();
    testRendersAndRefusesBadFrames();
    if (g_failures != 0) {
        fprintf(stderr, "%d check(s) failed\n", g_failures);
        return 1;
    }
    printf("all checks passed\n");
    return 0;
}

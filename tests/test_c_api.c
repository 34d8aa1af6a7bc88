/* The C API (gusuku.h) from C99, on a headless runtime (lavapipe, validation on: CTest fails the test on any
 * "Vulkan validation" line). The bake set is built here in C: a 2 m box on a flat ground grid, a sunny and an
 * overcast slot of constant baked light. Checked against numbers computed here, not by gusuku:
 *   - under full cloud cover the sun is gone and the overcast slot alone lights the building, so a pixel of its
 *     south face is sRGB(albedo / pi * E_ind_overcast * exposure), with the sRGB curve written out below;
 *   - a sky pixel (above the horizon, beside nothing) comes through bit for bit;
 *   - bad input (NaN pose, zero focal length, a NaN texel, a NULL array, an unset struct_size) gets the right code
 *     and a message naming the field, the runtime stays usable, and NULL handles never crash;
 *   - the frame's counters (ground quads: (cells - 1)^2 in the grid, none drawn without sun or change), the
 *     profiled frame (same bytes, every pass timed) and the ground colour match of a desc with ground albedo;
 *   - the helpers against values worked out by hand: look-at, field of view, projection, the weather estimate. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gusuku/runtime/gusuku.h"
#include "support/c_checks.h"


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
    float ground[kCells * kCells * 4], ground_albedo[kCells * kCells * 4];
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
    fill(scene->ground_albedo, kCells * kCells, 0.3f, 1.0f);

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

    desc->struct_size = sizeof *desc;
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
    desc->ground_albedo.width = desc->ground_albedo.height = kCells;
    desc->ground_albedo.rgba = scene->ground_albedo;
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
    CHECK_RESULT(gusuku_runtime_invalidate_shadow_maps(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_runtime_invalidate_shadow_maps: runtime: is NULL");
    CHECK_RESULT(gusuku_runtime_render_profiled(NULL, &frame, NULL, NULL, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_runtime_render_profiled: runtime: is NULL");
    CHECK_RESULT(gusuku_runtime_options_fill_defaults(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_frame_input_fill_defaults(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_runtime_options_default(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(gusuku_frame_input_default(NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(strcmp(gusuku_runtime_last_error(NULL), "") == 0);
    CHECK_RESULT(gusuku_runtime_close(NULL), GUSUKU_OK);
    CHECK_RESULT(gusuku_bakeset_free(NULL), GUSUKU_OK);
    CHECK(strcmp(gusuku_result_name(GUSUKU_ERROR_INVALID_FRAME), "GUSUKU_ERROR_INVALID_FRAME") == 0);
    CHECK(strcmp(gusuku_result_name((gusuku_result)99), "GUSUKU_UNKNOWN_RESULT") == 0);
}

/* Every versioned struct refuses an unset struct_size naming it; fill_defaults fills only what the size names. */
static void testStructSizesAreChecked(void) {
    BoxScene* scene = (BoxScene*)malloc(sizeof(BoxScene));
    gusuku_bakeset* bake_set = (gusuku_bakeset*)&g_failures;
    gusuku_runtime* runtime = (gusuku_runtime*)&g_failures;
    gusuku_runtime_options options;
    gusuku_vulkan_device device;
    CHECK(gusuku_api_version() == GUSUKU_API_VERSION && GUSUKU_API_VERSION >= 1u);
    /* The paper's names stay, as aliases of today's (a C compiler, not only C++, must see them equal). */
    CHECK(GUSUKU_MODE_BAKED_LIGHT == 0 && GUSUKU_MODE_PROPOSED == GUSUKU_MODE_BAKED_LIGHT);
    CHECK(GUSUKU_COLOUR_MATCH_REINHARD == 1 && GUSUKU_COLOUR_MATCH_PAPER == GUSUKU_COLOUR_MATCH_REINHARD);
    buildBakeSet(scene);
    scene->desc.struct_size = 0;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(bake_set == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_bakeset_create: desc.struct_size: 0 is not the size of "
                                                   "any gusuku_bakeset_desc this library knows (");
    scene->desc.struct_size = sizeof scene->desc;
    CHECK_RESULT(gusuku_bakeset_create(&scene->desc, &bake_set), GUSUKU_OK);
    memset(&options, 0, sizeof options);
    options.struct_size = 3;
    CHECK_RESULT(gusuku_runtime_options_fill_defaults(&options), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(options.frame_width == 0); /* untouched */
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "options.struct_size: 3");
    CHECK_RESULT(gusuku_runtime_open_headless(bake_set, &options, &runtime), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK(runtime == NULL);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_runtime_open_headless: options.struct_size: 3");
    CHECK_RESULT(gusuku_runtime_options_default(&options), GUSUKU_OK);
    memset(&device, 0, sizeof device); /* struct_size 0 is refused before the NULL handles are */
    CHECK_RESULT(gusuku_runtime_open(&device, bake_set, &options, &runtime), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_runtime_open: device.struct_size: 0");
    device.struct_size = sizeof device;
    CHECK_RESULT(gusuku_runtime_open(&device, bake_set, &options, &runtime), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "device: instance, physical_device, device and queue");
    CHECK_RESULT(gusuku_bakeset_free(bake_set), GUSUKU_OK);
    free(scene);
}

/* The helpers against values worked out here. */
static void testCameraAndWeatherHelpers(void) {
    static const double expected_rotation[9] = {1, 0, 0, /**/ 0, 0, 1, /**/ 0, -1, 0};
    const double position[3] = {0.0, -12.0, 1.5}, target[3] = {0.0, 0.0, 1.5}, ahead[3] = {1.0, 0.0, 0.5};
    const double behind[3] = {0.0, -20.0, 1.5}, not_finite[3] = {0.0, NAN, 0.0};
    static uint8_t black[kWidth * kHeight * 4];
    gusuku_pose pose;
    gusuku_intrinsics intrinsics;
    gusuku_weather weather = {0.5f};
    double pixel[2] = {0.0, 0.0};
    int32_t in_front = -1;
    int i;
    /* Looking north, level: camera x = east, y = down, z = north; the position kept. */
    CHECK_RESULT(gusuku_pose_looking_at(position, target, &pose), GUSUKU_OK);
    for (i = 0; i < 9; ++i) CHECK(fabs(pose.camera_to_enu[i] - expected_rotation[i]) < 1e-12);
    CHECK(pose.position_enu[1] == -12.0 && pose.position_enu[2] == 1.5);
    CHECK_RESULT(gusuku_pose_looking_at(position, position, &pose), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_pose_looking_at: target_enu: within 1 um");
    CHECK_RESULT(gusuku_pose_looking_at(not_finite, target, &pose), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "position_enu[1]: not finite");
    CHECK_RESULT(gusuku_pose_looking_at(position, target, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    /* 90 degrees across 64 pixels: f = 32 / tan(45 degrees) = 32. */
    CHECK_RESULT(gusuku_intrinsics_from_field_of_view(kWidth, kHeight, 90.0, &intrinsics), GUSUKU_OK);
    CHECK(fabs(intrinsics.fx - 32.0) < 1e-12 && fabs(intrinsics.fy - 32.0) < 1e-12);
    CHECK(intrinsics.cx == 32.0 && intrinsics.cy == 24.0 && intrinsics.width == kWidth && intrinsics.height == kHeight);
    CHECK_RESULT(gusuku_intrinsics_from_field_of_view(kWidth, kHeight, 180.0, &intrinsics),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "horizontal_fov_deg: 180");
    CHECK_RESULT(gusuku_intrinsics_from_field_of_view(0, kHeight, 60.0, &intrinsics), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "width, height: 0 x 48");
    /* (1, 0, 0.5) from (0, -12, 1.5) looking north: camera (1, 1, 12), so u = 60 / 12 + 32, v = 60 / 12 + 24. */
    CHECK_RESULT(gusuku_pose_looking_at(position, target, &pose), GUSUKU_OK);
    intrinsics.fx = intrinsics.fy = kFocal;
    CHECK_RESULT(gusuku_project_to_pixel(&intrinsics, &pose, ahead, pixel, &in_front), GUSUKU_OK);
    CHECK(in_front == 1 && fabs(pixel[0] - 37.0) < 1e-9 && fabs(pixel[1] - 29.0) < 1e-9);
    CHECK_RESULT(gusuku_project_to_pixel(&intrinsics, &pose, behind, pixel, &in_front), GUSUKU_OK);
    CHECK(in_front == 0 && isnan(pixel[0]) && isnan(pixel[1]));
    intrinsics.fy = 0.0;
    CHECK_RESULT(gusuku_project_to_pixel(&intrinsics, &pose, ahead, pixel, &in_front), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_project_to_pixel: intrinsics: focal lengths");
    intrinsics.fy = kFocal;
    pose.camera_to_enu[0] = 2.0;
    CHECK_RESULT(gusuku_project_to_pixel(&intrinsics, &pose, ahead, pixel, &in_front), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "pose.camera_to_enu: not a rotation");
    /* An all-black frame reads as overcast (weather_estimate.h's documented fallback). */
    CHECK_RESULT(gusuku_weather_estimate(black, kWidth, kHeight, &weather), GUSUKU_OK);
    CHECK(weather.cloud_cover == 1.0f);
    CHECK_RESULT(gusuku_weather_estimate(NULL, kWidth, kHeight, &weather), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "gusuku_weather_estimate: camera_rgba8: is NULL");
    CHECK_RESULT(gusuku_weather_estimate(black, 70000, 70000, &weather), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_last_error_message(), "at most 2^28 pixels");
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

/* A sunny frame: the box's shadow gets ratio quads, some but not all; profiled, the same bytes and every pass
 * timed; the ground colour match runs (the desc gave ground albedo); invalidating the shadow maps changes nothing. */
static void checkSunnyFrameCountersAndProfile(gusuku_runtime* runtime, const gusuku_frame_input* overcast,
                                              const uint8_t* camera) {
    gusuku_frame_input frame = *overcast;
    gusuku_frame_info info, profiled_info;
    gusuku_pass_timings timings;
    uint8_t* plain = (uint8_t*)malloc(kWidth * kHeight * 4);
    uint8_t* profiled = (uint8_t*)malloc(kWidth * kHeight * 4);
    memset(&info, 0, sizeof info);
    memset(&profiled_info, 0, sizeof profiled_info);
    memset(&timings, 0, sizeof timings);
    info.struct_size = profiled_info.struct_size = sizeof info;
    timings.struct_size = sizeof timings;
    frame.camera_rgba8 = camera;
    frame.weather.cloud_cover = 0.0f;
    /* 09:00 at the site (the overcast frame's instant): the sun at about 45 degrees, a 3 m shadow to the west. */
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, plain, &info), GUSUKU_OK);
    CHECK(info.sun_above_horizon && info.ground_quads_total == (kCells - 1) * (kCells - 1));
    CHECK(info.ground_quads_drawn > 0 && info.ground_quads_drawn < info.ground_quads_total);
    CHECK_RESULT(gusuku_runtime_invalidate_shadow_maps(runtime), GUSUKU_OK);
    CHECK_RESULT(gusuku_runtime_render_profiled(runtime, &frame, profiled, &profiled_info, &timings), GUSUKU_OK);
    CHECK(memcmp(plain, profiled, kWidth * kHeight * 4) == 0);
    CHECK(profiled_info.ground_quads_drawn == info.ground_quads_drawn);
    CHECK(timings.struct_size == sizeof timings && timings.shadow_ms > 0.0 && timings.building_ms > 0.0);
    CHECK(timings.total_ms >= timings.shadow_ms + timings.building_ms);
    printf("sunny frame: %u of %u ground quads drawn; profiled %.2f ms (shadow %.2f, building %.2f)\n",
           info.ground_quads_drawn, info.ground_quads_total, timings.total_ms, timings.shadow_ms, timings.building_ms);
    CHECK_RESULT(gusuku_runtime_render_profiled(runtime, &frame, profiled, &profiled_info, NULL),
                 GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "gusuku_runtime_render_profiled: timings: is NULL");
    frame.colour_match = GUSUKU_COLOUR_MATCH_GROUND;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, profiled, NULL), GUSUKU_OK);
    free(plain);
    free(profiled);
}

/* struct_size: unset or larger than this library knows, the frame and the info are refused naming it. */
static void checkFrameStructSizes(gusuku_runtime* runtime, const gusuku_frame_input* good, uint8_t* output) {
    gusuku_frame_input frame = *good;
    gusuku_frame_info info;
    memset(&info, 0, sizeof info);
    frame.struct_size = 0;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "gusuku_runtime_render: frame.struct_size: 0 is not the "
                                                          "size of any gusuku_frame_input this library knows");
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "set it to sizeof(gusuku_frame_input)");
    frame.struct_size = sizeof frame + 8;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, NULL), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "built against a newer gusuku.h");
    frame.struct_size = sizeof frame;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_ERROR_INVALID_ARGUMENT);
    CHECK_MESSAGE_HAS(gusuku_runtime_last_error(runtime), "info.struct_size: 0");
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
    CHECK(options.struct_size == sizeof options);
    CHECK(options.frame_width == 1280 && options.shadow_map_size == 1024);
    CHECK(options.shadow_sun_step_deg == 0.05f && options.ground_change_threshold == 1.0f / 255.0f);
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
            {&options.shadow_sun_step_deg, 11.0f, "options.shadow_sun_step_deg"},
            {&options.shadow_sun_step_deg, NAN, "options.shadow_sun_step_deg"},
            {&options.ground_change_threshold, 1.5f, "options.ground_change_threshold"},
            {&options.ground_change_threshold, -0.1f, "options.ground_change_threshold"},
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
    CHECK(frame.colour_match == GUSUKU_COLOUR_MATCH_AUTO); /* FrameInput's ColourMatch::kAuto */
    setCamera(&frame);
    frame.camera_rgba8 = camera;
    frame.utc_unix_seconds = 1782000000.0; /* 2026-06-21T00:00:00Z, 09:00 at the site */
    frame.weather.cloud_cover = 1.0f;
    frame.exposure = kExposure;
    frame.colour_match = GUSUKU_COLOUR_MATCH_OFF;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    CHECK_RESULT(gusuku_runtime_render(runtime, &frame, output, &info), GUSUKU_OK);
    CHECK(info.overcast_slot == 1 && info.overcast_weight == 1.0f);
    /* The grid's cells are its quads' corners; with no sun and ground_with == ground_without nothing changes. */
    CHECK(info.ground_quads_total == (kCells - 1) * (kCells - 1));
    CHECK(info.ground_quads_drawn == 0);
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
    frame.mode = GUSUKU_MODE_BAKED_LIGHT;
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
    checkSunnyFrameCountersAndProfile(runtime, &frame, camera);
    checkFrameStructSizes(runtime, &frame, output);
    CHECK_RESULT(gusuku_runtime_close(runtime), GUSUKU_OK);
    free(camera);
    free(output);
}

int main(void) {
    printf("gusuku %s, C API test\n", gusuku_version());
    testNullHandlesNeverCrash();
    testStructSizesAreChecked();
    testCameraAndWeatherHelpers();
    testBadBakeSetsAreRefusedNamingTheField();
    testRendersAndRefusesBadFrames();
    if (g_failures != 0) {
        fprintf(stderr, "%d check(s) failed\n", g_failures);
        return 1;
    }
    printf("all checks passed\n");
    return 0;
}

/* An app against the installed gusuku: a one-wall bake set in memory, a headless runtime, one frame. The wall
 * is lit by its overcast slot alone, so its pixel is sRGB(albedo / pi * E_ind), computed here. An optional argument
 * sets the samples a pixel (scripts/cross-build-aarch64.sh passes 1 under qemu-user while msaa 4 crashes there). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gusuku/runtime/gusuku.h>

#define SIZE 16

int main(int argc, char** argv) {
    /* A 4 m x 4 m wall in the plane y = 0 facing south (-y), centre (0, 0, 2). */
    const float positions[] = {-2, 0, 0, 2, 0, 0, 2, 0, 4, -2, 0, 4};
    const float normals[] = {0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0};
    const float uv[] = {0.25f, 0.25f, 0.75f, 0.25f, 0.75f, 0.75f, 0.25f, 0.75f};
    const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
    const uint32_t triangle_material[] = {0, 0};
    const gusuku_material material = {{0.5f, 0.5f, 0.5f, 1.0f}, -1};
    const float lightmap[2 * 2 * 4] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    const float ground_geometry[2 * 2 * 4] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float ground[2 * 2 * 4] = {2, 2, 2, 1, 2, 2, 2, 1, 2, 2, 2, 1, 2, 2, 2, 1};
    gusuku_slot overcast;
    gusuku_bakeset_desc desc;
    gusuku_bakeset* bake_set = NULL;
    gusuku_runtime_options options;
    gusuku_runtime* runtime = NULL;
    gusuku_frame_input frame;
    gusuku_frame_info info;
    uint8_t camera[SIZE * SIZE * 4], output[SIZE * SIZE * 4];
    uint64_t device_bytes = 0;
    const uint8_t* centre = output + ((SIZE / 2) * SIZE + SIZE / 2) * 4;
    double expected;

    memset(&overcast, 0, sizeof overcast);
    overcast.sky = GUSUKU_SKY_OVERCAST;
    overcast.building.width = overcast.building.height = 2;
    overcast.building.rgba = lightmap;
    overcast.ground_with.width = overcast.ground_with.height = 2;
    overcast.ground_with.rgba = ground;
    overcast.ground_without = overcast.ground_with;

    memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc;
    desc.latitude_deg = 26.2856;
    desc.longitude_deg = 127.8008;
    desc.positions = positions;
    desc.normals = normals;
    desc.uv0 = uv;
    desc.uv1 = uv;
    desc.vertex_count = 4;
    desc.indices = indices;
    desc.index_count = 6;
    desc.triangle_material = triangle_material;
    desc.materials = &material;
    desc.material_count = 1;
    desc.lightmap_resolution = 2;
    desc.ground_origin_enu_m[0] = desc.ground_origin_enu_m[1] = -4.0;
    desc.ground_cell_m = 4.0;
    desc.ground_columns = desc.ground_rows = 2;
    desc.ground_geometry.width = desc.ground_geometry.height = 2;
    desc.ground_geometry.rgba = ground_geometry;
    desc.slots = &overcast;
    desc.slot_count = 1;

    gusuku_runtime_options_default(&options);
    options.frame_width = options.frame_height = SIZE;
    options.shadow_map_size = 64;
    if (argc > 1) options.msaa_samples = (uint32_t)strtoul(argv[1], NULL, 10); /* the runtime refuses a bad count */
    if (gusuku_bakeset_create(&desc, &bake_set) != GUSUKU_OK ||
        gusuku_runtime_open_headless(bake_set, &options, &runtime) != GUSUKU_OK) {
        fprintf(stderr, "consumer: %s\n", gusuku_last_error_message());
        gusuku_bakeset_free(bake_set);
        return 1;
    }
    gusuku_bakeset_free(bake_set);

    memset(camera, 30, sizeof camera);
    gusuku_frame_input_default(&frame);
    frame.camera_rgba8 = camera;
    frame.intrinsics.fx = frame.intrinsics.fy = 16.0;
    frame.intrinsics.cx = frame.intrinsics.cy = SIZE / 2.0;
    frame.intrinsics.width = frame.intrinsics.height = SIZE;
    /* 10 m south of the wall at 2 m, looking north: camera x = east, y = down, z = north (row-major). */
    frame.pose.position_enu[1] = -10.0;
    frame.pose.position_enu[2] = 2.0;
    {
        const double camera_to_enu[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
        memcpy(frame.pose.camera_to_enu, camera_to_enu, sizeof camera_to_enu);
    }
    frame.utc_unix_seconds = 1782000000.0;
    frame.colour_match = GUSUKU_COLOUR_MATCH_OFF;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    if (gusuku_runtime_render(runtime, &frame, output, &info) != GUSUKU_OK ||
        gusuku_runtime_device_memory_bytes(runtime, &device_bytes) != GUSUKU_OK) {
        fprintf(stderr, "consumer: %s\n", gusuku_runtime_last_error(runtime));
        gusuku_runtime_close(runtime);
        return 1;
    }
    gusuku_runtime_close(runtime);

    expected = 0.5 / 3.14159265358979323846 * 1.0;
    expected = 255.0 * (1.055 * pow(expected, 1.0 / 2.4) - 0.055);
    printf("consumer: gusuku %s, %dx%d frame, %llu bytes of device memory, wall pixel %d %d %d (expected %.1f)\n",
           gusuku_version(), SIZE, SIZE, (unsigned long long)device_bytes, centre[0], centre[1], centre[2], expected);
    return fabs(centre[0] - expected) <= 1.5 && fabs(centre[1] - expected) <= 1.5 ? 0 : 1;
}

#include <stdio.h>
#include <gusuku/runtime/gusuku.h>
int main(void) { /* A grey 4 m wall facing south, baked irradiance 1, overcast: its pixel is sRGB(0.5 / pi) = 111 */
    const float wall[] = {-2, 0, 0, 2, 0, 0, 2, 0, 4, -2, 0, 4}, south[] = {0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0};
    const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1}; const gusuku_material grey = {{.5f, .5f, .5f, 1}, -1};
    static uint8_t camera[1280 * 720 * 4], out[1280 * 720 * 4]; /* the default frame size; a black camera image */
    float one[16], up[16]; for (int i = 0; i < 16; ++i) one[i] = 1, up[i] = i % 4 == 2;
    const uint32_t indices[] = {0, 1, 2, 0, 2, 3}, tri_material[] = {0, 0};
    const gusuku_slot overcast = {GUSUKU_SKY_OVERCAST, .building = {2, 2, one}, .ground_with = {2, 2, one},
                                  .ground_without = {2, 2, one}}; /* 2 x 2 texels of RGBA 1 each */
    const gusuku_bakeset_desc desc = {sizeof desc, .latitude_deg = 26.2856, .longitude_deg = 127.8008, /* size first */
        .positions = wall, .normals = south, .uv0 = uv, .uv1 = uv, .vertex_count = 4, .indices = indices,
        .index_count = 6, .triangle_material = tri_material, .materials = &grey, .material_count = 1,
        .lightmap_resolution = 2, .ground_origin_enu_m = {-4, -4}, .ground_cell_m = 4, .ground_columns = 2,
        .ground_rows = 2, .ground_geometry = {2, 2, up}, .slots = &overcast, .slot_count = 1}; /* up: +z, height 0 */
    gusuku_bakeset* set; gusuku_runtime* rt; gusuku_frame_input frame;
    if (gusuku_bakeset_create(&desc, &set) || gusuku_runtime_open_headless(set, NULL, &rt))
        return puts(gusuku_last_error_message()), 1;
    gusuku_bakeset_free(set); gusuku_frame_input_default(&frame); /* the runtime keeps its own copy of the set */
    frame.camera_rgba8 = camera; frame.weather.cloud_cover = 1; frame.utc_unix_seconds = 1782000000;
    frame.intrinsics = (gusuku_intrinsics){640, 640, 640, 360, 1280, 720}; /* 10 m south at 2 m, looking north: */
    frame.pose = (gusuku_pose){{0, -10, 2}, {1, 0, 0, 0, 0, 1, 0, -1, 0}}; /* camera x east, y down, z north */
    if (gusuku_runtime_render(rt, &frame, out, NULL)) return puts(gusuku_runtime_last_error(rt)), 1;
    gusuku_runtime_close(rt); const int red = out[(360 * 1280 + 640) * 4]; return red >= 110 && red <= 112 ? 0 : 1;
}

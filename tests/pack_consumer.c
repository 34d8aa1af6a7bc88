/* A C99 app as a phone app links gusuku: the runtime and the runtime pack's reader (gusuku_pack_loader, the C++
 * standard library only). pack_consumer PACK_FOLDER loads the pack, opens a headless runtime on it and renders one
 * 320 x 180 frame from 25 m south-east of the site's origin at 1.6 m, printing what it loaded; a bad pack prints
 * the loader's one-line message and exits 1. Its `ldd` must list only the Vulkan loader and the C/C++ runtime
 * (pack_consumer_ldd, tests/pack_consumer_ldd.cmake). */
#include <stdio.h>
#include <stdlib.h>

#include "gusuku/pack_loader/gusuku_pack_loader.h"
#include "gusuku/runtime/gusuku.h"

int main(int argc, char** argv) {
    if (argc != 2) return fprintf(stderr, "usage: pack_consumer PACK_FOLDER\n"), 2;
    gusuku_bakeset* set = NULL;
    if (gusuku_bakeset_load_pack(argv[1], &set) != GUSUKU_OK) return puts(gusuku_last_error_message()), 1;
    gusuku_runtime_options options;
    gusuku_runtime_options_default(&options);
    options.frame_width = 320;
    options.frame_height = 180;
    gusuku_runtime* runtime = NULL;
    if (gusuku_runtime_open_headless(set, &options, &runtime) != GUSUKU_OK) return puts(gusuku_last_error_message()), 1;
    gusuku_bakeset_free(set);
    unsigned char* camera = calloc(320 * 180 * 4, 1);
    unsigned char* out = calloc(320 * 180 * 4, 1);
    gusuku_frame_input frame;
    gusuku_frame_input_default(&frame);
    frame.camera_rgba8 = camera;
    frame.intrinsics = (gusuku_intrinsics){200, 200, 160, 90, 320, 180};
    /* World from camera, row-major (gusuku.h): camera x north-east, y down, z north-west, from (18, -18, 1.6). */
    frame.pose = (gusuku_pose){{18, -18, 1.6}, {0.7071f, 0, -0.7071f, 0.7071f, 0, 0.7071f, 0, -1, 0}};
    int result = 0;
    if (gusuku_runtime_render(runtime, &frame, out, NULL) != GUSUKU_OK) {
        puts(gusuku_runtime_last_error(runtime));
        result = 1;
    } else {
        size_t changed = 0;
        for (size_t index = 0; index < 320 * 180 * 4; ++index) changed += out[index] != camera[index];
        printf("pack_consumer: %s loaded and drawn, %zu of %d bytes differ from the camera frame\n", argv[1], changed,
               320 * 180 * 4);
    }
    gusuku_runtime_close(runtime);
    free(camera);
    free(out);
    return result;
}

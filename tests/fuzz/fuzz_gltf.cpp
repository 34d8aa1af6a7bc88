// libFuzzer target: loadGltf on arbitrary bytes as a .gltf (JSON), or as a .glb when built with GUSUKU_FUZZ_GLB.
// Bad input must end in gusuku::InputError; any other exception, a crash, a sanitizer report, a leak or a hang is
// a finding. The instancing and texture limits are lowered (the code paths are the same) so one input stays fast.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_workdir.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/formats/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
#ifdef GUSUKU_FUZZ_GLB
    const std::string path = gusuku::fuzz::writeInput("input.glb", data, size);
#else
    const std::string path = gusuku::fuzz::writeInput("input.gltf", data, size);
#endif
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    options.max_texture_size = 64;
    options.max_instanced_triangles = 20000;
    options.max_instanced_vertices = 60000;
    std::vector<std::string> warnings;
    try {
        gusuku::loadGltf(path, options, &warnings);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

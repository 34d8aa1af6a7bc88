// libFuzzer target: readFloatRgbaExr on arbitrary bytes, as the bake set loader reads every lightmap and ground
// image (scanline and tiled OpenEXR, and whatever else OpenImageIO recognises in the bytes). Bad input must end in
// gusuku::InputError; any other exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_workdir.h"
#include "gusuku/assets/image.h"
#include "gusuku/maths/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gusuku::fuzz::writeInput("lightmap.exr", data, size);
    try {
        gusuku::readFloatRgbaExr(path);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

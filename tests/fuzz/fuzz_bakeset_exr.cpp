// libFuzzer target: readFloatRgbaExr on arbitrary bytes, as the bake set loader reads every lightmap and ground
// image (scanline and tiled OpenEXR, and whatever else OpenImageIO recognises in the bytes). Bad input must end in
// gusuku::InputError; any other exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_workdir.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"

// The bake set loader decodes only a file whose header declares the manifest's size (loadExr reads the size
// first), so the harness decodes only headers up to that of a large lightmap: a corrupt header declaring 10^8
// texels makes OpenEXR allocate 1.6 GB, which under AddressSanitizer takes more than the 10 s that counts as a
// hang, and which the loader never reaches.
constexpr int64_t kLargestDecodedTexels = int64_t(4096) * 4096;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gusuku::fuzz::writeInput("lightmap.exr", data, size);
    try {
        const gusuku::ImageSize declared = gusuku::readImageSize(path);
        if (int64_t(declared.width) * declared.height > kLargestDecodedTexels) return 0;
        gusuku::readFloatRgbaExr(path);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

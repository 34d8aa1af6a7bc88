// libFuzzer target: an 8-bit sky photo's exposure from its EXIF and its decoding (gusuku/assets/sky_photo.h), on
// arbitrary bytes named photo.jpg: skyPhotoEv100 (OpenImageIO's EXIF parser, then EV100 from ExposureTime, FNumber
// and the ISO speed, held to site.json's ev100 range), then readSkyPhotos as the bake reads the sky (the JPEG or
// PNG decode, a truncated file refused, the 2:1 check). Bad input must end in gusuku::InputError; any other
// exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "fuzz_workdir.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/formats/input_error.h"

// A decoded photo under AddressSanitizer: headers declaring more are not decoded (the reader would, band by band,
// but a fuzzed 8192 x 4096 photo takes longer than the 10 s that count as a hang).
constexpr int64_t kLargestDecodedTexels = int64_t(1024) * 512;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gusuku::fuzz::writeInput("photo.jpg", data, size);
    try {
        const double ev100 = gusuku::skyPhotoEv100(path, std::nullopt);
        // What the reader returns is what the bake's lighting takes: a finite EV100 inside site.json's range.
        if (!(ev100 >= gusuku::kSkyPhotoEv100Range.minimum && ev100 <= gusuku::kSkyPhotoEv100Range.maximum)) {
            std::fprintf(stderr, "fuzz_exif: EV100 %g returned outside the range\n", ev100);
            std::abort();
        }
    } catch (const gusuku::InputError&) {
    }
    try {
        const gusuku::ImageSize declared = gusuku::readImageSize(path);
        if (int64_t(declared.width) * declared.height > kLargestDecodedTexels) return 0;
        // The exposure as site.json's ev100, so the decode is fuzzed whether or not the EXIF holds one.
        gusuku::readSkyPhotos({gusuku::SkyPhotoConfig{path, 12.0}});
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

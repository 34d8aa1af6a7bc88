// libFuzzer target: the runtime pack's readers (standard library only, gusuku_pack_loader) on arbitrary bytes. The
// first byte chooses the reader (modulo 8): 0-3 decodeKtx2 expecting E5B9G9R9, R8, RGBA32F or RGBA8 sRGB;
// 4 decodePackGeometry (pack.bin); 5 readPackManifest (manifest.json and its JSON reader); 6 decodeKtx2 expecting
// ASTC 4x4 HDR (the lightmaps); 7 decodeKtx2MipChain expecting ASTC 6x6 sRGB (the textures' mip chains). Bad input must end
// in gusuku::InputError; any other exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gusuku/maths/input_error.h"
#include "gusuku/maths/ktx2.h"
#include "gusuku/maths/pack_geometry.h"
#include "pack_manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const int reader = data[0] % 8;  // seeds 0-6 keep their reader
    const uint8_t* bytes = data + 1;
    const size_t length = size - 1;
    const gusuku::Ktx2Format formats[4] = {gusuku::Ktx2Format::kE5b9g9r9Ufloat, gusuku::Ktx2Format::kR8Unorm,
                                           gusuku::Ktx2Format::kR32g32b32a32Sfloat, gusuku::Ktx2Format::kR8g8b8a8Srgb};
    try {
        if (reader < 4)
            gusuku::decodeKtx2(bytes, length, "lightmap.ktx2", formats[reader]);
        else if (reader == 6)
            gusuku::decodeKtx2(bytes, length, "lightmap_astc.ktx2", gusuku::Ktx2Format::kAstc4x4Sfloat);
        else if (reader == 7)
            gusuku::decodeKtx2MipChain(bytes, length, "texture_0_astc.ktx2", gusuku::Ktx2Format::kAstc6x6Srgb);
        else if (reader == 4)
            gusuku::decodePackGeometry(bytes, length, "pack.bin");
        else
            gusuku::pack_detail::readPackManifest(std::string(reinterpret_cast<const char*>(bytes), length), "manifest.json");
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

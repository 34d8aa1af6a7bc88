// libFuzzer target: the runtime pack's readers (standard library only, gusuku_pack_loader) on arbitrary bytes. The
// first byte chooses the reader (modulo 9): 0-3 decodeKtx2 expecting E5B9G9R9, R8, RGBA32F or RGBA8 sRGB;
// 4 decodePackGeometry (pack.bin); 5 readPackManifest (manifest.json and its JSON reader, with every range of
// gusuku/formats/bakeset_ranges.h: the seeds seed_5_* are a real pack's manifest with numbers varied); 6 decodeKtx2
// expecting ASTC 4x4 HDR (the lightmaps); 7 decodeKtx2MipChain expecting ASTC 6x6 sRGB (the textures' mip chains);
// 8 decodeKtx2 expecting RGBA32F, then its texels against the ground geometry's or the irradiance's rows
// (findBakeSetTexelProblem, as loadRuntimePack checks them). Bad input must end in gusuku::InputError or a texel
// problem; any other exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/formats/pack_geometry.h"
#include "pack_manifest.h"

namespace {

// A float image's texels against the rows loadRuntimePack holds that image to; the problem, when one is found,
// must name a texel and the row.
void checkTexels(const uint8_t* bytes, size_t length) {
    const gusuku::Ktx2Image image =
        gusuku::decodeKtx2(bytes, length, "ground_geometry.ktx2", gusuku::Ktx2Format::kR32g32b32a32Sfloat);
    gusuku::BakeSetImage texels{int(image.width), int(image.height), std::vector<float>(image.texels.size() / 4)};
    std::memcpy(texels.rgba.data(), image.texels.data(), image.texels.size());
    const bool geometry = image.width % 2 == 0;  // either set of rows, chosen by the image itself
    const std::optional<gusuku::BakeSetTexelProblem> problem =
        geometry ? gusuku::findBakeSetTexelProblem(texels, {gusuku::kBakeSetGroundNormal, gusuku::kBakeSetGroundHeightM})
                 : gusuku::findBakeSetTexelProblem(texels, {gusuku::kBakeSetTexelIrradiance, gusuku::kBakeSetTexelCoverage});
    if (problem && (problem->field.rfind("texel (", 0) != 0 || problem->problem.find(" (") == std::string::npos))
        __builtin_trap();  // a problem that names no texel or no row
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const int reader = data[0] % 9;  // seeds 0-7 keep their reader
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
        else if (reader == 8)
            checkTexels(bytes, length);
        else if (reader == 4)
            gusuku::decodePackGeometry(bytes, length, "pack.bin");
        else
            gusuku::pack_detail::readPackManifest(std::string(reinterpret_cast<const char*>(bytes), length), "manifest.json");
    } catch (const gusuku::InputError&) {
    }
    return 0;
}

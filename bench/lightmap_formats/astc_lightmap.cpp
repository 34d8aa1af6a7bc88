// ASTC 4x4 HDR round trip of a lightmap (astc_lightmap.h), through astcenc's C++ API.

#include "astc_lightmap.h"

#include <stdexcept>
#include <string>
#include <vector>

#ifdef GUSUKU_HAVE_ASTCENC
#include <astcenc.h>
#endif

namespace gusuku::bench {

size_t astcBytes(int width, int height) { return size_t((width + 3) / 4) * size_t((height + 3) / 4) * 16; }

#ifdef GUSUKU_HAVE_ASTCENC

bool astcAvailable() { return true; }

BakeSetImage astcRoundTrip(const BakeSetImage& lightmap, float quality) {
    auto check = [](astcenc_error error, const char* step) {
        if (error != ASTCENC_SUCCESS) throw std::runtime_error(std::string("astcenc ") + step + ": " + astcenc_get_error_string(error));
    };
    astcenc_config config;
    check(astcenc_config_init(ASTCENC_PRF_HDR_RGB_LDR_A, 4, 4, 1, quality, 0, &config), "config");
    astcenc_context* context = nullptr;
    check(astcenc_context_alloc(&config, 1, &context), "context");
    std::vector<float> texels = lightmap.rgba;
    for (size_t texel = 0; texel < texels.size() / 4; ++texel) texels[texel * 4 + 3] = 1.0f;  // RGB only
    void* slices[1] = {texels.data()};
    astcenc_image image{unsigned(lightmap.width), unsigned(lightmap.height), 1, ASTCENC_TYPE_F32, slices};
    const astcenc_swizzle identity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    std::vector<uint8_t> blocks(astcBytes(lightmap.width, lightmap.height));
    const astcenc_error compressed = astcenc_compress_image(context, &image, &identity, blocks.data(), blocks.size(), 0);
    std::vector<float> decoded(texels.size());
    void* decoded_slices[1] = {decoded.data()};
    astcenc_image out{unsigned(lightmap.width), unsigned(lightmap.height), 1, ASTCENC_TYPE_F32, decoded_slices};
    const astcenc_error decompressed =
        compressed == ASTCENC_SUCCESS
            ? astcenc_decompress_image(context, blocks.data(), blocks.size(), &out, &identity, 0)
            : compressed;
    astcenc_context_free(context);
    check(decompressed, "compress or decompress");
    BakeSetImage result = lightmap;
    for (size_t index = 0; index < decoded.size(); ++index)
        if (index % 4 != 3) result.rgba[index] = decoded[index];
    return result;
}

#else

bool astcAvailable() { return false; }

BakeSetImage astcRoundTrip(const BakeSetImage&, float) {
    throw std::runtime_error("this build has no astcenc (install libastcenc-dev and configure again)");
}

#endif

}  // namespace gusuku::bench

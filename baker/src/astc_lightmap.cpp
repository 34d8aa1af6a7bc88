// ASTC 4x4 HDR lightmaps through astcenc's C API (gusuku_bake/astc_lightmap.h).

#include "gusuku_bake/astc_lightmap.h"

#include <astcenc.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

namespace gusuku::bake {
namespace {

constexpr float kLargestAstcHdrValue = 65504.0f;  // HDR endpoints are half floats
const astcenc_swizzle kIdentity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};

void check(astcenc_error error, const char* step) {
    if (error != ASTCENC_SUCCESS)
        throw std::runtime_error(std::string("astcenc ") + step + ": " + astcenc_get_error_string(error));
}

struct ContextFree {
    void operator()(astcenc_context* context) const { astcenc_context_free(context); }
};
using Context = std::unique_ptr<astcenc_context, ContextFree>;

// A context for 4x4 blocks, profile HDR RGB with LDR alpha (the alpha is a constant 1), for `threads` threads.
Context makeContext(float quality, unsigned threads, unsigned flags) {
    astcenc_config config;
    check(astcenc_config_init(ASTCENC_PRF_HDR_RGB_LDR_A, 4, 4, 1, quality, flags, &config), "config");
    astcenc_context* context = nullptr;
    check(astcenc_context_alloc(&config, threads, &context), "context");
    return Context(context);
}

}  // namespace

size_t astcLightmapBytes(int width, int height) { return size_t((width + 3) / 4) * size_t((height + 3) / 4) * 16; }

std::vector<uint8_t> encodeAstcLightmap(const BakeSetImage& lightmap, float inverse_scale, float quality,
                                        unsigned threads) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<float> texels(lightmap.rgba.size());
    for (size_t index = 0; index < texels.size(); ++index)
        texels[index] = index % 4 == 3 ? 1.0f : std::min(lightmap.rgba[index] * inverse_scale, kLargestAstcHdrValue);
    void* slices[1] = {texels.data()};
    astcenc_image image{unsigned(lightmap.width), unsigned(lightmap.height), 1, ASTCENC_TYPE_F32, slices};
    std::vector<uint8_t> blocks(astcLightmapBytes(lightmap.width, lightmap.height));
    const Context context = makeContext(quality, threads, 0);
    // astcenc splits one image's blocks among the threads that call it with their own thread index.
    std::vector<astcenc_error> errors(threads, ASTCENC_SUCCESS);
    std::vector<std::thread> workers;
    for (unsigned thread = 1; thread < threads; ++thread)
        workers.emplace_back([&, thread] {
            errors[thread] = astcenc_compress_image(context.get(), &image, &kIdentity, blocks.data(), blocks.size(), thread);
        });
    errors[0] = astcenc_compress_image(context.get(), &image, &kIdentity, blocks.data(), blocks.size(), 0);
    for (std::thread& worker : workers) worker.join();
    for (astcenc_error error : errors) check(error, "compress");
    return blocks;
}

BakeSetImage decodeAstcLightmap(const std::vector<uint8_t>& blocks, int width, int height) {
    if (width <= 0 || height <= 0 || blocks.size() != astcLightmapBytes(width, height))
        throw std::runtime_error("decodeAstcLightmap: " + std::to_string(blocks.size()) + " bytes are not the 4 x 4 "
                                 "blocks of " + std::to_string(width) + " x " + std::to_string(height) + " texels");
    BakeSetImage out{width, height, std::vector<float>(size_t(width) * height * 4)};
    void* slices[1] = {out.rgba.data()};
    astcenc_image image{unsigned(width), unsigned(height), 1, ASTCENC_TYPE_F32, slices};
    const Context context = makeContext(kAstcBakeQuality, 1, ASTCENC_FLG_DECOMPRESS_ONLY);
    check(astcenc_decompress_image(context.get(), blocks.data(), blocks.size(), &image, &kIdentity, 0), "decompress");
    return out;
}

}  // namespace gusuku::bake

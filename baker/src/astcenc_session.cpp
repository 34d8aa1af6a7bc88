// astcenc's C API as the baker's ASTC encoders use it (astcenc_session.h).

#include "astcenc_session.h"

#include <stdexcept>
#include <string>
#include <thread>

namespace gusuku::bake {

void checkAstcenc(astcenc_error error, const char* step) {
    if (error != ASTCENC_SUCCESS)
        throw std::runtime_error(std::string("astcenc ") + step + ": " + astcenc_get_error_string(error));
}

AstcencContext makeAstcencContext(astcenc_profile profile, unsigned block_side, float quality, unsigned threads,
                                  unsigned flags, std::optional<float> alpha_weight) {
    astcenc_config config;
    checkAstcenc(astcenc_config_init(profile, block_side, block_side, 1, quality, flags, &config), "config");
    if (alpha_weight) config.cw_a_weight = *alpha_weight;
    astcenc_context* context = nullptr;
    checkAstcenc(astcenc_context_alloc(&config, threads, &context), "context");
    return AstcencContext(context);
}

void compressAstcImage(astcenc_context* context, astcenc_image& image, std::vector<uint8_t>& blocks,
                       unsigned threads) {
    std::vector<astcenc_error> errors(threads, ASTCENC_SUCCESS);
    std::vector<std::thread> workers;
    for (unsigned thread = 1; thread < threads; ++thread)
        workers.emplace_back([&, thread] {
            errors[thread] =
                astcenc_compress_image(context, &image, &kAstcIdentitySwizzle, blocks.data(), blocks.size(), thread);
        });
    errors[0] = astcenc_compress_image(context, &image, &kAstcIdentitySwizzle, blocks.data(), blocks.size(), 0);
    for (std::thread& worker : workers) worker.join();
    for (astcenc_error error : errors) checkAstcenc(error, "compress");
}

void decompressAstcImage(astcenc_context* context, const std::vector<uint8_t>& blocks, astcenc_image& image) {
    checkAstcenc(astcenc_decompress_image(context, blocks.data(), blocks.size(), &image, &kAstcIdentitySwizzle, 0),
                 "decompress");
}

}  // namespace gusuku::bake

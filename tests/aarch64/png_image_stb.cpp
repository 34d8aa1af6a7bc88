// readImage and writePngRgba8 (gusuku/assets/image.h) for the AArch64 test programs, through stb_image: the
// runtime-only cross build has no OpenImageIO for arm64. Only what test_runtime_golden.cpp asks of them: 8-bit
// PNG goldens read back as values (ImageEncoding::Linear: code / 255) and RGBA8 frames written as they are.

#include <stdexcept>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "gusuku/assets/image.h"

namespace gusuku {

ImageRGBA readImage(const std::string& path, ImageEncoding encoding, int /*max_side*/) {
    int width = 0, height = 0, channels = 0;
    stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (pixels == nullptr) throw std::runtime_error(path + ": not read as an 8-bit PNG: " + stbi_failure_reason());
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.resize(size_t(width) * size_t(height) * 4);
    for (size_t index = 0; index < image.texels.size(); ++index) {
        const float value = float(pixels[index]) / 255.0f;
        // 8-bit colour is sRGB-encoded unless the caller says the values are linear; alpha is always linear.
        image.texels[index] = encoding == ImageEncoding::Linear || index % 4 == 3 ? value : srgbDecode(value);
    }
    stbi_image_free(pixels);
    return image;
}

void writePngRgba8(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba8) {
    if (rgba8.size() != size_t(width) * size_t(height) * 4)
        throw std::invalid_argument(path + ": " + std::to_string(rgba8.size()) + " bytes are not " +
                                    std::to_string(width) + " x " + std::to_string(height) + " x 4");
    if (stbi_write_png(path.c_str(), width, height, 4, rgba8.data(), width * 4) == 0)
        throw std::runtime_error(path + ": could not be written");
}

}  // namespace gusuku

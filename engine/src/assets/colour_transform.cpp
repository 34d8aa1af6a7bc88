// The sRGB transfer curve for whole images, as an OpenColorIO CPU processor (docs/design.md 2 routes colour
// conversions through OpenColorIO). The scalar IEC 61966-2-1 formulas are srgbEncode / srgbDecode in
// gusuku/maths/colour.h (engine/src/maths/colour.cpp); a test pins the two to each other.
#include <array>
#include <cstdint>

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/imageio.h>

#include "gusuku/maths/colour.h"
#include "gusuku/assets/image.h"

namespace OCIO = OCIO_NAMESPACE;

namespace gusuku {

namespace {

// ExponentWithLinearTransform with gamma 2.4 and offset 0.055 is the sRGB curve: its forward direction maps
// encoded values to linear ((x + offset) / (1 + offset))^gamma with the linear toe derived from continuity.
// Alpha gets gamma 1, offset 0: an identity.
OCIO::ConstCPUProcessorRcPtr makeSrgbProcessor(OCIO::TransformDirection direction) {
    OCIO::ExponentWithLinearTransformRcPtr curve = OCIO::ExponentWithLinearTransform::Create();
    const double gamma[4] = {2.4, 2.4, 2.4, 1.0};
    const double offset[4] = {0.055, 0.055, 0.055, 0.0};
    curve->setGamma(gamma);
    curve->setOffset(offset);
    curve->setDirection(direction);
    OCIO::ConstConfigRcPtr config = OCIO::Config::CreateRaw();
    OCIO::ConstProcessorRcPtr processor = config->getProcessor(curve);
    // Lossless: no fast-pow approximation, so the image path matches the scalar formulas.
    return processor->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                               OCIO::OPTIMIZATION_LOSSLESS);
}

const OCIO::CPUProcessor& srgbDecoder() {
    static const OCIO::ConstCPUProcessorRcPtr processor = makeSrgbProcessor(OCIO::TRANSFORM_DIR_FORWARD);
    return *processor;
}

const OCIO::CPUProcessor& srgbEncoder() {
    static const OCIO::ConstCPUProcessorRcPtr processor = makeSrgbProcessor(OCIO::TRANSFORM_DIR_INVERSE);
    return *processor;
}

void applyToImage(const OCIO::CPUProcessor& processor, ImageRGBA& image) {
    if (image.width <= 0 || image.height <= 0) return;
    OCIO::PackedImageDesc description(image.texels.data(), image.width, image.height, 4);
    processor.apply(description);
}

}  // namespace

void srgbDecodeImage(ImageRGBA& image) { applyToImage(srgbDecoder(), image); }

void srgbEncodeImage(ImageRGBA& image) { applyToImage(srgbEncoder(), image); }

void srgbDecodeBytes(const uint8_t* encoded_rgba, size_t texel_count, float* linear_rgba) {
    // The 256 byte values decoded once through the processor above: OpenImageIO's byte-to-float conversion, then
    // the curve (OpenColorIO's own 8-bit input path evaluates the pow per texel, measured: no faster). Alpha is
    // linear: the byte's float value.
    struct ByteTable {
        std::array<float, 256> linear{};
        std::array<float, 256> value{};
    };
    static const ByteTable table = [] {
        ByteTable made;
        std::array<uint8_t, 256> bytes{};
        for (int k = 0; k < 256; ++k) bytes[size_t(k)] = uint8_t(k);
        OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, bytes.data(), OIIO::TypeDesc::FLOAT, made.value.data(),
                                   256);
        ImageRGBA row;
        row.width = 256;
        row.height = 1;
        row.texels.resize(256 * 4);
        for (size_t k = 0; k < 256; ++k) row.texels[k * 4] = row.texels[k * 4 + 1] = row.texels[k * 4 + 2] = made.value[k];
        applyToImage(srgbDecoder(), row);
        for (size_t k = 0; k < 256; ++k) made.linear[k] = row.texels[k * 4];
        return made;
    }();
    for (size_t i = 0; i < texel_count; ++i, encoded_rgba += 4, linear_rgba += 4) {
        linear_rgba[0] = table.linear[encoded_rgba[0]];
        linear_rgba[1] = table.linear[encoded_rgba[1]];
        linear_rgba[2] = table.linear[encoded_rgba[2]];
        linear_rgba[3] = table.value[encoded_rgba[3]];
    }
}

}  // namespace gusuku

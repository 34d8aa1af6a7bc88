// The sRGB transfer curve, twice: once as scalar IEC 61966-2-1 formulas (for single values and tests), once as
// an OpenColorIO CPU processor (for whole images; DESIGN.md 2 routes colour conversions through OpenColorIO).
// A test pins the two to each other.
#include <cmath>

#include <OpenColorIO/OpenColorIO.h>

#include "gusuku/image.h"

namespace OCIO = OCIO_NAMESPACE;

namespace gusuku {

float srgbEncode(float linear) {
    if (linear <= 0.0031308f) return 12.92f * linear;
    return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

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

}  // namespace gusuku

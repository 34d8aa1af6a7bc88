// The sun horizons' file (gusuku/formats/sun_horizon_ktx2.h).

#include "gusuku/formats/sun_horizon_ktx2.h"

#include <stdexcept>

#include "gusuku/formats/format_table.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"

namespace gusuku {

std::vector<uint8_t> encodeSunHorizonKtx2(const BakeSetSunHorizon& horizon) {
    if (horizon.width < kMinSunHorizonResolution || horizon.width > kMaxSunHorizonResolution ||
        horizon.height != horizon.width ||
        horizon.rgba8.size() != size_t(kSunHorizonLayers) * size_t(horizon.width) * size_t(horizon.height) * 4)
        throw std::invalid_argument("encodeSunHorizonKtx2: not a square horizon image of two RGBA8 layers");
    Ktx2Image image;
    image.format = Ktx2Format(formats::kVkR8g8b8a8Unorm);
    image.width = uint32_t(horizon.width);
    image.height = uint32_t(kSunHorizonLayers * horizon.height);
    image.texels = horizon.rgba8;
    return encodeKtx2(image);
}

BakeSetSunHorizon decodeSunHorizonKtx2(const uint8_t* bytes, size_t size, const std::string& file) {
    Ktx2Image image = decodeKtx2(bytes, size, file, Ktx2Format(formats::kVkR8g8b8a8Unorm));
    if (image.height != uint32_t(kSunHorizonLayers) * image.width)
        throw InputError(file, "pixelHeight",
                         std::to_string(image.height) + " is not twice the width " + std::to_string(image.width) +
                             " (two layers one above the other)");
    if (image.width < uint32_t(kMinSunHorizonResolution) || image.width > uint32_t(kMaxSunHorizonResolution))
        throw InputError(file, "pixelWidth",
                         std::to_string(image.width) + " is outside [" + std::to_string(kMinSunHorizonResolution) +
                             ", " + std::to_string(kMaxSunHorizonResolution) + "]");
    BakeSetSunHorizon horizon;
    horizon.width = horizon.height = int(image.width);
    horizon.rgba8 = std::move(image.texels);
    return horizon;
}

}  // namespace gusuku

// A bake set lightmap in 8 linear bits with one scale (gusuku_bake/lightmap_export.h, quantiseLightmapLinear8): the
// encoding MOZ_lightmap's readers decode, byte / 255 * intensity, with no sRGB curve.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gusuku_bake/lightmap_export.h"

namespace gusuku::bake {

LinearLightmap8 quantiseLightmapLinear8(const BakeSetImage& lightmap) {
    const size_t texels = size_t(std::max(lightmap.width, 0)) * size_t(std::max(lightmap.height, 0));
    if (texels == 0 || lightmap.rgba.size() != texels * 4)
        throw std::invalid_argument("lightmap of " + std::to_string(lightmap.width) + " x " +
                                    std::to_string(lightmap.height) + " texels holds " +
                                    std::to_string(lightmap.rgba.size()) + " floats, not 4 a texel");
    LinearLightmap8 encoded;
    encoded.width = lightmap.width;
    encoded.height = lightmap.height;
    // The largest value sets the scale: nothing clips, so the error bound holds on every texel (a percentile
    // would spend the 8 bits better on dark texels but clip the brightest, and a viewer cannot tell which).
    double brightest = 0.0;
    for (size_t t = 0; t < texels; ++t)
        for (int c = 0; c < 3; ++c) brightest = std::max(brightest, double(lightmap.rgba[4 * t + c]));
    encoded.intensity = brightest > 0.0 ? brightest : 1.0;
    encoded.rgb8.resize(texels * 3);
    for (size_t t = 0; t < texels; ++t)
        for (int c = 0; c < 3; ++c) {
            const double step = double(std::max(lightmap.rgba[4 * t + c], 0.0f)) / encoded.intensity * 255.0;
            encoded.rgb8[3 * t + c] = uint8_t(std::clamp(std::lround(step), 0L, 255L));
        }
    return encoded;
}

}  // namespace gusuku::bake

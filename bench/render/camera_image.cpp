#include "camera_image.h"

#include <algorithm>

#include "gusuku/assets/image.h"
#include "gusuku/maths/colour.h"

namespace gusuku::render_cli {

CameraImage readCameraImage(const std::string& path) {
    const ImageRGBA image = readImage(path, ImageEncoding::Auto);  // by format: integer sRGB, float linear
    CameraImage camera;
    camera.width = uint32_t(image.width);
    camera.height = uint32_t(image.height);
    camera.srgb_rgba8.resize(size_t(camera.width) * camera.height * 4);
    for (size_t index = 0; index < camera.srgb_rgba8.size(); ++index) {
        const float value = index % 4 == 3 ? image.texels[index] : srgbEncode(image.texels[index]);
        camera.srgb_rgba8[index] = uint8_t(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    return camera;
}

}  // namespace gusuku::render_cli

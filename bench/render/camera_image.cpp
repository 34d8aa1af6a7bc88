#include "camera_image.h"

#include <algorithm>

#include "gusuku/assets/image.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::render_cli {

static_assert(kMinCameraSide == RuntimeOptions{}.statistics_stride,
              "gusuku-render keeps the runtime's default statistics_stride: the smallest camera side follows it");

CameraImage readCameraImage(const std::string& path) {
    // A camera frame is the runtime's frame: never downsampled to fit (readImage would), so one larger than the
    // runtime takes is refused from its header, before it is decoded.
    const ImageSize size = readImageSize(path);
    if (size.width > kMaxCameraSide || size.height > kMaxCameraSide)
        throw InputError(path, "image size",
                         std::to_string(size.width) + " x " + std::to_string(size.height) +
                             " pixels: a camera frame is at most " + std::to_string(kMaxCameraSide) +
                             " on a side (the runtime's frame limit)");
    // Said of the image here: the runtime's own refusal would name its statistics_stride, an option the user of
    // gusuku-render never sets.
    if (size.width < kMinCameraSide || size.height < kMinCameraSide)
        throw InputError(path, "image size",
                         std::to_string(size.width) + " x " + std::to_string(size.height) +
                             " pixels: a camera frame is at least " + std::to_string(kMinCameraSide) +
                             " on a side (the runtime's colour statistics sample every " +
                             std::to_string(kMinCameraSide) + "th pixel each way)");
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

// gusuku-render's camera frame from a file (bench/render/camera_image.h): whatever the file's bit depth, the
// runtime gets the sRGB bytes of the same picture. Expected bytes come from the sRGB curve (IEC 61966-2-1).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "camera_image.h"
#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"

namespace {

// Writes an image of `channels` channels with the given values per texel (the same for every texel); 8 x 8 is the
// smallest camera frame (kMinCameraSide).
void writeImage(const std::string& path, int channels, OIIO::TypeDesc format, const std::vector<float>& texel,
                int width = 8, int height = 8) {
    OIIO::ImageSpec spec(width, height, channels, format);
    std::vector<float> values;
    for (int i = 0; i < width * height; ++i) values.insert(values.end(), texel.begin(), texel.end());
    auto output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output && output->open(path, spec)) << OIIO::geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, values.data()) && output->close());
}

uint8_t srgbByteOfLinear(float linear) { return uint8_t(std::lround(gusuku::srgbEncode(linear) * 255.0f)); }

TEST(RenderCameraImage, EveryBitDepthGivesTheSameSrgbBytes) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_camera_image");
    // The picture: linear (0.2140, 0.0500, 0.8000), which sRGB-encodes to about (128, 63, 231).
    const std::vector<float> linear = {0.2140f, 0.05f, 0.8f};
    std::vector<float> encoded;
    for (float value : linear) encoded.push_back(std::round(gusuku::srgbEncode(value) * 255.0f) / 255.0f);
    const uint8_t expected[3] = {srgbByteOfLinear(linear[0]), srgbByteOfLinear(linear[1]), srgbByteOfLinear(linear[2])};

    writeImage(dir + "/camera8.png", 3, OIIO::TypeDesc::UINT8, encoded);
    writeImage(dir + "/camera16.png", 3, OIIO::TypeDesc::UINT16, encoded);
    writeImage(dir + "/camera_float.exr", 3, OIIO::TypeDesc::FLOAT, linear);  // linear data, as EXR holds
    writeImage(dir + "/camera_half.exr", 4, OIIO::TypeDesc::HALF, {linear[0], linear[1], linear[2], 1.0f});
    for (const char* name : {"camera8.png", "camera16.png", "camera_float.exr", "camera_half.exr"}) {
        SCOPED_TRACE(name);
        const gusuku::render_cli::CameraImage camera = gusuku::render_cli::readCameraImage(dir + "/" + name);
        ASSERT_EQ(camera.width, 8u);
        ASSERT_EQ(camera.height, 8u);
        ASSERT_EQ(camera.srgb_rgba8.size(), 8u * 8u * 4u);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(int(camera.srgb_rgba8[size_t(c)]), int(expected[c]), 1) << c;
        EXPECT_EQ(camera.srgb_rgba8[3], 255);  // no alpha in the file, or alpha 1: opaque
    }
}

TEST(RenderCameraImage, GreyExpandsToRgb) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_camera_image");
    writeImage(dir + "/grey.exr", 1, OIIO::TypeDesc::FLOAT, {0.2140f});
    const gusuku::render_cli::CameraImage camera = gusuku::render_cli::readCameraImage(dir + "/grey.exr");
    for (int c = 0; c < 3; ++c) EXPECT_EQ(camera.srgb_rgba8[size_t(c)], srgbByteOfLinear(0.2140f)) << c;
}

TEST(RenderCameraImage, AFrameLargerThanTheRuntimeTakesIsRefusedFromItsHeader) {
    // A 16384 x 16 PNG: refused by its declared size, not downsampled, and not after a GPU buffer fails.
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_camera_image");
    OIIO::ImageSpec spec(16384, 16, 3, OIIO::TypeDesc::UINT8);
    const std::vector<unsigned char> black(size_t(16384) * 16 * 3, 0);
    auto output = OIIO::ImageOutput::create(dir + "/wide.png");
    ASSERT_TRUE(output && output->open(dir + "/wide.png", spec));
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, black.data()) && output->close());
    try {
        gusuku::render_cli::readCameraImage(dir + "/wide.png");
        ADD_FAILURE() << "a 16384-pixel-wide camera frame was accepted";
    } catch (const gusuku::InputError& error) {
        EXPECT_EQ(std::string(error.what()), dir + "/wide.png: image size: 16384 x 16 pixels: a camera frame is at "
                                                   "most 8192 on a side (the runtime's frame limit)");
    }
}

TEST(RenderCameraImage, AFrameSmallerThanTheStatisticsSampleIsRefusedNamingItsSize) {
    // 1 x 1 and 7 x 8: refused by the image's size, not by the runtime's statistics_stride, an option gusuku-render
    // never asks its user for.
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_camera_image");
    for (const auto& [width, height] : {std::pair{1, 1}, std::pair{7, 8}}) {
        const std::string path = dir + "/small" + std::to_string(width) + ".png";
        writeImage(path, 3, OIIO::TypeDesc::UINT8, {0.5f, 0.5f, 0.5f}, width, height);
        try {
            gusuku::render_cli::readCameraImage(path);
            ADD_FAILURE() << "a " << width << " x " << height << " camera frame was accepted";
        } catch (const gusuku::InputError& error) {
            EXPECT_EQ(std::string(error.what()),
                      path + ": image size: " + std::to_string(width) + " x " + std::to_string(height) +
                          " pixels: a camera frame is at least 8 on a side (the runtime's colour statistics sample "
                          "every 8th pixel each way)");
        }
    }
}

}  // namespace

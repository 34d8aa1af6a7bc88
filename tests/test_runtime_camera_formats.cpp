// The platform's camera as it comes (runtime.h, CameraFormat): each format and source gives the composite the
// RGBA8 host path gives for the same pixels, under validation.
//   - BGRA8 host pixels and RGBA8 pixels with a row pitch: byte for byte.
//   - NV12 / NV21, BT.601 / BT.709, narrow / full: a Y'CbCr frame made from an RGB frame on the CPU; the RGB
//     path is fed that frame decoded by an independent CPU implementation of the ITU formulas, rounded to
//     bytes; the two composites agree within one code value everywhere (the building and the ground ratio
//     included), and the decoded frame is within 3 codes of the RGB frame it was made from.
//   - The app's VkImage, R8G8B8A8 _UNORM and _SRGB, B8G8R8A8, in every documented layout, sampled in place.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"
#include "test_msaa.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 160, kHeight = 120;

RuntimeOptions optionsFor(CameraFormat format, YcbcrModel model = YcbcrModel::kBt601,
                          YcbcrRange range = YcbcrRange::kNarrow) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 512;
    options.camera_format = format;
    options.camera_ycbcr_model = model;
    options.camera_ycbcr_range = range;
    options.msaa_samples = testing::testMsaaSamples();
    return options;
}

FrameInput frameLookingAtTheBuilding() {
    FrameInput frame;
    const double focal = 120.0;
    frame.intrinsics = {focal, focal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = CameraPose::lookingAt({3, -12, 3}, {0, 0, 1});
    frame.utc_unix_seconds = syntheticLocalTime(15, 0);
    frame.weather = Weather::sunny();
    frame.exposure = 0.1f;
    return frame;
}

// Colours that vary per 2 x 2 block (so 4:2:0 chroma loses nothing) with luma noise per pixel, alpha 255.
std::vector<uint8_t> blockyRgba(uint32_t seed) {
    std::mt19937 random(seed);
    std::vector<uint8_t> image(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; y += 2)
        for (uint32_t x = 0; x < kWidth; x += 2) {
            const int base[3] = {int(30 + random() % 190), int(30 + random() % 190), int(30 + random() % 190)};
            for (uint32_t dy = 0; dy < 2; ++dy)
                for (uint32_t dx = 0; dx < 2; ++dx) {
                    const int noise = int(random() % 9) - 4;
                    uint8_t* pixel = &image[((size_t(y + dy) * kWidth) + x + dx) * 4];
                    for (int channel = 0; channel < 3; ++channel)
                        pixel[channel] = uint8_t(std::clamp(base[channel] + noise, 0, 255));
                    pixel[3] = 255;
                }
        }
    return image;
}

struct YcbcrCoefficients {
    double kr, kb;
};
YcbcrCoefficients coefficientsOf(YcbcrModel model) {
    return model == YcbcrModel::kBt709 ? YcbcrCoefficients{0.2126, 0.0722} : YcbcrCoefficients{0.299, 0.114};
}

struct YuvPlanes {
    std::vector<uint8_t> luma, chroma;  // chroma: width/2 x height/2 pairs, Cb Cr (NV12) or Cr Cb (NV21)
};

// R'G'B' bytes to Y'CbCr bytes (ITU-R BT.601 / BT.709), chroma the mean of each 2 x 2 block.
YuvPlanes encodeYuv(const std::vector<uint8_t>& rgba, CameraFormat format, YcbcrModel model, YcbcrRange range) {
    const YcbcrCoefficients k = coefficientsOf(model);
    const bool full = range == YcbcrRange::kFull;
    YuvPlanes planes;
    planes.luma.resize(size_t(kWidth) * kHeight);
    planes.chroma.resize(size_t(kWidth / 2) * (kHeight / 2) * 2);
    auto toByte = [](double value) { return uint8_t(std::clamp(std::lround(value), 0L, 255L)); };
    std::vector<double> cb_sum(planes.chroma.size() / 2, 0.0), cr_sum(cb_sum.size(), 0.0);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const uint8_t* pixel = &rgba[(size_t(y) * kWidth + x) * 4];
            const double r = pixel[0] / 255.0, g = pixel[1] / 255.0, b = pixel[2] / 255.0;
            const double luma = k.kr * r + (1.0 - k.kr - k.kb) * g + k.kb * b;
            const double cb = (b - luma) / (2.0 * (1.0 - k.kb)), cr = (r - luma) / (2.0 * (1.0 - k.kr));
            planes.luma[size_t(y) * kWidth + x] = toByte(full ? luma * 255.0 : 16.0 + 219.0 * luma);
            const size_t block = size_t(y / 2) * (kWidth / 2) + x / 2;
            cb_sum[block] += cb / 4.0;
            cr_sum[block] += cr / 4.0;
        }
    const bool swapped = format == CameraFormat::kNv21;
    for (size_t block = 0; block < cb_sum.size(); ++block) {
        const uint8_t cb = toByte(full ? 128.0 + 255.0 * cb_sum[block] : 128.0 + 224.0 * cb_sum[block]);
        const uint8_t cr = toByte(full ? 128.0 + 255.0 * cr_sum[block] : 128.0 + 224.0 * cr_sum[block]);
        planes.chroma[block * 2] = swapped ? cr : cb;
        planes.chroma[block * 2 + 1] = swapped ? cb : cr;
    }
    return planes;
}

// Y'CbCr bytes back to R'G'B' bytes, the chroma of pixel (x, y) the block (x / 2, y / 2)'s.
std::vector<uint8_t> decodeYuv(const YuvPlanes& planes, CameraFormat format, YcbcrModel model, YcbcrRange range) {
    const YcbcrCoefficients k = coefficientsOf(model);
    const bool full = range == YcbcrRange::kFull, swapped = format == CameraFormat::kNv21;
    std::vector<uint8_t> rgba(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const double luma_code = planes.luma[size_t(y) * kWidth + x];
            const size_t block = size_t(y / 2) * (kWidth / 2) + x / 2;
            const double first = planes.chroma[block * 2], second = planes.chroma[block * 2 + 1];
            const double cb_code = swapped ? second : first, cr_code = swapped ? first : second;
            const double luma = full ? luma_code / 255.0 : (luma_code - 16.0) / 219.0;
            const double cb = (cb_code - 128.0) / (full ? 255.0 : 224.0), cr = (cr_code - 128.0) / (full ? 255.0 : 224.0);
            const double r = luma + 2.0 * (1.0 - k.kr) * cr, b = luma + 2.0 * (1.0 - k.kb) * cb;
            const double g = (luma - k.kr * r - k.kb * b) / (1.0 - k.kr - k.kb);
            uint8_t* pixel = &rgba[(size_t(y) * kWidth + x) * 4];
            const double channels[3] = {r, g, b};
            for (int channel = 0; channel < 3; ++channel)
                pixel[channel] = uint8_t(std::clamp(std::lround(channels[channel] * 255.0), 0L, 255L));
            pixel[3] = 255;
        }
    return rgba;
}

int largestDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    int largest = 0;
    for (size_t index = 0; index < a.size(); ++index) largest = std::max(largest, std::abs(int(a[index]) - int(b[index])));
    return largest;
}

class RuntimeCameraFormats : public testing::GpuTest {
protected:
    std::vector<uint8_t> render(const RuntimeOptions& options, const FrameInput& frame) {
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), options);
        std::vector<uint8_t> composite(size_t(kWidth) * kHeight * 4);
        runtime->renderFrame(frame, composite.data());
        return composite;
    }
    std::vector<uint8_t> renderRgba(const std::vector<uint8_t>& rgba) {
        FrameInput frame = frameLookingAtTheBuilding();
        frame.camera_rgba8 = rgba.data();
        return render(optionsFor(CameraFormat::kRgba8), frame);
    }
};

TEST_F(RuntimeCameraFormats, BgraPixelsGiveTheRgbaComposite) {
    const std::vector<uint8_t> rgba = blockyRgba(3);
    std::vector<uint8_t> bgra = rgba;
    for (size_t index = 0; index < bgra.size(); index += 4) std::swap(bgra[index], bgra[index + 2]);
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_rgba8 = bgra.data();
    const std::vector<uint8_t> from_rgba = renderRgba(rgba);
    EXPECT_EQ(render(optionsFor(CameraFormat::kBgra8), frame), from_rgba);
    EXPECT_NE(from_rgba, rgba);  // the building is in the frame
}

TEST_F(RuntimeCameraFormats, RowPitchIsHonoured) {
    const std::vector<uint8_t> rgba = blockyRgba(4);
    const uint32_t pitch = kWidth * 4 + 64;
    std::vector<uint8_t> padded(size_t(pitch) * kHeight, 0xAB);
    for (uint32_t row = 0; row < kHeight; ++row)
        std::copy_n(&rgba[size_t(row) * kWidth * 4], kWidth * 4, &padded[size_t(row) * pitch]);
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_rgba8 = padded.data();
    frame.camera_row_bytes = pitch;
    EXPECT_EQ(render(optionsFor(CameraFormat::kRgba8), frame), renderRgba(rgba));
}

struct YuvCase {
    const char* name;
    CameraFormat format;
    YcbcrModel model;
    YcbcrRange range;
};

class RuntimeYuvCamera : public RuntimeCameraFormats, public ::testing::WithParamInterface<YuvCase> {};

TEST_P(RuntimeYuvCamera, MatchesTheRgbPathWithinOneCode) {
    const YuvCase& yuv = GetParam();
    const std::vector<uint8_t> original = blockyRgba(7);
    const YuvPlanes planes = encodeYuv(original, yuv.format, yuv.model, yuv.range);
    const std::vector<uint8_t> decoded = decodeYuv(planes, yuv.format, yuv.model, yuv.range);
    EXPECT_LE(largestDifference(decoded, original), 3) << "the CPU encode and decode should nearly round-trip";

    // The chroma plane with a row pitch, as Android's YUV_420_888 planes often have.
    const uint32_t chroma_pitch = kWidth + 32;
    std::vector<uint8_t> chroma_rows(size_t(chroma_pitch) * (kHeight / 2), 0x5A);
    for (uint32_t row = 0; row < kHeight / 2; ++row)
        std::copy_n(&planes.chroma[size_t(row) * kWidth], kWidth, &chroma_rows[size_t(row) * chroma_pitch]);
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_luma = planes.luma.data();
    frame.camera_chroma = chroma_rows.data();
    frame.camera_chroma_row_bytes = chroma_pitch;
    const std::vector<uint8_t> from_yuv = render(optionsFor(yuv.format, yuv.model, yuv.range), frame);
    const std::vector<uint8_t> from_rgb = renderRgba(decoded);
    EXPECT_LE(largestDifference(from_yuv, from_rgb), 1) << yuv.name;
    EXPECT_GT(largestDifference(from_rgb, decoded), 10) << "the building should be drawn";
}

INSTANTIATE_TEST_SUITE_P(
    Formats, RuntimeYuvCamera,
    ::testing::Values(YuvCase{"nv12_bt601_narrow", CameraFormat::kNv12, YcbcrModel::kBt601, YcbcrRange::kNarrow},
                      YuvCase{"nv21_bt601_narrow", CameraFormat::kNv21, YcbcrModel::kBt601, YcbcrRange::kNarrow},
                      YuvCase{"nv12_bt709_narrow", CameraFormat::kNv12, YcbcrModel::kBt709, YcbcrRange::kNarrow},
                      YuvCase{"nv21_bt709_full", CameraFormat::kNv21, YcbcrModel::kBt709, YcbcrRange::kFull},
                      YuvCase{"nv12_bt601_full", CameraFormat::kNv12, YcbcrModel::kBt601, YcbcrRange::kFull}),
    [](const ::testing::TestParamInfo<YuvCase>& info) { return std::string(info.param.name); });

struct ImageCase {
    const char* name;
    CameraFormat camera;
    VkFormat image_format;
    VkImageLayout layout;
};

class RuntimeCameraImage : public RuntimeCameraFormats, public ::testing::WithParamInterface<ImageCase> {};

// The app's image in each documented layout and format is sampled in place and gives the host path's
// composite byte for byte; the image is left in the layout it came in (a second frame reads it again).
TEST_P(RuntimeCameraImage, GivesTheHostPathsComposite) {
    const ImageCase& test_case = GetParam();
    const std::vector<uint8_t> rgba = blockyRgba(9);
    std::vector<uint8_t> texels = rgba;
    if (test_case.camera == CameraFormat::kBgra8)
        for (size_t index = 0; index < texels.size(); index += 4) std::swap(texels[index], texels[index + 2]);
    GpuImageDescription description;
    description.format = test_case.image_format;
    description.width = kWidth;
    description.height = kHeight;
    description.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    GpuImage app_image(context(), description);
    app_image.upload(texels.data(), texels.size(), 0, test_case.layout);

    std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), optionsFor(test_case.camera));
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_image = app_image.handle();
    frame.camera_image_layout = test_case.layout;
    frame.camera_image_format = test_case.image_format;
    std::vector<uint8_t> first(rgba.size()), second(rgba.size());
    runtime->renderFrame(frame, first.data());
    frame.utc_unix_seconds += 1.0;
    runtime->renderFrame(frame, second.data());
    const std::vector<uint8_t> from_host = renderRgba(rgba);
    EXPECT_EQ(first, from_host) << test_case.name;
    EXPECT_LE(largestDifference(second, from_host), 1) << test_case.name;
    runtime->forgetCameraImage(app_image.handle());
}

INSTANTIATE_TEST_SUITE_P(
    Layouts, RuntimeCameraImage,
    ::testing::Values(
        ImageCase{"rgba_unorm_shader_read", CameraFormat::kRgba8, VK_FORMAT_R8G8B8A8_UNORM,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        ImageCase{"rgba_unorm_transfer_src", CameraFormat::kRgba8, VK_FORMAT_R8G8B8A8_UNORM,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
        ImageCase{"rgba_unorm_general", CameraFormat::kRgba8, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_LAYOUT_GENERAL},
        ImageCase{"rgba_srgb_shader_read", CameraFormat::kRgba8, VK_FORMAT_R8G8B8A8_SRGB,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        ImageCase{"bgra_unorm_shader_read", CameraFormat::kBgra8, VK_FORMAT_B8G8R8A8_UNORM,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        ImageCase{"bgra_srgb_transfer_src", CameraFormat::kBgra8, VK_FORMAT_B8G8R8A8_SRGB,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}),
    [](const ::testing::TestParamInfo<ImageCase>& info) { return std::string(info.param.name); });

TEST_F(RuntimeCameraFormats, BadCameraInputsAreRefusedByName) {
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), makeSyntheticBakeSet(), optionsFor(CameraFormat::kNv12));
    const std::vector<uint8_t> rgba = blockyRgba(1);
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_rgba8 = rgba.data();
    auto messageOf = [&](const FrameInput& input) {
        try {
            runtime->renderFrame(input, nullptr);
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
            return std::string(error.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(messageOf(frame).find("camera_rgba8"), std::string::npos) << messageOf(frame);
    frame.camera_rgba8 = nullptr;
    frame.camera_luma = rgba.data();
    EXPECT_NE(messageOf(frame).find("camera_chroma"), std::string::npos) << messageOf(frame);
    frame.camera_chroma = rgba.data();
    frame.camera_luma_row_bytes = kWidth - 1;
    EXPECT_NE(messageOf(frame).find("camera_luma_row_bytes"), std::string::npos) << messageOf(frame);

    RuntimeOptions odd = optionsFor(CameraFormat::kNv21);
    odd.frame_width = kWidth + 1;
    EXPECT_THROW(Runtime::open(context(), makeSyntheticBakeSet(), odd), RuntimeError);
}

}  // namespace
}  // namespace gusuku

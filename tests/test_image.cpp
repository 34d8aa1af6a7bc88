// Image I/O (gusuku/image.h), the sRGB curve, InputError's message and atomic writes.
// Expected values come from the sRGB standard (IEC 61966-2-1) and from the inputs themselves, never from a
// previous run of the code.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "gpu_test_support.h"
#include "gusuku/atomic_file.h"
#include "gusuku/image.h"
#include "gusuku/input_error.h"

namespace {

using gusuku::ImageRGBA;
using gusuku::InputError;
namespace fs = std::filesystem;

ImageRGBA makeImage(int width, int height) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, 0.0f);
    return image;
}

// A smooth, non-symmetric pattern so a transposed or flipped read would not match.
ImageRGBA makeGradient(int width, int height, float scale) {
    ImageRGBA image = makeImage(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* t = image.texel(x, y);
            t[0] = scale * float(x) / float(width - 1);
            t[1] = scale * float(y) / float(height - 1);
            t[2] = scale * float((x * 7 + y * 3) % 11) / 10.0f;
            t[3] = 0.25f + 0.75f * float(x + y) / float(width + height - 2);
        }
    return image;
}

std::string expectInputError(const std::function<void()>& action) {
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no InputError thrown";
    return "";
}

TEST(InputErrorTest, MessageIsFileFieldProblem) {
    EXPECT_STREQ(InputError("site.json", "/site/latitude_deg", "out of range").what(),
                 "site.json: /site/latitude_deg: out of range");
    const InputError whole_file("house.glb", "", "truncated");
    EXPECT_STREQ(whole_file.what(), "house.glb: truncated");
    EXPECT_EQ(whole_file.file(), "house.glb");
    EXPECT_EQ(whole_file.field(), "");
    EXPECT_EQ(whole_file.problem(), "truncated");
}

TEST(AtomicFileTest, WritesThroughTemporaryAndCreatesDirectories) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_atomic");
    const std::string final_path = dir + "/a/b/out.txt";
    std::string seen_temporary;
    gusuku::writeFileAtomically(final_path, [&](const std::string& temporary_path) {
        seen_temporary = temporary_path;
        std::ofstream(temporary_path) << "hello";
        EXPECT_FALSE(fs::exists(final_path)) << "final path must not appear before the rename";
    });
    EXPECT_EQ(fs::path(seen_temporary).parent_path(), fs::path(final_path).parent_path());
    EXPECT_EQ(seen_temporary.rfind(final_path + ".tmp-", 0), 0u) << seen_temporary;
    EXPECT_EQ(gusuku::readWholeFile(final_path), "hello");
    EXPECT_FALSE(fs::exists(seen_temporary));
}

TEST(AtomicFileTest, FailedWriteLeavesOldFileAndNoTemporary) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_atomic");
    const std::string final_path = dir + "/out.bin";
    gusuku::writeBytesAtomically(final_path, "old", 3);
    EXPECT_THROW(gusuku::writeFileAtomically(final_path,
                                             [](const std::string& temporary_path) {
                                                 std::ofstream(temporary_path) << "half";
                                                 throw std::runtime_error("interrupted");
                                             }),
                 std::runtime_error);
    EXPECT_EQ(gusuku::readWholeFile(final_path), "old");
    size_t file_count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++file_count;
    EXPECT_EQ(file_count, 1u) << "the temporary file was left behind";
}

TEST(AtomicFileTest, ReadingMissingFileNamesIt) {
    const std::string message = expectInputError([] { gusuku::readWholeFile("/nonexistent/gusuku.txt"); });
    EXPECT_NE(message.find("/nonexistent/gusuku.txt"), std::string::npos) << message;
}

TEST(SrgbCurveTest, MatchesPublishedValues) {
    // IEC 61966-2-1: linear 0.5 encodes to 0.735357; encoded 0.5 decodes to 0.214041; breakpoints
    // 0.0031308 (linear) <-> 0.04045 (encoded).
    EXPECT_NEAR(gusuku::srgbEncode(0.5f), 0.735357f, 1e-6f);
    EXPECT_NEAR(gusuku::srgbDecode(0.5f), 0.214041f, 1e-6f);
    EXPECT_NEAR(gusuku::srgbEncode(0.0031308f), 0.04045f, 1e-6f);
    EXPECT_NEAR(gusuku::srgbDecode(0.04045f), 0.0031308f, 1e-7f);
    EXPECT_FLOAT_EQ(gusuku::srgbEncode(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(gusuku::srgbEncode(1.0f), 1.0f);
    EXPECT_FLOAT_EQ(gusuku::srgbDecode(1.0f), 1.0f);
    for (int i = 0; i <= 1000; ++i) {
        const float encoded = float(i) / 1000.0f;
        EXPECT_NEAR(gusuku::srgbEncode(gusuku::srgbDecode(encoded)), encoded, 2e-6f);
    }
}

TEST(SrgbCurveTest, OpenColorIOPathAgreesWithScalarFormulas) {
    constexpr int kSteps = 4096;
    ImageRGBA encoded = makeImage(kSteps + 1, 1);
    for (int i = 0; i <= kSteps; ++i) {
        float* t = encoded.texel(i, 0);
        t[0] = t[1] = t[2] = float(i) / float(kSteps);
        t[3] = 0.3f;
    }
    ImageRGBA decoded = encoded;
    gusuku::srgbDecodeImage(decoded);
    ImageRGBA re_encoded = decoded;
    gusuku::srgbEncodeImage(re_encoded);
    for (int i = 0; i <= kSteps; ++i) {
        const float value = encoded.texel(i, 0)[0];
        for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(decoded.texel(i, 0)[c], gusuku::srgbDecode(value), 1e-5f) << "encoded " << value;
            const float linear = decoded.texel(i, 0)[c];
            ASSERT_NEAR(re_encoded.texel(i, 0)[c], gusuku::srgbEncode(linear), 1e-5f) << "linear " << linear;
        }
        ASSERT_EQ(decoded.texel(i, 0)[3], 0.3f) << "alpha must pass through";
    }
}

TEST(ImageFileTest, ExrRoundTripIsExact) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    ImageRGBA image = makeGradient(13, 7, 1000.0f);
    image.texel(2, 3)[0] = 1.0e-7f;  // tiny and huge values survive float32 exactly
    image.texel(5, 1)[1] = 6.5e4f;
    for (bool with_alpha : {false, true}) {
        const std::string path = dir + (with_alpha ? "/rgba.exr" : "/rgb.exr");
        gusuku::writeExr(path, image, with_alpha);
        const ImageRGBA back = gusuku::readImage(path);
        ASSERT_EQ(back.width, image.width);
        ASSERT_EQ(back.height, image.height);
        for (size_t i = 0; i < image.texels.size(); ++i) {
            const bool is_alpha = i % 4 == 3;
            const float expected = is_alpha && !with_alpha ? 1.0f : image.texels[i];
            ASSERT_EQ(back.texels[i], expected) << "float " << i << (with_alpha ? " (RGBA)" : " (RGB)");
        }
    }
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << "temporary left: " << entry.path();
}

TEST(ImageFileTest, PngSrgbRoundTripWithinOneStep) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const ImageRGBA image = makeGradient(17, 9, 1.0f);
    const std::string path = dir + "/gradient.png";
    gusuku::writePngSrgb(path, image, true);
    const ImageRGBA back = gusuku::readImage(path);  // Auto: 8-bit is sRGB
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (size_t i = 0; i < image.texels.size(); ++i) {
        const bool is_alpha = i % 4 == 3;
        // Quantisation is in the encoded domain: compare there.
        const float expected = is_alpha ? image.texels[i] : gusuku::srgbEncode(image.texels[i]);
        const float actual = is_alpha ? back.texels[i] : gusuku::srgbEncode(back.texels[i]);
        ASSERT_NEAR(actual, expected, 1.0f / 255.0f) << "float " << i;
    }
}

TEST(ImageFileTest, PngHoldsSrgbEncodedBytes) {
    // Linear 0.5 must be stored as round(255 * 0.735357) = 188, linear 0.18 as round(255 * 0.461356) = 118.
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    ImageRGBA image = makeImage(2, 1);
    for (int c = 0; c < 4; ++c) image.texel(0, 0)[c] = 0.5f;
    for (int c = 0; c < 4; ++c) image.texel(1, 0)[c] = 0.18f;
    const std::string path = dir + "/grey.png";
    gusuku::writePngSrgb(path, image, false);
    auto input = OIIO::ImageInput::open(path);
    ASSERT_TRUE(input) << OIIO::geterror();
    ASSERT_EQ(input->spec().nchannels, 3);
    unsigned char bytes[6] = {};
    ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, bytes));
    EXPECT_EQ(bytes[0], 188);
    EXPECT_EQ(bytes[2], 188);
    EXPECT_EQ(bytes[3], 118);
}

TEST(ImageFileTest, GreyImageExpandsToRgbWithOpaqueAlpha) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string path = dir + "/grey1.png";
    const unsigned char grey[4] = {0, 128, 255, 64};
    {
        auto output = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(output);
        ASSERT_TRUE(output->open(path, OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::UINT8)));
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, grey));
        ASSERT_TRUE(output->close());
    }
    const ImageRGBA image = gusuku::readImage(path);
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 2);
    const float expected = gusuku::srgbDecode(128.0f / 255.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.texel(1, 0)[c], expected, 1e-5f);
    EXPECT_EQ(image.texel(1, 0)[3], 1.0f);
    EXPECT_NEAR(image.texel(0, 1)[0], 1.0f, 1e-6f);
    // Linear says: no decoding.
    const ImageRGBA raw = gusuku::readImage(path, gusuku::ImageEncoding::Linear);
    EXPECT_NEAR(raw.texel(1, 0)[0], 128.0f / 255.0f, 1e-6f);
}

TEST(ImageFileTest, MemoryDecodeMatchesFileDecode) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const ImageRGBA image = makeGradient(8, 5, 1.0f);
    const std::string path = dir + "/gradient.png";
    gusuku::writePngSrgb(path, image, true);
    const std::string file_bytes = gusuku::readWholeFile(path);
    const ImageRGBA from_file = gusuku::readImage(path);
    const ImageRGBA from_memory = gusuku::readImageFromMemory(
        "embedded", std::vector<unsigned char>(file_bytes.begin(), file_bytes.end()));
    EXPECT_EQ(from_memory.texels, from_file.texels);
    const std::vector<unsigned char> encoded = gusuku::encodePngSrgb(image, true);
    EXPECT_EQ(gusuku::readImageFromMemory("encoded", encoded).texels, from_file.texels);
    const std::string message = expectInputError(
        [] { gusuku::readImageFromMemory("junk.png", std::vector<unsigned char>{1, 2, 3, 4, 5}); });
    EXPECT_NE(message.find("junk.png"), std::string::npos) << message;
}

TEST(ImageFileTest, MissingFileNamesTheFile) {
    const std::string path = "/nonexistent/dir/sky.hdr";
    try {
        gusuku::readImage(path);
        FAIL() << "no InputError";
    } catch (const InputError& error) {
        EXPECT_EQ(error.file(), path);
        EXPECT_NE(std::string(error.what()).find(path), std::string::npos);
    }
    EXPECT_THROW(gusuku::readRadianceMap(path), InputError);
}

TEST(RadianceMapTest, HdrRoundTripWithinRgbePrecision) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const ImageRGBA image = makeGradient(16, 8, 5000.0f);
    const std::string path = dir + "/sky.hdr";
    gusuku::writeHdr(path, image);
    const ImageRGBA back = gusuku::readRadianceMap(path);
    ASSERT_EQ(back.width, 16);
    ASSERT_EQ(back.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            // RGBE shares one exponent: each channel is within 1/256 of the texel's largest channel.
            const float* a = image.texel(x, y);
            const float largest = std::max({a[0], a[1], a[2]});
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(back.texel(x, y)[c], a[c], largest / 128.0f + 1e-6f);
            ASSERT_EQ(back.texel(x, y)[3], 1.0f);
        }
}

void expectBadTexel(const std::string& dir, const char* name, int x, int y, int channel, float value,
                    const std::string& expected_field) {
    ImageRGBA image = makeGradient(6, 4, 2.0f);
    image.texel(x, y)[channel] = value;
    const std::string path = dir + "/" + name;
    gusuku::writeExr(path, image);
    try {
        gusuku::readRadianceMap(path);
        FAIL() << "no InputError for " << value;
    } catch (const InputError& error) {
        EXPECT_EQ(error.file(), path);
        EXPECT_EQ(error.field(), expected_field) << error.what();
    }
}

TEST(RadianceMapTest, RejectsNaNInfinityAndNegativeTexels) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    expectBadTexel(dir, "nan.exr", 3, 1, 1, std::numeric_limits<float>::quiet_NaN(), "texel (3, 1) channel G");
    expectBadTexel(dir, "negative.exr", 0, 2, 0, -0.5f, "texel (0, 2) channel R");
    expectBadTexel(dir, "infinite.exr", 5, 3, 2, std::numeric_limits<float>::infinity(), "texel (5, 3) channel B");
}

TEST(RadianceMapTest, RejectsLowDynamicRangeFormats) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string path = dir + "/sky.png";
    gusuku::writePngSrgb(path, makeGradient(4, 4, 1.0f));
    EXPECT_THROW(gusuku::readRadianceMap(path), InputError);
}

TEST(BoxDownsampleTest, AveragesBlocksAndFitsTheLimit) {
    ImageRGBA image = makeImage(5, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 4; ++c) image.texel(x, y)[c] = float(x + 10 * y);
    const ImageRGBA reduced = gusuku::boxDownsample(image, 3);  // factor 2 -> 3 x 1, last block partial
    ASSERT_EQ(reduced.width, 3);
    ASSERT_EQ(reduced.height, 1);
    EXPECT_FLOAT_EQ(reduced.texel(0, 0)[0], (0 + 1 + 10 + 11) / 4.0f);
    EXPECT_FLOAT_EQ(reduced.texel(1, 0)[0], (2 + 3 + 12 + 13) / 4.0f);
    EXPECT_FLOAT_EQ(reduced.texel(2, 0)[0], (4 + 14) / 2.0f);
    EXPECT_EQ(gusuku::boxDownsample(image, 0).width, 5);
    EXPECT_EQ(gusuku::boxDownsample(image, 8).width, 5);
}

}  // namespace

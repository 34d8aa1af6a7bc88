// Image I/O (gusuku/assets/image.h), the sRGB curve, InputError's message and atomic writes.
// Expected values come from the sRGB standard (IEC 61966-2-1) and from the inputs themselves, never from a
// previous run of the code.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "fifo_watchdog.h"
#include "gpu_test_support.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"

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

// The rename onto the final name would replace what is there: an output onto a device (as root, -o /dev/full
// once replaced the device with a PNG), a FIFO or a folder is refused before anything is written.
TEST(AtomicFileTest, OutputOntoADeviceFifoOrFolderIsRefused) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_atomic");
    fs::create_symlink("/dev/null", dir + "/null.png");
    ASSERT_TRUE(gusuku::testing::makeFifo(dir + "/pipe.png"));
    fs::create_directory(dir + "/folder.png");
    const std::vector<uint8_t> rgba8(4 * 4, 128);
    for (const auto& [name, type] : {std::pair{"null.png", "a character device"}, {"pipe.png", "a FIFO (named pipe)"},
                                     {"folder.png", "a directory"}}) {
        const std::string path = dir + "/" + name;
        try {
            gusuku::writePngRgba8(path, 2, 2, rgba8);
            ADD_FAILURE() << name << " was written";
        } catch (const std::runtime_error& error) {
            EXPECT_EQ(std::string(error.what()), path + ": is " + type + "; an output must be a regular file or a new name");
        }
    }
    EXPECT_TRUE(fs::is_symlink(dir + "/null.png"));
    EXPECT_TRUE(fs::is_fifo(dir + "/pipe.png"));
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    size_t file_count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++file_count;
    EXPECT_EQ(file_count, 3u) << "a temporary file was left behind";
}

TEST(AtomicFileTest, ALoopOfLinksIsNamedAsOne) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_atomic");
    fs::create_symlink(dir + "/b", dir + "/a");
    fs::create_symlink(dir + "/a", dir + "/b");
    EXPECT_EQ(expectInputError([&] { gusuku::readWholeFile(dir + "/a"); }),
              dir + "/a: is a loop of symbolic links; not read");
    EXPECT_EQ(expectInputError([&] { gusuku::readImage(dir + "/a"); }), dir + "/a: is a loop of symbolic links; not read");
}

TEST(AtomicFileTest, ReadingMissingFileNamesIt) {
    const std::string message = expectInputError([] { gusuku::readWholeFile("/nonexistent/gusuku.txt"); });
    EXPECT_NE(message.find("/nonexistent/gusuku.txt"), std::string::npos) << message;
}

// Every file a tool reads whole (glTF buffers and images being hashed for the bake set's input hash, a bake set's
// manifest) is checked before it is opened: a FIFO would block the bake forever, /dev/zero fill memory.
TEST(AtomicFileTest, ReadingWholeRefusesWhatIsNotAFileOfBoundedSize) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_atomic");
    const std::string fifo = dir + "/buffer.bin";
    ASSERT_TRUE(gusuku::testing::makeFifo(fifo));
    std::string message;
    EXPECT_FALSE(gusuku::testing::fifoWasOpenedDuring(
        fifo, [&] { message = expectInputError([&] { gusuku::readWholeFile(fifo); }); }));
    EXPECT_EQ(message, fifo + ": is a FIFO (named pipe), not a regular file; not read");
    fs::create_symlink("/dev/zero", dir + "/zero.bin");
    EXPECT_EQ(expectInputError([&] { gusuku::readWholeFile(dir + "/zero.bin"); }),
              dir + "/zero.bin: is a character device, not a regular file; not read");
    fs::create_directory(dir + "/folder.bin");
    EXPECT_EQ(expectInputError([&] { gusuku::readWholeFile(dir + "/folder.bin"); }),
              dir + "/folder.bin: is a directory, not a regular file; not read");
    // The size limit: a file of exactly max_bytes is read whole, one byte more is refused unread.
    const std::string bytes(1000, 'g');
    gusuku::writeBytesAtomically(dir + "/data.bin", bytes.data(), bytes.size());
    EXPECT_EQ(gusuku::readWholeFile(dir + "/data.bin", 1000), bytes);
    EXPECT_EQ(expectInputError([&] { gusuku::readWholeFile(dir + "/data.bin", 999); }),
              dir + "/data.bin: is 1000 bytes, more than the 999 a file read whole may have");
    EXPECT_EQ(gusuku::readWholeFile(dir + "/data.bin"), bytes);  // the default limit, kMaxInputFileBytes
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

// 8-bit files are decoded by OpenColorIO's byte table (srgbDecodeBytes): every byte value must give exactly what
// the float path gives for the value OpenImageIO converts that byte to (so bakes do not change), grey and alpha
// expanded as before.
TEST(SrgbCurveTest, ByteTableIsExactlyTheFloatDecode) {
    std::vector<uint8_t> bytes(256 * 4);
    for (int k = 0; k < 256; ++k) {
        bytes[size_t(k) * 4 + 0] = uint8_t(k);
        bytes[size_t(k) * 4 + 1] = uint8_t(255 - k);
        bytes[size_t(k) * 4 + 2] = uint8_t(k);
        bytes[size_t(k) * 4 + 3] = uint8_t(k);
    }
    std::vector<float> from_table(bytes.size());
    gusuku::srgbDecodeBytes(bytes.data(), 256, from_table.data());
    ImageRGBA from_floats;
    from_floats.width = 256;
    from_floats.height = 1;
    from_floats.texels.resize(bytes.size());
    ASSERT_TRUE(OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, bytes.data(), OIIO::TypeDesc::FLOAT,
                                           from_floats.texels.data(), int(bytes.size())));
    const std::vector<float> encoded = from_floats.texels;
    gusuku::srgbDecodeImage(from_floats);
    for (size_t i = 0; i < bytes.size(); ++i) {
        if (i % 4 == 3) {
            ASSERT_EQ(from_table[i], encoded[i]) << "alpha of byte " << i / 4 << " passes through as k / 255";
        } else {
            ASSERT_EQ(from_table[i], from_floats.texels[i]) << "byte " << int(bytes[i]) << ", channel " << i % 4;
        }
    }
    EXPECT_EQ(from_table[0], 0.0f);
    EXPECT_EQ(from_table[255 * 4], 1.0f);
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

TEST(ImageFileTest, FifoDeviceAndDirectoryAreRefusedUnopened) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string fifo = dir + "/pipe.exr";
    ASSERT_TRUE(gusuku::testing::makeFifo(fifo));
    std::string message;
    EXPECT_FALSE(gusuku::testing::fifoWasOpenedDuring(
        fifo, [&] { message = expectInputError([&] { gusuku::readRadianceMap(fifo); }); }));
    EXPECT_EQ(message, fifo + ": is a FIFO (named pipe), not a regular file; not read");
    fs::create_symlink("/dev/zero", dir + "/zero.png");
    EXPECT_EQ(expectInputError([&] { gusuku::readImage(dir + "/zero.png"); }),
              dir + "/zero.png: is a character device, not a regular file; not read");
    fs::create_directory(dir + "/folder.hdr");
    EXPECT_EQ(expectInputError([&] { gusuku::readRadianceMap(dir + "/folder.hdr"); }),
              dir + "/folder.hdr: is a directory, not a regular file; not read");
}

// An image wider than the side limit is box-averaged while it is decoded. Texel (x, y) holds (x, y, 1), so a
// block of `factor` columns and rows starting at (f i, f j) averages to (f i + (f - 1) / 2, f j + (f - 1) / 2).
TEST(ImageFileTest, ImagesAboveTheSideLimitAreDownsampledWhileDecoding) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    ImageRGBA image = makeImage(gusuku::kMaxImageSide + 808, 4);  // 9000 x 4
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            image.texel(x, y)[0] = float(x);
            image.texel(x, y)[1] = float(y);
            image.texel(x, y)[2] = 1.0f;
        }
    const std::string path = dir + "/wide.exr";
    gusuku::writeExr(path, image);
    const ImageRGBA read = gusuku::readImage(path);  // factor 2
    ASSERT_EQ(read.width, 4500);
    ASSERT_EQ(read.height, 2);
    for (int x : {0, 1, 2000, 4499}) {
        EXPECT_FLOAT_EQ(read.texel(x, 1)[0], 2.0f * float(x) + 0.5f);
        EXPECT_FLOAT_EQ(read.texel(x, 1)[1], 2.5f);
        EXPECT_FLOAT_EQ(read.texel(x, 1)[2], 1.0f);
        EXPECT_FLOAT_EQ(read.texel(x, 1)[3], 1.0f);
    }
    // A caller's smaller limit: factor 90 gives 100 x 1, every block whole in x, partial (4 rows) in y.
    const ImageRGBA small = gusuku::readImage(path, gusuku::ImageEncoding::Linear, 100);
    ASSERT_EQ(small.width, 100);
    ASSERT_EQ(small.height, 1);
    EXPECT_FLOAT_EQ(small.texel(7, 0)[0], 90.0f * 7.0f + 44.5f);
    EXPECT_FLOAT_EQ(small.texel(7, 0)[1], 1.5f);
}

// Writes `image` as a tiled file (OpenEXR float or TIFF 8-bit) with tiles of tile_side texels, as Nuke and Blender
// write OpenEXR; the image's sides are deliberately not multiples of the tile side.
void writeTiled(const std::string& path, const ImageRGBA& image, int tile_side, OIIO::TypeDesc format) {
    OIIO::ImageSpec spec(image.width, image.height, 4, format);
    spec.tile_width = tile_side;
    spec.tile_height = tile_side;
    auto output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output) << OIIO::geterror();
    ASSERT_TRUE(output->open(path, spec)) << output->geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, image.texels.data())) << output->geterror();
    ASSERT_TRUE(output->close());
}

TEST(ImageFileTest, TiledExrReadsAsTheScanlineFileDoes) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const ImageRGBA image = makeGradient(45, 37, 250.0f);
    for (int tile_side : {16, 64}) {
        const std::string path = dir + "/tiled_" + std::to_string(tile_side) + ".exr";
        writeTiled(path, image, tile_side, OIIO::TypeDesc::FLOAT);
        {
            auto input = OIIO::ImageInput::open(path);
            ASSERT_TRUE(input);
            ASSERT_EQ(input->spec().tile_width, tile_side) << "the file is not tiled";
        }
        const ImageRGBA back = gusuku::readImage(path);
        ASSERT_EQ(back.width, image.width);
        ASSERT_EQ(back.height, image.height);
        for (size_t i = 0; i < image.texels.size(); ++i)
            ASSERT_EQ(back.texels[i], image.texels[i]) << "float " << i << ", tiles of " << tile_side;
        const ImageRGBA sky = gusuku::readRadianceMap(path);
        EXPECT_EQ(sky.texels, back.texels);
        // Box-downsampled while decoding (factor 3): bands that do not start on a tile row.
        const ImageRGBA reduced = gusuku::readImage(path, gusuku::ImageEncoding::Linear, 15);
        ASSERT_EQ(reduced.width, 15);
        ASSERT_EQ(reduced.height, 13);
        for (int y : {0, 5, 12})
            for (int x : {0, 7, 14}) {
                double expected_red = 0.0;
                int count = 0;
                for (int fy = 3 * y; fy < std::min(image.height, 3 * y + 3); ++fy)
                    for (int fx = 3 * x; fx < 3 * x + 3; ++fx, ++count) expected_red += image.texel(fx, fy)[0];
                EXPECT_NEAR(reduced.texel(x, y)[0], expected_red / count, 1e-3) << x << ", " << y;
            }
    }
}

TEST(ImageFileTest, TiledMipmappedExrReadsItsFullResolutionLevel) {
    // The texture route (maketx, ImageBufAlgo::make_texture): tiled, with a full mip chain.
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const ImageRGBA image = makeGradient(40, 24, 3.0f);
    OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT),
                          const_cast<float*>(image.texels.data()));
    OIIO::ImageSpec config;
    config.tile_width = config.tile_height = 16;
    config.attribute("maketx:filtername", "box");
    const std::string path = dir + "/mipmapped.exr";
    ASSERT_TRUE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, source, path, config))
        << OIIO::geterror();
    {
        auto input = OIIO::ImageInput::open(path);
        ASSERT_TRUE(input);
        ASSERT_GT(input->spec().tile_width, 0) << "the file is not tiled";
        ASSERT_TRUE(input->seek_subimage(0, 1)) << "the file has no second mip level";
    }
    const ImageRGBA back = gusuku::readImage(path);
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (size_t i = 0; i < image.texels.size(); ++i) ASSERT_NEAR(back.texels[i], image.texels[i], 2e-3f) << i;
}

TEST(ImageFileTest, TiledEightBitTiffDecodesAsSrgbBytes) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    ImageRGBA image = makeGradient(33, 20, 1.0f);
    const std::string path = dir + "/tiled.tif";
    writeTiled(path, image, 16, OIIO::TypeDesc::UINT8);
    const ImageRGBA back = gusuku::readImage(path);  // 8-bit: sRGB-encoded, decoded to linear
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float byte = std::round(image.texel(x, y)[c] * 255.0f);
                // Within 1e-5 of the curve (the table is OpenColorIO's), far below one byte's step (3e-4 at least).
                ASSERT_NEAR(back.texel(x, y)[c], gusuku::srgbDecode(byte / 255.0f), 1e-5f) << x << ", " << y;
            }
}

// A PNG header declaring 100000 x 100000 texels (40 GB as float RGBA) in a file of a few dozen bytes.
TEST(ImageFileTest, HugeHeaderIsRefusedBeforeDecoding) {
    const unsigned char png[] = {
        0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x01,
        0x86, 0xA0, 0x00, 0x01, 0x86, 0xA0, 0x08, 0x02, 0x00, 0x00, 0x00, 0x27, 0x30, 0x9C, 0x9F, 0x00, 0x00, 0x00,
        0x0C, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0x60, 0xA0, 0x0C, 0x00, 0x00, 0x00, 0x40, 0x00, 0x01, 0xB7,
        0x34, 0x7C, 0xEF, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
    const std::vector<unsigned char> bytes(png, png + sizeof png);
    const std::string message = expectInputError([&] { gusuku::readImageFromMemory("huge.png", bytes); });
    EXPECT_EQ(message, "huge.png: image header declares 100000 x 100000 texels, more than the 268435456 (16384 x "
                       "16384) this reader decodes; refused before decoding");
}

// libpng prints "libpng error: ..." on stderr by itself; the reader folds the failure into its one-line error and
// leaves stderr clean.
TEST(ImageFileTest, CorruptPngGivesOneLineAndNothingOnStderr) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string path = dir + "/corrupt.png";
    gusuku::writePngSrgb(path, makeGradient(16, 16, 1.0f));
    std::string bytes = gusuku::readWholeFile(path);
    const size_t data = bytes.find("IDAT");
    ASSERT_NE(data, std::string::npos);
    bytes[data + 3] = 'B';  // "IDAB": an unknown critical chunk
    gusuku::writeBytesAtomically(path, bytes.data(), bytes.size());
    ::testing::internal::CaptureStderr();
    const std::string message = expectInputError([&] { gusuku::readImage(path); });
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(printed, "");
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(path + ": cannot ", 0), 0u) << message;
    EXPECT_NE(message.find("IDAB"), std::string::npos) << message;  // libpng's reason, folded in
}

// A PNG cut inside a chunk is refused from its chunk chain before the codec runs (OpenImageIO 2.4's PNG reader
// leaks when libpng long-jumps out of its read callback at the end of the data).
TEST(ImageFileTest, TruncatedPngIsRefusedFromItsChunkChain) {
    const std::vector<unsigned char> png = gusuku::encodePngSrgb(makeGradient(16, 16, 1.0f));
    const std::vector<unsigned char> truncated(png.begin(), png.begin() + 60);
    const std::string message = expectInputError([&] { gusuku::readImageFromMemory("cut.png", truncated); });
    EXPECT_EQ(message.rfind("cut.png: truncated PNG: the chunk at byte ", 0), 0u) << message;
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    gusuku::writeBytesAtomically(dir + "/cut.png", truncated.data(), truncated.size());
    EXPECT_EQ(expectInputError([&] { gusuku::readImage(dir + "/cut.png"); }), dir + "/" + message);
    const std::vector<unsigned char> no_end(png.begin(), png.end() - 12);  // without IEND
    EXPECT_EQ(expectInputError([&] { gusuku::readImageFromMemory("noend.png", no_end); }),
              "noend.png: truncated PNG: no IEND chunk before the data ends at byte " + std::to_string(no_end.size()));
}

// Writes a width x height 8-bit RGB JPEG whose texels vary (so its entropy-coded data fills the file evenly).
void writeTestJpeg(const std::string& path, int width, int height) {
    std::vector<unsigned char> codes(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < codes.size(); ++i) codes[i] = (unsigned char)((i * 37 + (i / 3) * 11) % 256);
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output && output->open(path, spec)) << OIIO::geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, codes.data()));
    ASSERT_TRUE(output->close());
}

// A JPEG cut short decodes "successfully" in libjpeg, which fills the missing rows with grey and says "Premature
// end of JPEG file" only as a warning (issue 39 item 7: a sky cut to 44 % became flat grey without a word). The
// reader refuses it naming the file, from a file and from memory (an embedded texture) alike; the whole file reads.
TEST(ImageFileTest, TruncatedJpegIsRefusedNamingTheFile) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    writeTestJpeg(dir + "/whole.jpg", 256, 128);
    EXPECT_NO_THROW(gusuku::readImage(dir + "/whole.jpg"));
    const std::string bytes = gusuku::readWholeFile(dir + "/whole.jpg");
    const std::string cut_bytes = bytes.substr(0, bytes.size() * 44 / 100);
    gusuku::writeBytesAtomically(dir + "/cut.jpg", cut_bytes.data(), cut_bytes.size());
    const std::string message = expectInputError([&] { gusuku::readImage(dir + "/cut.jpg"); });
    EXPECT_EQ(message.rfind(dir + "/cut.jpg: damaged image data", 0), 0u) << message;
    EXPECT_NE(message.find("Premature end of JPEG file"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    const std::vector<unsigned char> cut_memory(cut_bytes.begin(), cut_bytes.end());
    const std::string from_memory =
        expectInputError([&] { gusuku::readImageFromMemory("textures/cut.jpg", cut_memory); });
    EXPECT_EQ(from_memory.rfind("textures/cut.jpg: damaged image data", 0), 0u) << from_memory;
    // Padding between segments (libjpeg's "extraneous bytes before marker", which some cameras and editors
    // write) loses no pixel: the image reads, with the same texels as the file without it.
    const size_t start_of_scan = bytes.find("\xff\xda");
    ASSERT_NE(start_of_scan, std::string::npos);
    const std::string padded = bytes.substr(0, start_of_scan) + std::string(3, '\0') + bytes.substr(start_of_scan);
    gusuku::writeBytesAtomically(dir + "/padded.jpg", padded.data(), padded.size());
    EXPECT_EQ(gusuku::readImage(dir + "/padded.jpg").texels, gusuku::readImage(dir + "/whole.jpg").texels);
    // A Radiance HDR cut short fails in its own decoder: refused as well, naming the file.
    gusuku::writeHdr(dir + "/whole.hdr", makeGradient(64, 32, 2.0f));
    const std::string hdr = gusuku::readWholeFile(dir + "/whole.hdr");
    gusuku::writeBytesAtomically(dir + "/cut.hdr", hdr.data(), hdr.size() * 44 / 100);
    EXPECT_EQ(expectInputError([&] { gusuku::readRadianceMap(dir + "/cut.hdr"); }).rfind(dir + "/cut.hdr: ", 0), 0u);
}

// A downsampled image keeps its proportion (issue 39 item 8): 2:1 with an odd height, 102 x 51 under a side limit
// of 100 (factor 2), reads as 52 x 26, not 51 x 26 (both sides divided by 2 and rounded up). Each reduced texel
// averages the file texels falling in it: with texel (x, y) holding (x, y), reduced texel i along a side of n
// file texels and m reduced ones averages file texels in [i n / m, (i + 1) n / m).
TEST(ImageFileTest, DownsamplingKeepsTheProportionOfAnOddSidedTwoToOneImage) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    ImageRGBA image = makeImage(102, 51);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            image.texel(x, y)[0] = float(x);
            image.texel(x, y)[1] = float(y);
            image.texel(x, y)[3] = 1.0f;
        }
    gusuku::writeExr(dir + "/sky.exr", image);
    const ImageRGBA read = gusuku::readImage(dir + "/sky.exr", gusuku::ImageEncoding::Linear, 100);
    ASSERT_EQ(read.width, 52);
    ASSERT_EQ(read.height, 26);
    double x_sum = 0.0;
    for (int i = 0; i < read.width; ++i) {
        const float x_mean = read.texel(i, 0)[0];
        EXPECT_GE(x_mean, float(i) * 102.0f / 52.0f - 1e-4f) << i;
        EXPECT_LT(x_mean, float(i + 1) * 102.0f / 52.0f) << i;
        x_sum += x_mean;
    }
    for (int j = 0; j < read.height; ++j) {
        EXPECT_GE(read.texel(0, j)[1], float(j) * 51.0f / 26.0f - 1e-4f) << j;
        EXPECT_LT(read.texel(0, j)[1], float(j + 1) * 51.0f / 26.0f) << j;
    }
    // 102 file columns in 52 bins of 1 or 2: the bins' means average to about the file's mean, 50.5.
    EXPECT_NEAR(x_sum / read.width, 50.5, 0.5);
}

// 1e39 is no float: an EXR holding it stores infinity (here a half channel, whose range ends at 65504). RGBE's
// largest exponent byte, 255, encodes 2^127 times the mantissa (1.7e38): a float, but beyond any sky, whose square
// overflows float sums.
TEST(RadianceMapTest, RadianceBeyondFloatRangeOrTheLimitIsRefused) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string half_path = dir + "/half.exr";
    {
        std::vector<float> pixels = {1.0f, 2.0f, 3.0f, 1e5f, 1.0f, 1.0f};
        OIIO::ImageSpec spec(2, 1, 3, OIIO::TypeDesc::HALF);
        auto output = OIIO::ImageOutput::create(half_path);
        ASSERT_TRUE(output && output->open(half_path, spec));
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        output->close();
    }
    EXPECT_EQ(expectInputError([&] { gusuku::readRadianceMap(half_path); }),
              half_path + ": texel (1, 0) channel R: infinite radiance (a value beyond the range of the file's half "
                          "or float channels)");

    const std::string rgbe_path = dir + "/overflow.hdr";
    std::string rgbe = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n";
    rgbe += std::string("\x80\x80\x80\x81", 4);  // 1.0
    rgbe += std::string("\xFF\xFF\xFF\xFF", 4);  // 255.5 / 256 * 2^127
    gusuku::writeBytesAtomically(rgbe_path, rgbe.data(), rgbe.size());
    const std::string message = expectInputError([&] { gusuku::readRadianceMap(rgbe_path); });
    EXPECT_EQ(message.rfind(rgbe_path + ": texel (1, 0) channel R: radiance 1.69", 0), 0u) << message;
    EXPECT_NE(message.find("above the limit 1e+15"), std::string::npos) << message;
}

// OpenImageIO falls back to whichever reader accepts the bytes: a PNG named sky.hdr would be read as 8-bit sRGB
// "radiance". The format actually read decides.
TEST(RadianceMapTest, EightBitImageNamedHdrIsRefused) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku_image");
    const std::string path = dir + "/sky.hdr";
    const std::vector<unsigned char> png = gusuku::encodePngSrgb(makeGradient(8, 4, 1.0f));
    gusuku::writeBytesAtomically(path, png.data(), png.size());
    const std::string message = expectInputError([&] { gusuku::readRadianceMap(path); });
    EXPECT_EQ(message, path + ": holds png 8-bit data (uint8): a sky must be an HDR radiance map (Radiance .hdr or "
                              "OpenEXR .exr with half or float channels), not an 8-bit image");
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

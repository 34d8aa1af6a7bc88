// gusuku-bench --cycles-truth (bench/bench/cycles_truth.h): the frame difference's figures against values worked
// out by hand on constant frames, the per-material colours against the pixels they average, and the reader's
// one-line errors naming the file (a missing render, a render of the wrong size, a material id out of range).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "cycles_truth.h"
#include "gusuku/assets/image.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"

namespace gusuku::bench {
namespace {

namespace fs = std::filesystem;

ImageRGBA constantFrame(int width, int height, float r, float g, float b) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.resize(size_t(width) * height * 4);
    for (size_t pixel = 0; pixel < size_t(width) * height; ++pixel) {
        image.texels[4 * pixel] = r;
        image.texels[4 * pixel + 1] = g;
        image.texels[4 * pixel + 2] = b;
        image.texels[4 * pixel + 3] = 1.0f;
    }
    return image;
}

TEST(BenchCyclesTruth, AFrameAgainstItselfDiffersByNothing) {
    const ImageRGBA frame = constantFrame(8, 4, 0.2f, 0.3f, 0.1f);
    const FrameDifference difference = frameDifference(frame, frame, 1.0f, {});
    EXPECT_EQ(difference.mean_de00, 0.0);
    EXPECT_EQ(difference.rms_de00, 0.0);
    EXPECT_EQ(difference.rms_relative_luminance, 0.0);
    EXPECT_EQ(difference.luminance_bias, 0.0);
    EXPECT_EQ(difference.pixels, 32u);
}

TEST(BenchCyclesTruth, ABrighterFrameReadsAsItsLuminanceRatioOverTheMaskOnly) {
    // Grey 0.2 against 0.25 inside the mask (luminance ratio 0.8: bias -0.2, |dL| / L 0.2), equal outside.
    ImageRGBA frame = constantFrame(4, 2, 0.2f, 0.2f, 0.2f);
    const ImageRGBA reference = constantFrame(4, 2, 0.25f, 0.25f, 0.25f);
    std::vector<uint8_t> mask(8, 0);
    for (size_t pixel : {0u, 1u, 2u}) mask[pixel] = 1;
    for (size_t pixel = 3; pixel < 8; ++pixel)
        for (int c = 0; c < 3; ++c) frame.texels[4 * pixel + c] = 0.25f;
    const FrameDifference difference = frameDifference(frame, reference, 1.0f, mask);
    EXPECT_EQ(difference.pixels, 3u);
    EXPECT_NEAR(difference.luminance_bias, -0.2, 1e-6);
    EXPECT_NEAR(difference.rms_relative_luminance, 0.2, 1e-6);
    // Every masked pixel differs by the same CIEDE2000, so its mean and RMS agree; the colour difference of the
    // two 8-bit greys is that of their sRGB bytes.
    const double expected = summariseError(std::vector<uint8_t>{uint8_t(std::lround(srgbEncode(0.2f) * 255)),
                                                                uint8_t(std::lround(srgbEncode(0.2f) * 255)),
                                                                uint8_t(std::lround(srgbEncode(0.2f) * 255)), 255},
                                           std::vector<uint8_t>{uint8_t(std::lround(srgbEncode(0.25f) * 255)),
                                                                uint8_t(std::lround(srgbEncode(0.25f) * 255)),
                                                                uint8_t(std::lround(srgbEncode(0.25f) * 255)), 255})
                                .mean_de00;
    EXPECT_GT(expected, 1.0);
    EXPECT_NEAR(difference.mean_de00, expected, 1e-9);
    EXPECT_NEAR(difference.rms_de00, expected, 1e-9);
}

TEST(BenchCyclesTruth, MaterialColoursAverageOnlyEachMaterialsInteriorPixels) {
    // A 5 x 5 frame whose 3 x 3 centre is material 1: only the very centre has four neighbours of it.
    CyclesView cycles;
    cycles.materials = {"red_paint"};
    cycles.material_ids.assign(25, 0);
    for (int y = 1; y <= 3; ++y)
        for (int x = 1; x <= 3; ++x) cycles.material_ids[size_t(y) * 5 + x] = 1;
    cycles.with_building[0] = constantFrame(5, 5, 0.4f, 0.1f, 0.1f);
    cycles.with_building[1] = constantFrame(5, 5, 0.2f, 0.1f, 0.1f);
    const ImageRGBA tracer = constantFrame(5, 5, 0.3f, 0.12f, 0.1f);
    // The composite's byte 128 decodes to 0.2158605 linear; exposure 2 halves it.
    const std::vector<uint8_t> composite(25 * 4, 128);
    const std::vector<MaterialColour> colours = materialColours(cycles, composite, 2.0f, tracer);
    ASSERT_EQ(colours.size(), 1u);
    EXPECT_EQ(colours[0].name, "red_paint");
    EXPECT_EQ(colours[0].pixels, 1u);
    EXPECT_NEAR(colours[0].cycles.r, 0.3, 1e-6);  // the mean of Cycles' two seeds
    EXPECT_NEAR(colours[0].tracer.g, 0.12, 1e-6);
    EXPECT_NEAR(colours[0].runtime.b, srgbDecode(128.0 / 255.0) / 2.0, 1e-6);
}

class BenchCyclesTruthFiles : public ::testing::Test {
protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() / ("gusuku_cycles_truth_" + std::to_string(::getpid()));
        fs::remove_all(folder_);
        fs::create_directories(folder_);
        for (const char* stem : {"front_building", "front_building_b", "front_site", "front_site_b"})
            writeExr((folder_ / (std::string(stem) + ".exr")).string(), constantFrame(4, 2, 0.1f, 0.1f, 0.1f), true);
        writeExr((folder_ / "front_materials.exr").string(), constantFrame(4, 2, 1.0f, 0.0f, 0.0f), true);
        std::ofstream(folder_ / "materials.json") << "[\"MA_Structure\"]";
    }
    void TearDown() override { fs::remove_all(folder_); }
    std::string expectInputError(uint32_t width, uint32_t height) {
        try {
            readCyclesView(folder_.string(), "front", width, height);
        } catch (const InputError& error) {
            return error.what();
        }
        ADD_FAILURE() << "readCyclesView accepted the folder";
        return "";
    }
    fs::path folder_;
};

TEST_F(BenchCyclesTruthFiles, ReadsAPoseThatCyclesRendered) {
    const CyclesView view = readCyclesView(folder_.string(), "front", 4, 2);
    EXPECT_EQ(view.materials, std::vector<std::string>{"MA_Structure"});
    EXPECT_EQ(view.material_ids, std::vector<uint32_t>(8, 1u));
    EXPECT_NEAR(view.without_building[1].texels[0], 0.1f, 1e-6f);
}

TEST_F(BenchCyclesTruthFiles, ARenderOfAnotherSizeIsNamedWithBothSizes) {
    const std::string message = expectInputError(8, 2);
    EXPECT_NE(message.find("front_building.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("is 4 x 2, the bench's frames are 8 x 2"), std::string::npos) << message;
}

TEST_F(BenchCyclesTruthFiles, AMissingRenderIsNamed) {
    fs::remove(folder_ / "front_site_b.exr");
    const std::string message = expectInputError(4, 2);
    EXPECT_NE(message.find("front_site_b.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("not found"), std::string::npos) << message;
}

TEST_F(BenchCyclesTruthFiles, AMaterialIdPastTheListIsNamed) {
    writeExr((folder_ / "front_materials.exr").string(), constantFrame(4, 2, 2.0f, 0.0f, 0.0f), true);
    const std::string message = expectInputError(4, 2);
    EXPECT_NE(message.find("front_materials.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("names material 2 of 1"), std::string::npos) << message;
}

}  // namespace
}  // namespace gusuku::bench

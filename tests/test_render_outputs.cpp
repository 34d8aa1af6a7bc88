// gusuku-render never writes over what it reads (bench/render/render_outputs.h): each output (-o, --direct-only,
// --camera-out) against the bake set's files, the camera image, site.json and the other outputs, whatever path
// spelling or link names them.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/formats/input_error.h"
#include "render_outputs.h"

namespace {

namespace fs = std::filesystem;
using gusuku::InputError;
using gusuku::render_cli::RenderRequest;

class RenderOutputsTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = gusuku::testing::makeTemporaryDirectory("gusuku_render_outputs");
        fs::create_directory(dir_ + "/set");
        for (const char* name : {"building_overcast.exr", "ground_geometry.exr"})
            std::ofstream(dir_ + "/set/" + name) << "bytes";
        std::ofstream(dir_ + "/set/manifest.json") << R"({"format": "gusuku-bakeset/1"})";  // what marks a set
        std::ofstream(dir_ + "/camera.png") << "bytes";
        request_.bake_set = dir_ + "/set";
        request_.camera = dir_ + "/camera.png";
        request_.output_png = dir_ + "/composite.png";
    }

    // The option and the problem of the refusal, or "" when the request is accepted.
    std::string refusal() const {
        try {
            gusuku::render_cli::refuseOutputsThatAreInputs(request_, gusuku::render_cli::renderInputFiles(request_, ""));
        } catch (const InputError& error) {
            return error.field() + ": " + error.problem();
        }
        return "";
    }

    std::string dir_;
    RenderRequest request_;
};

TEST_F(RenderOutputsTest, OutputsBesideTheInputsAreAccepted) {
    request_.direct_only_png = dir_ + "/direct.png";
    request_.camera_png = dir_ + "/camera_out.png";
    EXPECT_EQ(refusal(), "");
}

// A new file inside the bake set's folder destroys nothing today, but the set's next bake or pack would take the
// folder for its own: the guard every writing command shares refuses it, and a file inside a pack likewise.
TEST_F(RenderOutputsTest, AnOutputInsideTheBakeSetFolderIsRefused) {
    request_.output_png = dir_ + "/set/composite.png";
    EXPECT_EQ(refusal().rfind("-o: ", 0), 0u) << refusal();
    EXPECT_NE(refusal().find("inside"), std::string::npos) << refusal();
    fs::create_directory(dir_ + "/set/pack");
    std::ofstream(dir_ + "/set/pack/pack.bin") << "bytes";
    request_.output_png = dir_ + "/composite.png";
    request_.camera_png = dir_ + "/set/pack/camera.png";
    EXPECT_EQ(refusal().rfind("--camera-out: ", 0), 0u) << refusal();
}

TEST_F(RenderOutputsTest, AnOutputOntoABakeSetFileIsRefused) {
    request_.output_png = dir_ + "/set/building_overcast.exr";
    EXPECT_EQ(refusal().rfind("-o: is an input of this render", 0), 0u) << refusal();
    request_.output_png = dir_ + "/composite.png";
    request_.direct_only_png = dir_ + "/set/../set/./manifest.json";  // another spelling of the same file
    EXPECT_EQ(refusal().rfind("--direct-only: is an input of this render", 0), 0u) << refusal();
    request_.direct_only_png.reset();
    request_.camera_png = dir_ + "/set";
    EXPECT_EQ(refusal(), "--camera-out: is the bake set folder; write the image elsewhere");
}

TEST_F(RenderOutputsTest, AnOutputOntoTheCameraImageOrThroughALinkIsRefused) {
    request_.output_png = dir_ + "/camera.png";
    EXPECT_EQ(refusal().rfind("-o: is an input of this render", 0), 0u) << refusal();
    fs::create_symlink(dir_ + "/set/ground_geometry.exr", dir_ + "/link.png");
    request_.output_png = dir_ + "/link.png";
    EXPECT_EQ(refusal().rfind("-o: is an input of this render", 0), 0u) << refusal();
}

TEST_F(RenderOutputsTest, TwoOutputsOntoOneFileAreRefused) {
    request_.camera_png = dir_ + "/composite.png";
    EXPECT_EQ(refusal(), "--camera-out: is also the -o output; each output needs its own file");
}

TEST_F(RenderOutputsTest, SiteJsonOfTheSampleCameraIsAnInput) {
    std::ofstream(dir_ + "/site.json") << "{}";
    request_.camera = "sample";
    request_.output_png = dir_ + "/site.json";
    try {
        gusuku::render_cli::refuseOutputsThatAreInputs(
            request_, gusuku::render_cli::renderInputFiles(request_, dir_ + "/site.json"));
        ADD_FAILURE() << "site.json accepted as the output";
    } catch (const InputError& error) {
        EXPECT_EQ(error.field(), "-o");
        EXPECT_EQ(error.file(), dir_ + "/site.json");
    }
}

}  // namespace

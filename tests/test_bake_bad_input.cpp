// The baker meets bad input (issue 3, "Bad input"): degenerate triangles and NaN normals are repaired or left
// out with a warning, a building sunk into the ground bakes without light leaking from under it, and a sky map
// with NaN texels is refused naming the file. Never a crash, never NaN in an output.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "bake_output_checks.h"
#include "fifo_watchdog.h"
#include "gpu_test_support.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;
namespace fs = std::filesystem;


BakeOptions quietOptions(const std::string& output_dir) {
    BakeOptions options;
    options.output_dir = output_dir;
    options.show_progress = false;
    return options;
}

class BakeBadInputTest : public GpuTest {};

TEST_F(BakeBadInputTest, DegenerateTrianglesAndNanNormalsBakeWithWarnings) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-degenerate");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    TriangleMesh house = gusuku::testing::closedBox({-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 2.0f}, false, glm::vec3(0.7f));
    // A zero-area triangle (a repeated vertex) and a sliver with three collinear points.
    const uint32_t base = uint32_t(house.positions.size());
    house.positions.insert(house.positions.end(), {{0.0f, 0.0f, 3.0f}, {1.0f, 0.0f, 3.0f}, {2.0f, 0.0f, 3.0f}});
    house.normals.insert(house.normals.end(), 3, glm::vec3(0.0f, 0.0f, 1.0f));
    house.uv0.insert(house.uv0.end(), 3, glm::vec2(0.0f));
    house.indices.insert(house.indices.end(), {base, base, base + 1, base, base + 1, base + 2});
    house.triangle_material.insert(house.triangle_material.end(), 2, 0u);
    writeGlb(dir + "/building.glb", house, glm::inverse(enuFromGltfYUp()));
    // Our writer never writes a NaN normal, so put NaN into the first vertices' normals with tinygltf itself, as
    // a broken exporter would.
    {
        tinygltf::TinyGLTF gltf;
        tinygltf::Model model;
        std::string error, warning;
        ASSERT_TRUE(gltf.LoadBinaryFromFile(&model, &error, &warning, dir + "/building.glb")) << error;
        const tinygltf::Accessor& accessor = model.accessors.at(size_t(model.meshes.at(0).primitives.at(0).attributes.at("NORMAL")));
        const tinygltf::BufferView& view = model.bufferViews.at(size_t(accessor.bufferView));
        auto* normals = reinterpret_cast<float*>(model.buffers.at(size_t(view.buffer)).data.data() + view.byteOffset +
                                                 accessor.byteOffset);
        for (int i = 0; i < 4 * 3; ++i) normals[i] = std::numeric_limits<float>::quiet_NaN();
        ASSERT_TRUE(gltf.WriteGltfSceneToFile(&model, dir + "/building.glb", true, true, false, true));
    }

    const BakeReport report = runBake(context(), loadSiteConfig(site_path), quietOptions(dir + "/bake"));
    ASSERT_TRUE(report.completed);
    std::string warnings;
    for (const std::string& warning : report.warnings) warnings += warning + "\n";
    EXPECT_NE(warnings.find("NORMAL"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("degenerate"), std::string::npos) << warnings;
    EXPECT_GT(gusuku::testing::expectExrImagesFinite(dir + "/bake"), 0);
}

TEST_F(BakeBadInputTest, BuildingSunkIntoTheGroundDoesNotLeakLight) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-sunk");
    gusuku::testing::MiniSiteOptions site_options;
    site_options.samples_per_texel = 16;
    const std::string site_path = gusuku::testing::writeMiniSite(dir, site_options);
    // The box reaches 1 m below the flat stand-in ground at z = 0.
    const TriangleMesh house =
        gusuku::testing::closedBox({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 2.0f}, false, glm::vec3(0.7f));
    writeGlb(dir + "/building.glb", house, glm::inverse(enuFromGltfYUp()));

    const BakeReport report = runBake(context(), loadSiteConfig(site_path), quietOptions(dir + "/bake"));
    ASSERT_TRUE(report.completed);
    EXPECT_GT(gusuku::testing::expectExrImagesFinite(dir + "/bake"), 0);
    std::ifstream manifest_file(dir + "/bake/manifest.json");
    const nlohmann::json manifest = nlohmann::json::parse(manifest_file);
    // The underground third of the walls sees the ground's back face: those texels are found invalid (and
    // filled by dilation) instead of gathering light from below the ground.
    const size_t invalid = manifest["slots"][0]["invalid_texels"].get<size_t>();
    EXPECT_GT(invalid, report.building_texels / 10) << "of " << report.building_texels;
    EXPECT_LT(invalid, report.building_texels / 2);
}

// The bake hashes every input file before it decodes any (the bake set's input hash), glTF buffers included,
// which the site's own checks do not see: each is checked first, so a FIFO named as a building's buffer is
// refused unopened (it used to block the bake forever) and nothing is written.
TEST_F(BakeBadInputTest, GltfBufferThatIsAFifoIsRefusedUnopened) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-fifobuffer");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    // building.glb as building.gltf with its buffer in building.bin, then that buffer replaced by a FIFO.
    tinygltf::TinyGLTF gltf;
    tinygltf::Model model;
    std::string error, warning;
    ASSERT_TRUE(gltf.LoadBinaryFromFile(&model, &error, &warning, dir + "/building.glb")) << error;
    ASSERT_EQ(model.buffers.size(), 1u);
    model.buffers[0].uri = "building.bin";
    ASSERT_TRUE(gltf.WriteGltfSceneToFile(&model, dir + "/building.gltf", false, false, true, false));
    ASSERT_TRUE(fs::remove(dir + "/building.bin"));
    ASSERT_TRUE(gusuku::testing::makeFifo(dir + "/building.bin"));
    std::string text;
    {
        std::ifstream in(site_path);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    text.replace(text.find("building.glb"), std::string("building.glb").size(), "building.gltf");
    std::ofstream(site_path) << text;

    std::string message;
    EXPECT_FALSE(gusuku::testing::fifoWasOpenedDuring(dir + "/building.bin", [&] {
        try {
            runBake(context(), loadSiteConfig(site_path), quietOptions(dir + "/bake"));
            ADD_FAILURE() << "a FIFO buffer was accepted";
        } catch (const InputError& error) {
            message = error.what();
        }
    }));
    EXPECT_NE(message.find("building.bin"), std::string::npos) << message;
    EXPECT_NE(message.find("is a FIFO (named pipe), not a regular file; not read"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir + "/bake/manifest.json"));
}

TEST_F(BakeBadInputTest, SkyWithNanTexelsIsRefusedNamingTheFile) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-nansky");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    ImageRGBA sky = gusuku::testing::uniformSky(32, 16, glm::vec3(1.0f));
    sky.texel(5, 3)[1] = std::numeric_limits<float>::quiet_NaN();
    writeExr(dir + "/sky_nan.exr", sky);
    std::string text;
    {
        std::ifstream in(site_path);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    text.replace(text.find("sky_sunny.hdr"), std::string("sky_sunny.hdr").size(), "sky_nan.exr");
    std::ofstream(site_path) << text;

    try {
        runBake(context(), loadSiteConfig(site_path), quietOptions(dir + "/bake"));
        FAIL() << "a sky with a NaN texel was accepted";
    } catch (const InputError& error) {
        EXPECT_NE(error.file().find("sky_nan.exr"), std::string::npos) << error.what();
        EXPECT_NE(error.field().find("(5, 3)"), std::string::npos) << error.what();
    }
    EXPECT_FALSE(fs::exists(dir + "/bake/manifest.json"));

    // The command line says the same and exits non-zero.
    const std::string command = gusuku::testing::bakeExecutablePath() + " bake " + site_path + " -o " + dir +
                                "/cli --quiet 2>" + dir + "/stderr.txt";
    const int status = std::system(command.c_str());
    EXPECT_EQ(WEXITSTATUS(status), 1);
    std::ifstream err(dir + "/stderr.txt");
    const std::string message((std::istreambuf_iterator<char>(err)), {});
    EXPECT_NE(message.find("sky_nan.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("NaN"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir + "/cli/manifest.json"));
}

}  // namespace
}  // namespace gusuku::bake

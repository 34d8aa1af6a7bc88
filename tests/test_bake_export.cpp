// gusuku-bake export (issue 21, item 8; gusuku_bake/lightmap_export.h, docs/export.md): a bake of the sample site
// exported with one slot's lightmap, loaded back with tinygltf as a viewer would: every material carries
// MOZ_lightmap naming an embedded PNG on TEXCOORD_1, TEXCOORD_1 is building.glb's own charts byte for byte, the
// PNG's texels decoded as the extension's readers decode them (byte / 255 * intensity) equal the bake set's
// lightmap (read by loadBakeSet) within half a step, and the sun is a directional light pointing along -s with
// E_sun as intensity times colour. Bad input is refused in one line naming the input, with nothing written.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "bake_command.h"
#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku_bake/lightmap_export.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::CommandResult;
using gusuku::testing::runBakeCommand;

// The sample site (`gusuku-bake sample`) baked at 4 samples: a real bake set, made as a user makes one.
std::string bakeSampleSet(const std::string& dir) {
    const CommandResult sample = runBakeCommand({"sample", dir + "/site"}, dir);
    EXPECT_EQ(sample.exit_code, 0) << sample.stderr_text;
    const CommandResult bake =
        runBakeCommand({"bake", dir + "/site/site.json", "-o", dir + "/bakeset", "--samples", "4", "--quiet"}, dir);
    EXPECT_EQ(bake.exit_code, 0) << bake.stderr_text;
    return dir + "/bakeset";
}

// Keeps each image's encoded bytes, so the test decodes the PNG itself (with the project's OpenImageIO reader).
bool keepEncodedBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    image->image.assign(bytes, bytes + size);
    return true;
}

tinygltf::Model loadGlb(const std::string& path) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&keepEncodedBytes, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << path << ": " << error;
    return model;
}

// An accessor's elements as bytes, tightly packed (whatever the view's stride).
std::vector<unsigned char> accessorBytes(const tinygltf::Model& model, int accessor_index, size_t element_bytes) {
    const tinygltf::Accessor& accessor = model.accessors.at(size_t(accessor_index));
    const tinygltf::BufferView& view = model.bufferViews.at(size_t(accessor.bufferView));
    const size_t stride = view.byteStride ? view.byteStride : element_bytes;
    const unsigned char* first = model.buffers.at(size_t(view.buffer)).data.data() + view.byteOffset + accessor.byteOffset;
    std::vector<unsigned char> bytes;
    for (size_t i = 0; i < accessor.count; ++i) bytes.insert(bytes.end(), first + i * stride, first + i * stride + element_bytes);
    return bytes;
}

std::vector<std::string> filesIn(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(BakeExport, LinearEightBitsDecodeWithinHalfAStepAndTheBrightestValueIsTheScale) {
    BakeSetImage lightmap;
    lightmap.width = 3;
    lightmap.height = 1;
    // Values with known bytes at scale 2: 2 -> 255, 1 -> 127.5 -> 128, 0.004 -> 0.51 -> 1, 0.5 -> 63.75 -> 64,
    // 0.0008 -> 0.10 -> 0; a negative value (never in a bake set) would clamp to 0.
    lightmap.rgba = {2.0f, 1.0f, 0.0f, 1.0f, 0.004f, 0.0f, 0.5f, 0.0f, 0.0008f, 0.0019f, 0.0f, 1.0f};
    const LinearLightmap8 encoded = quantiseLightmapLinear8(lightmap);
    EXPECT_DOUBLE_EQ(encoded.intensity, 2.0);
    EXPECT_EQ(encoded.rgb8, (std::vector<uint8_t>{255, 128, 0, 1, 0, 64, 0, 0, 0}));
    for (size_t i = 0; i < encoded.rgb8.size(); ++i)
        EXPECT_LE(std::abs(encoded.rgb8[i] / 255.0 * encoded.intensity - lightmap.rgba[4 * (i / 3) + i % 3]),
                  linearLightmapMaxError(encoded.intensity) * (1 + 1e-6))
            << "channel " << i;
    BakeSetImage black = lightmap;
    std::fill(black.rgba.begin(), black.rgba.end(), 0.0f);
    EXPECT_DOUBLE_EQ(quantiseLightmapLinear8(black).intensity, 1.0) << "an all-black map keeps a usable scale";
    black.rgba.pop_back();
    EXPECT_THROW(quantiseLightmapLinear8(black), std::invalid_argument);
}

TEST(BakeExport, TheSampleBakeLoadsBackWithItsLightmapOnTexcoord1WithinTheEncodingsPrecision) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-export");
    const std::string bakeset_folder = bakeSampleSet(dir);
    const std::string output = dir + "/out/sample.glb";
    const CommandResult result = runBakeCommand({"export", bakeset_folder, "--slot", "sunny_1500", "-o", output}, dir);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    EXPECT_EQ(filesIn(dir + "/out"), std::vector<std::string>{"sample.glb"}) << "no temporary file left";

    const BakeSetData bakeset = loadBakeSet(bakeset_folder);
    size_t slot = 0;
    while (slot < bakeset.manifest.slots.size() && bakeset.manifest.slots[slot].name != "sunny_1500") ++slot;
    ASSERT_LT(slot, bakeset.manifest.slots.size());
    const BakeSetImage& baked = bakeset.slots[slot].building;
    const tinygltf::Model model = loadGlb(output);
    const tinygltf::Model building = loadGlb(bakeset_folder + "/building.glb");
    ASSERT_NE(std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "MOZ_lightmap"),
              model.extensionsUsed.end());
    EXPECT_TRUE(model.extensionsRequired.empty()) << "a viewer without MOZ_lightmap still shows the building";

    // Every material binds the same texture on TEXCOORD_1 at one intensity, the lightmap's brightest value.
    ASSERT_EQ(model.materials.size(), building.materials.size());
    int texture = -1;
    double intensity = 0.0;
    for (const tinygltf::Material& material : model.materials) {
        ASSERT_TRUE(material.extensions.count("MOZ_lightmap")) << material.name;
        const tinygltf::Value& lightmap = material.extensions.at("MOZ_lightmap");
        ASSERT_TRUE(lightmap.Get("index").IsInt() && lightmap.Get("texCoord").IsInt() && lightmap.Get("intensity").IsNumber());
        EXPECT_EQ(lightmap.Get("texCoord").GetNumberAsInt(), 1);
        if (texture < 0) texture = lightmap.Get("index").GetNumberAsInt(), intensity = lightmap.Get("intensity").GetNumberAsDouble();
        EXPECT_EQ(lightmap.Get("index").GetNumberAsInt(), texture);
        EXPECT_EQ(lightmap.Get("intensity").GetNumberAsDouble(), intensity);
    }
    float brightest = 0.0f;
    for (size_t i = 0; i < baked.rgba.size(); ++i)
        if (i % 4 != 3) brightest = std::max(brightest, baked.rgba[i]);
    EXPECT_NEAR(intensity, brightest, 1e-6 * brightest);

    // TEXCOORD_1 is building.glb's, byte for byte, in every primitive.
    ASSERT_EQ(model.meshes.size(), building.meshes.size());
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            const int uv = model.meshes[m].primitives[p].attributes.at("TEXCOORD_1");
            EXPECT_EQ(model.accessors[size_t(uv)].type, TINYGLTF_TYPE_VEC2);
            EXPECT_EQ(accessorBytes(model, uv, 8),
                      accessorBytes(building, building.meshes[m].primitives[p].attributes.at("TEXCOORD_1"), 8));
        }

    // The texels, decoded as three.js decodes a MOZ_lightmap (linear, times intensity).
    const tinygltf::Image& image = model.images.at(size_t(model.textures.at(size_t(texture)).source));
    EXPECT_EQ(image.mimeType, "image/png");
    const ImageRGBA decoded = readImageFromMemory("lightmap", image.image, ImageEncoding::Linear);
    ASSERT_EQ(decoded.width, baked.width);
    ASSERT_EQ(decoded.height, baked.height);
    const double tolerance = linearLightmapMaxError(intensity) * (1.0 + 1e-5);
    double largest_error = 0.0;
    for (size_t t = 0; t < size_t(baked.width) * size_t(baked.height); ++t)
        for (int c = 0; c < 3; ++c)
            largest_error = std::max(largest_error,
                                     std::abs(double(decoded.texels[4 * t + c]) * intensity - baked.rgba[4 * t + c]));
    EXPECT_LE(largest_error, tolerance);
    EXPECT_GT(largest_error, 0.2 * tolerance) << "8 bits cannot hold a real bake exactly: the decode is suspect";
    std::printf("lightmap %dx%d, intensity %.4g, largest error %.4g (bound %.4g)\n", baked.width, baked.height,
                intensity, largest_error, tolerance);

    // The sun: a directional light along -s (glTF (x, y, z) = ENU (x, z, -y)) carrying E_sun.
    const BakeSetSun& sun = bakeset.manifest.slots[slot].sun;
    ASSERT_TRUE(sun.present && sun.position);
    ASSERT_EQ(model.lights.size(), 1u);
    EXPECT_EQ(model.lights[0].type, "directional");
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(model.lights[0].intensity * model.lights[0].color[size_t(c)], sun.irradiance_rgb[c],
                    1e-9 * model.lights[0].intensity);
    const tinygltf::Node& light_node = model.nodes.back();
    ASSERT_EQ(light_node.rotation.size(), 4u);
    const glm::dquat rotation(light_node.rotation[3], light_node.rotation[0], light_node.rotation[1], light_node.rotation[2]);
    const glm::dvec3 s = sun.position->direction_enu;
    const glm::dvec3 travel = rotation * glm::dvec3(0.0, 0.0, -1.0);
    EXPECT_LT(glm::length(travel + glm::dvec3(s.x, s.z, -s.y)), 1e-9);
    const std::vector<int>& scene_nodes = model.scenes.at(size_t(std::max(model.defaultScene, 0))).nodes;
    EXPECT_NE(std::find(scene_nodes.begin(), scene_nodes.end(), int(model.nodes.size() - 1)), scene_nodes.end());

    // An overcast slot has no sun to add.
    ASSERT_EQ(runBakeCommand({"export", bakeset_folder, "--slot", "overcast", "-o", dir + "/overcast.glb"}, dir).exit_code, 0);
    EXPECT_TRUE(loadGlb(dir + "/overcast.glb").lights.empty());
    fs::remove_all(dir);
}

TEST(BakeExport, BadInputIsRefusedInOneLineNamingTheInputAndWritesNothing) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-export-refusals");
    const std::string bakeset_folder = bakeSampleSet(dir);
    fs::create_directories(dir + "/out");
    const std::string kept = dir + "/out/kept.glb";
    std::ofstream(kept) << "an earlier export";
    std::ofstream(dir + "/a_file") << "not a folder";
    const std::string missing = dir + "/no_bakeset";
    struct Refusal {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Refusal> refusals = {
        {{"export", bakeset_folder, "--slot", "dusk", "-o", kept},
         "gusuku-bake: error: " + bakeset_folder +
             "/manifest.json: /slots: no slot 'dusk' (its slots: sunny_0900, sunny_1200, sunny_1500, overcast)"},
        {{"export", missing, "--slot", "overcast", "-o", dir + "/out/missing.glb"},
         "gusuku-bake: error: " + missing + "/manifest.json: file not found"},
        {{"export", bakeset_folder, "--slot", "overcast", "-o", dir + "/a_file/x.glb"},
         "gusuku-bake: error: " + dir + "/a_file/x.glb: cannot write: "},
        {{"export", bakeset_folder, "--slot", "overcast", "-o", bakeset_folder + "/building.glb"},
         "gusuku-bake: error: " + bakeset_folder + "/building.glb: lies inside the bake set " + bakeset_folder},
        {{"export", bakeset_folder, "--slot", "overcast", "-o", dir + "/out/x.gltf"},
         "gusuku-bake: error: " + dir + "/out/x.gltf: the export is a glTF binary: name it .glb"},
        {{"export", bakeset_folder, "--slot", "overcast", "-o", dir + "/out"},
         "gusuku-bake: error: " + dir + "/out: the export is a glTF binary: name it .glb"},
    };
    const std::string building_before = gusuku::testing::readTextFile(bakeset_folder + "/building.glb");
    for (const Refusal& refusal : refusals) {
        const CommandResult result = runBakeCommand(refusal.args, dir);
        EXPECT_EQ(result.exit_code, 1) << refusal.message;
        EXPECT_EQ(result.stderr_text.substr(0, refusal.message.size()), refusal.message);
        EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1) << result.stderr_text;
        EXPECT_TRUE(result.stdout_text.empty()) << result.stdout_text;
    }
    EXPECT_EQ(filesIn(dir + "/out"), std::vector<std::string>{"kept.glb"});
    EXPECT_EQ(gusuku::testing::readTextFile(kept), "an earlier export");
    EXPECT_EQ(gusuku::testing::readTextFile(bakeset_folder + "/building.glb"), building_before);
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_EQ(runBakeCommand({"export", bakeset_folder, "-o", kept}, dir).exit_code, 2) << "--slot is required";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gusuku::bake

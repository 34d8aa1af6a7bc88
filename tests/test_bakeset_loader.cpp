// The bake set loader (gusuku/assets/bakeset_loader.h), the in-memory check (gusuku/formats/bakeset_validate.h) and the
// occluder the baker writes (gusuku_bake/occluder.h, issue 9). One real bake of the mini site with an SfM mesh
// (2 samples) is loaded and checked against what is known independently of the loader: the house's and the
// site's geometry, the manifest's texel counts, the ground grid's addressing. Each error case corrupts a copy.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <OpenImageIO/imageio.h>

#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/assets/glb_positions.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/occluder.h"
#include "mini_site.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::readTextFile;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ------------------------------------------------------------------------------------------------------------
// One real bake, shared by the tests of this binary
// ------------------------------------------------------------------------------------------------------------

/// The mini site (a 2 x 2 x 2 m house; slots "noon" and "cloudy") with its SfM stand-in: a ground of 48 x 48
/// quads over [-12, 12]^2 m at z = 0 and a closed 6 x 1 x 1 m wall box at y in [-2.25, -1.25].
constexpr size_t kSfmSourceTriangles = 48 * 48 * 2 + 12;

const std::string& bakedSet(VulkanContext& context) {
    static const std::string folder = [&] {
        const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-loader");
        gusuku::testing::MiniSiteOptions site_options;
        site_options.samples_per_texel = 2;
        site_options.with_sfm_mesh = true;
        bake::BakeOptions options;
        options.output_dir = dir + "/bakeset";
        options.show_progress = false;
        const bake::BakeReport report =
            bake::runBake(context, loadSiteConfig(gusuku::testing::writeMiniSite(dir, site_options)), options);
        EXPECT_TRUE(report.completed);
        return options.output_dir;
    }();
    return folder;
}

class BakeSetLoaderTest : public gusuku::testing::GpuTest {
protected:
    /// A fresh copy of the baked set, to corrupt.
    std::string copyOfBake(const std::string& name) {
        const std::string copy = gusuku::testing::makeTemporaryDirectory("gusuku-loader-" + name);
        for (const auto& entry : fs::directory_iterator(bakedSet(context())))
            if (entry.is_regular_file() && entry.path().filename() != ".lock")
                fs::copy_file(entry.path(), copy + "/" + entry.path().filename().string());
        return copy;
    }
};

/// loadBakeSet's InputError message, or "" when it loaded.
std::string loadError(const std::string& folder) {
    try {
        loadBakeSet(folder);
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << "one line";
        return error.what();
    }
    return "";
}

void editManifest(const std::string& folder, const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json manifest = nlohmann::json::parse(readTextFile(folder + "/manifest.json"));
    edit(manifest);
    std::ofstream(folder + "/manifest.json") << manifest.dump(2) << "\n";
}

/// Sum over triangles of their signed area projected on the ENU ground plane (counter-clockwise seen from above
/// counts positive): a closed surface gives 0, an up-facing open ground its area.
double projectedArea(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
    double area = 0.0;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
        area += 0.5 * glm::cross(b - a, c - a).z;
    }
    return area;
}

// ------------------------------------------------------------------------------------------------------------
// Loading the real bake
// ------------------------------------------------------------------------------------------------------------

TEST_F(BakeSetLoaderTest, LoadsTheBuildingOccluderAndImagesTheManifestNames) {
    const std::string& folder = bakedSet(context());
    const BakeSetData data = loadBakeSet(folder);
    EXPECT_EQ(data.manifest, readBakeSetManifest(folder + "/manifest.json"));
    EXPECT_EQ(findBakeSetProblem(data), std::nullopt);

    // The house, back in ENU: 6 quads of the box [-1, 1]^2 x [0, 2], one material of albedo (0.7, 0.6, 0.5).
    const BakeSetMesh& building = data.building;
    ASSERT_EQ(building.indices.size(), 36u);
    glm::vec3 low(1e9f), high(-1e9f);
    for (const glm::vec3& p : building.positions) low = glm::min(low, p), high = glm::max(high, p);
    EXPECT_EQ(low, glm::vec3(-1.0f, -1.0f, 0.0f));
    EXPECT_EQ(high, glm::vec3(1.0f, 1.0f, 2.0f));
    EXPECT_NEAR(projectedArea(building.positions, building.indices), 0.0, 1e-5) << "closed, consistently wound";
    for (const glm::vec3& n : building.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    for (const glm::vec2& uv : building.uv1)
        EXPECT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f) << uv.x << ", " << uv.y;
    ASSERT_EQ(building.materials.size(), 1u);
    EXPECT_EQ(building.materials[0].base_color_factor, glm::vec4(0.7f, 0.6f, 0.5f, 1.0f));
    EXPECT_EQ(building.materials[0].base_color_texture, -1);

    // The occluder: fewer triangles than the SfM mesh, the ground's outline and the wall's top kept, the ground
    // facing up (projected area = the ground's 24 x 24 m; the closed wall box adds nothing).
    ASSERT_TRUE(data.manifest.occluder);
    const BakeSetOccluderInfo& info = *data.manifest.occluder;
    EXPECT_EQ(info.source_triangles, kSfmSourceTriangles);
    EXPECT_EQ(data.occluder.indices.size() / 3, info.triangles);
    EXPECT_LT(info.triangles, info.source_triangles / 10);
    EXPECT_EQ(info.target_error_m, bake::kOccluderTargetErrorM);
    EXPECT_LE(info.simplification_error_m, info.target_error_m);
    low = glm::vec3(1e9f), high = glm::vec3(-1e9f);
    for (const glm::vec3& p : data.occluder.positions) low = glm::min(low, p), high = glm::max(high, p);
    for (int c = 0; c < 3; ++c) {  // site.json's quaternion turns the Y-up mesh with float rounding
        EXPECT_NEAR(low[c], glm::vec3(-12.0f, -12.0f, 0.0f)[c], 1e-5f) << c;
        EXPECT_NEAR(high[c], glm::vec3(12.0f, 12.0f, 1.0f)[c], 1e-5f) << c;
    }
    EXPECT_NEAR(projectedArea(data.occluder.positions, data.occluder.indices), 24.0 * 24.0, 1e-3);
    std::cout << "occluder: " << info.source_triangles << " -> " << info.triangles << " triangles, error "
              << info.simplification_error_m << " m\n";

    // Images at the manifest's sizes; the building's alpha marks exactly the traced valid texels it counts.
    const int resolution = data.manifest.building.lightmap_resolution;
    const GroundGrid& grid = data.manifest.ground_grid.grid;
    ASSERT_EQ(data.slots.size(), 2u);
    for (size_t s = 0; s < data.slots.size(); ++s) {
        const BakeSetSlotImages& slot = data.slots[s];
        EXPECT_EQ(slot.building.width, resolution);
        EXPECT_EQ(slot.building.height, resolution);
        size_t valid = 0;
        for (size_t i = 3; i < slot.building.rgba.size(); i += 4) valid += slot.building.rgba[i] == 1.0f;
        EXPECT_EQ(valid, data.manifest.building.texels - data.manifest.slots[s].invalid_texels) << s;
        for (const BakeSetImage* ground : {&slot.ground_with, &slot.ground_without}) {
            EXPECT_EQ(ground->width, grid.columns);
            EXPECT_EQ(ground->height, grid.rows);
        }
    }
    // Row 0 is the north edge: the wall (1 m high, south of the house) is in the south rows, the north is flat.
    const auto heightAt = [&](double x, double y) {
        const std::optional<GroundCellAddress> cell = groundCellAt(grid, {x, y});
        if (!cell) return std::numeric_limits<float>::quiet_NaN();
        return data.ground_geometry.rgba[groundCellIndex(grid, *cell) * 4 + 3];
    };
    EXPECT_NEAR(heightAt(0.1, -1.75), 1.0f, 1e-4f);
    EXPECT_NEAR(heightAt(0.1, 2.0), 0.0f, 1e-4f);
}

TEST_F(BakeSetLoaderTest, TexturesComeBackAsTheirSrgbBytes) {
    const std::string folder = copyOfBake("texture");
    // Known 8-bit sRGB bytes, decoded to linear as a glTF reader does, written into the bake's building.glb.
    const std::vector<uint8_t> bytes = {0, 1, 10, 255, 64, 128, 200, 128, 255, 254, 3, 0, 17, 99, 180, 77};
    TriangleMesh mesh = loadGltf(folder + "/building.glb", {enuFromGltfYUp()});
    ImageRGBA texture;
    texture.width = 2, texture.height = 2;
    for (size_t i = 0; i < bytes.size(); ++i)
        texture.texels.push_back(i % 4 == 3 ? bytes[i] / 255.0f : srgbDecode(bytes[i] / 255.0f));
    mesh.textures = {texture};
    mesh.texture_names = {"t"};
    mesh.materials[0].base_color_texture = 0;
    writeGlb(folder + "/building.glb", mesh, glm::inverse(enuFromGltfYUp()));

    const BakeSetData data = loadBakeSet(folder);
    ASSERT_EQ(data.building.textures.size(), 1u);
    EXPECT_EQ(data.building.textures[0].width, 2);
    EXPECT_EQ(data.building.textures[0].rgba8, bytes);
    EXPECT_EQ(data.building.materials[0].base_color_texture, 0);
}

// ------------------------------------------------------------------------------------------------------------
// Every error names the file, the field and the problem
// ------------------------------------------------------------------------------------------------------------

TEST_F(BakeSetLoaderTest, MissingManifest) {
    const std::string folder = copyOfBake("no-manifest");
    fs::remove(folder + "/manifest.json");
    EXPECT_EQ(loadError(folder), folder + "/manifest.json: file not found: not a bake set folder, or its bake has "
                                          "not finished (the manifest is written last)");
}

TEST_F(BakeSetLoaderTest, WrongFormatVersion) {
    const std::string folder = copyOfBake("format");
    editManifest(folder, [](nlohmann::json& m) { m["format"] = "gusuku-bakeset/2"; });
    EXPECT_EQ(loadError(folder), folder + "/manifest.json: /format: \"gusuku-bakeset/2\" is not a format this reader "
                                          "knows (expected \"gusuku-bakeset/1\")");
}

TEST_F(BakeSetLoaderTest, ExrOfTheWrongSizeNamesTheExpectedSize) {
    const std::string folder = copyOfBake("size");
    const int resolution = readBakeSetManifest(folder + "/manifest.json").building.lightmap_resolution;
    ImageRGBA small;
    small.width = resolution - 1, small.height = resolution;
    small.texels.assign(size_t(small.width) * size_t(small.height) * 4, 0.5f);
    writeExr(folder + "/building_cloudy.exr", small, true);
    const std::string r = std::to_string(resolution), r1 = std::to_string(resolution - 1);
    EXPECT_EQ(loadError(folder), folder + "/building_cloudy.exr: image size: " + r1 + " x " + r + " texels, expected " +
                                     r + " x " + r + " (the manifest's /building/lightmap_resolution)");
}

TEST_F(BakeSetLoaderTest, NanInfiniteAndNegativeTexelsAreNamed) {
    const std::string folder = copyOfBake("texels");
    const auto corrupt = [&](const std::string& file, int x, int y, int channel, float value) {
        ImageRGBA image = readImage(folder + "/" + file, ImageEncoding::Linear);
        image.texel(x, y)[channel] = value;
        writeExr(folder + "/" + file, image, true);
    };
    corrupt("building_noon.exr", 3, 5, 1, kNaN);
    // The messages name the row of gusuku/formats/bakeset_ranges.h the texel breaks.
    EXPECT_EQ(loadError(folder), folder + "/building_noon.exr: texel (3, 5) channel G: NaN is not a finite number in "
                                          "[0, 1e+18] sky units x sr (irradiance (lightmap and ground irradiance RGB))");
    corrupt("building_noon.exr", 3, 5, 1, 0.25f);
    corrupt("ground_cloudy_with.exr", 2, 1, 0, -0.5f);
    EXPECT_EQ(loadError(folder), folder + "/ground_cloudy_with.exr: texel (2, 1) channel R: -0.5 is outside [0, 1e+18] "
                                          "sky units x sr (irradiance (lightmap and ground irradiance RGB))");
    corrupt("ground_cloudy_with.exr", 2, 1, 0, 0.5f);
    corrupt("ground_geometry.exr", 0, 0, 3, std::numeric_limits<float>::infinity());
    EXPECT_EQ(loadError(folder), folder + "/ground_geometry.exr: texel (0, 0) channel A: inf is not a finite number in "
                                          "[-100000, 100000] m (ground height (ground_geometry A))");
}

// A bake set's images are OpenEXR with 4 float32 channels (docs/bakeset.md): what the file holds decides, so a
// half or 3-channel EXR, or a PNG renamed .exr, is refused naming the file, and so is a texel whose irradiance
// would overflow the runtime's sums.
TEST_F(BakeSetLoaderTest, ImagesMustBeFloatRgbaExrWithinTheIrradianceLimit) {
    const std::string folder = copyOfBake("layout");
    const std::string path = folder + "/building_noon.exr";
    const ImageRGBA original = readImage(path, ImageEncoding::Linear);
    const auto rewrite = [&](const std::string& written_as, int channels, OIIO::TypeDesc format) {
        OIIO::ImageSpec spec(original.width, original.height, channels, format);
        std::vector<float> values;
        for (size_t i = 0; i < original.texels.size(); ++i)
            if (int(i % 4) < channels) values.push_back(original.texels[i]);
        auto output = OIIO::ImageOutput::create(written_as);
        ASSERT_TRUE(output && output->open(written_as, spec));
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, values.data()) && output->close());
        if (written_as != path) std::filesystem::rename(written_as, path);
    };
    rewrite(path, 4, OIIO::TypeDesc::HALF);
    EXPECT_EQ(loadError(folder), path + ": holds openexr data with 4 channels of half: expected OpenEXR with 4 "
                                        "float32 channels (RGBA)");
    rewrite(path, 3, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(loadError(folder), path + ": holds openexr data with 3 channels of float: expected OpenEXR with 4 "
                                        "float32 channels (RGBA)");
    rewrite(folder + "/renamed.png", 4, OIIO::TypeDesc::UINT8);
    EXPECT_EQ(loadError(folder), path + ": holds png data with 4 channels of uint8: expected OpenEXR with 4 "
                                        "float32 channels (RGBA)");
    ImageRGBA huge = original;
    huge.texel(3, 5)[0] = 3e38f;
    writeExr(path, huge, true);
    EXPECT_EQ(loadError(folder).rfind(path + ": texel (3, 5) channel R: 3.00000001e+38 is outside [0, 1e+18]", 0), 0u)
        << loadError(folder);
}

TEST_F(BakeSetLoaderTest, SlotWithAMissingFile) {
    const std::string folder = copyOfBake("slot-file");
    fs::remove(folder + "/ground_cloudy_without.exr");
    EXPECT_EQ(loadError(folder), folder + "/manifest.json: /slots/1/ground_irradiance_without_building: names "
                                          "\"ground_cloudy_without.exr\", which is not in " + folder);
}

TEST_F(BakeSetLoaderTest, BuildingWithoutLightmapUvsOrTriangles) {
    const std::string folder = copyOfBake("building");
    TriangleMesh mesh = loadGltf(folder + "/building.glb", {enuFromGltfYUp()});
    mesh.has_uv1 = false;
    mesh.uv1.clear();
    writeGlb(folder + "/building.glb", mesh, glm::inverse(enuFromGltfYUp()));
    EXPECT_EQ(loadError(folder), folder + "/building.glb: TEXCOORD_1: missing: a bake set's building carries its "
                                          "lightmap UVs there");

    // No triangles: the building's primitive turned into points (which a glTF reader skips), with tinygltf.
    writeGlb(folder + "/building.glb", mesh, glm::inverse(enuFromGltfYUp()));
    {
        tinygltf::TinyGLTF gltf;
        tinygltf::Model model;
        std::string error, warning;
        ASSERT_TRUE(gltf.LoadBinaryFromFile(&model, &error, &warning, folder + "/building.glb")) << error;
        for (tinygltf::Primitive& primitive : model.meshes.at(0).primitives) primitive.mode = TINYGLTF_MODE_POINTS;
        ASSERT_TRUE(gltf.WriteGltfSceneToFile(&model, folder + "/building.glb", true, true, false, true));
    }
    const std::string message = loadError(folder);
    EXPECT_EQ(message.rfind(folder + "/building.glb: ", 0), 0u) << message;
    EXPECT_NE(message.find("no triangles"), std::string::npos) << message;
}

TEST_F(BakeSetLoaderTest, OccluderCountAndFileNamesAreChecked) {
    const std::string folder = copyOfBake("occluder");
    const uint64_t triangles = readBakeSetManifest(folder + "/manifest.json").occluder->triangles;
    editManifest(folder, [](nlohmann::json& m) { m["occluder"]["triangles"] = 3; });
    EXPECT_EQ(loadError(folder), folder + "/occluder.glb: meshes: " + std::to_string(triangles) +
                                     " triangles, the manifest's /occluder/triangles says 3");
    editManifest(folder, [](nlohmann::json& m) { m["occluder"]["mesh"] = "../occluder.glb"; });
    EXPECT_EQ(loadError(folder), folder + "/manifest.json: /occluder/mesh: \"../occluder.glb\" is not a plain file "
                                          "name in the bake set folder");
}

// ------------------------------------------------------------------------------------------------------------
// The manifest's occluder entry
// ------------------------------------------------------------------------------------------------------------

TEST_F(BakeSetLoaderTest, ManifestOccluderRoundTripsAndItsAbsenceChangesNoByte) {
    BakeSetManifest manifest = readBakeSetManifest(bakedSet(context()) + "/manifest.json");
    ASSERT_TRUE(manifest.occluder);
    const std::string with = bakeSetManifestJson(manifest);
    EXPECT_EQ(parseBakeSetManifest("m.json", with), manifest);
    manifest.occluder.reset();
    const std::string without = bakeSetManifestJson(manifest);
    EXPECT_EQ(without.find("occluder"), std::string::npos);
    nlohmann::json stripped = nlohmann::json::parse(with);
    stripped.erase("occluder");
    EXPECT_EQ(stripped.dump(2) + "\n", without);

    nlohmann::json bad = nlohmann::json::parse(with);
    bad["occluder"]["triangles"] = bad["occluder"]["source_triangles"].get<uint64_t>() + 1;
    try {
        parseBakeSetManifest("m.json", bad.dump());
        ADD_FAILURE() << "more triangles than the source accepted";
    } catch (const InputError& error) {
        EXPECT_EQ(error.field(), "/occluder/triangles");
    }
}

// ------------------------------------------------------------------------------------------------------------
// simplifyOccluder and writePositionsGlb on meshes made here
// ------------------------------------------------------------------------------------------------------------

/// An n x n grid of quads over [0, side]^2 at z = 0, every quad with its own four corners (as a glTF loader
/// un-shares them), with one vertex raised by bump metres.
void tessellatedSquare(int n, float side, float bump, std::vector<glm::vec3>& positions,
                       std::vector<uint32_t>& indices) {
    const float step = side / float(n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t first = uint32_t(positions.size());
            for (const glm::ivec2 corner : {glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(1, 1), glm::ivec2(0, 1)}) {
                const int x = i + corner.x, y = j + corner.y;
                positions.push_back({float(x) * step, float(y) * step, (x == n / 2 && y == n / 2) ? bump : 0.0f});
            }
            for (const uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(first + k);
        }
}

TEST(Occluder, FlatAreasCollapseAndBumpsAboveTheErrorStay) {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    tessellatedSquare(20, 10.0f, 0.0f, positions, indices);
    const bake::OccluderMesh flat = bake::simplifyOccluder(positions, indices, 0.02);
    EXPECT_EQ(flat.source_triangles, 800u);
    EXPECT_LT(flat.triangleCount(), 200u) << "a plane needs few triangles; its border vertices stay";
    EXPECT_NEAR(projectedArea(flat.positions, flat.indices), 100.0, 1e-3);
    EXPECT_LE(flat.error_m, 0.02);

    positions.clear(), indices.clear();
    tessellatedSquare(20, 10.0f, 0.3f, positions, indices);
    const bake::OccluderMesh bumpy = bake::simplifyOccluder(positions, indices, 0.02);
    float top = 0.0f;
    for (const glm::vec3& p : bumpy.positions) top = std::max(top, p.z);
    EXPECT_EQ(top, 0.3f) << "a 30 cm bump is far above the 2 cm bound";
    const bake::OccluderMesh again = bake::simplifyOccluder(positions, indices, 0.02);
    EXPECT_EQ(again.positions, bumpy.positions);
    EXPECT_EQ(again.indices, bumpy.indices);
}

TEST(Occluder, PositionsGlbIsDeterministicAndReadsBack) {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    tessellatedSquare(4, 2.0f, 0.5f, positions, indices);
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-positions-glb");
    writePositionsGlb(dir + "/a.glb", positions, indices, glm::inverse(enuFromGltfYUp()));
    writePositionsGlb(dir + "/b.glb", positions, indices, glm::inverse(enuFromGltfYUp()));
    EXPECT_EQ(readTextFile(dir + "/a.glb"), readTextFile(dir + "/b.glb"));
    const TriangleMesh back = loadGltf(dir + "/a.glb", {enuFromGltfYUp()});
    ASSERT_EQ(back.indices.size(), indices.size());
    for (size_t i = 0; i < indices.size(); ++i) EXPECT_EQ(back.positions[back.indices[i]], positions[indices[i]]);
    EXPECT_THROW(writePositionsGlb(dir + "/c.glb", positions, {0, 1, 999}, glm::dmat4(1.0)), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir + "/c.glb"));
}

// ------------------------------------------------------------------------------------------------------------
// findBakeSetProblem on data made here
// ------------------------------------------------------------------------------------------------------------

/// One textured triangle, a 4^2 lightmap, a 3 x 2 ground grid, one overcast slot: consistent.
BakeSetData handMadeBakeSet() {
    BakeSetData data;
    data.manifest.building.lightmap_resolution = 4;
    data.manifest.ground_grid.grid = {{-1.0, -1.0}, 0.5, 3, 2};
    data.manifest.slots.resize(1);
    data.manifest.slots[0].sky = BakeSetSky::Overcast;
    BakeSetMesh& mesh = data.building;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    mesh.normals.assign(3, {0, -1, 0});
    mesh.uv0.assign(3, {0.5f, 0.5f});
    mesh.uv1 = {{0, 0}, {1, 0}, {0, 1}};
    mesh.indices = {0, 1, 2};
    mesh.triangle_material = {0};
    mesh.materials = {{glm::vec4(0.5f), 0}};
    mesh.textures = {{1, 1, {10, 20, 30, 255}}};
    const auto image = [](int width, int height) {
        return BakeSetImage{width, height, std::vector<float>(size_t(width) * size_t(height) * 4, 1.0f)};
    };
    data.ground_geometry = image(3, 2);
    data.slots = {{image(4, 4), image(3, 2), image(3, 2)}};
    return data;
}

TEST(FindBakeSetProblem, NamesTheFirstInconsistency) {
    EXPECT_EQ(findBakeSetProblem(handMadeBakeSet()), std::nullopt);
    const auto problem = [](const std::function<void(BakeSetData&)>& spoil) {
        BakeSetData data = handMadeBakeSet();
        spoil(data);
        return findBakeSetProblem(data).value_or("(none)");
    };
    EXPECT_EQ(problem([](BakeSetData& d) { d.slots[0].building.width = 3, d.slots[0].building.rgba.resize(48); }),
              "slots[0].building: 3 x 4 texels, the manifest says lightmap_resolution 4");
    EXPECT_EQ(problem([](BakeSetData& d) { d.slots[0].ground_with.rgba.pop_back(); }),
              "slots[0].ground_with: 23 floats, 3 x 2 RGBA needs 24");
    EXPECT_EQ(problem([](BakeSetData& d) { d.ground_geometry = d.slots[0].building; }),
              "ground_geometry: 4 x 4 texels, the manifest's ground grid is 3 x 2");
    EXPECT_EQ(problem([](BakeSetData& d) { d.slots.push_back(d.slots[0]); }),
              "slots: 2 entries, but manifest.slots has 1");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.indices[2] = 3; }),
              "building.indices[2]: 3 is out of range (3 positions)");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.indices.clear(); }),
              "building.indices: the building has no triangles");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.normals.pop_back(); }),
              "building.normals: 2 entries, but 3 positions");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.uv1.push_back({}); }), "building.uv1: 4 entries, but 3 positions");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.positions[1].y = kNaN; }), "building.positions[1]: is not finite");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.triangle_material[0] = 1; }),
              "building.triangle_material[0]: material 1 does not exist (1 materials)");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.materials[0].base_color_texture = 1; }),
              "building.materials[0].base_color_texture: 1 is neither -1 nor a texture (1 textures)");
    EXPECT_EQ(problem([](BakeSetData& d) { d.building.textures[0].rgba8.push_back(0); }),
              "building.textures[0].rgba8: 5 bytes, 1 x 1 RGBA8 needs 4");
    EXPECT_EQ(problem([](BakeSetData& d) { d.slots[0].building.rgba[(2 * 4 + 1) * 4 + 2] = kNaN; }),
              "slots[0].building: texel (1, 2) channel B is NaN");
    EXPECT_EQ(problem([](BakeSetData& d) { d.slots[0].ground_without.rgba[4] = -2.0f; }),
              "slots[0].ground_without: texel (1, 0) channel R is -2 (negative irradiance)");
    EXPECT_EQ(problem([](BakeSetData& d) { d.occluder.positions = {{0, 0, 0}}, d.occluder.indices = {0, 0, 1}; }),
              "occluder.indices[2]: 1 is out of range (1 positions)");
    EXPECT_EQ(problem([](BakeSetData& d) {
                  d.manifest.occluder = BakeSetOccluderInfo{"occluder.glb", 2, 10, 0.02, 0.01};
                  d.occluder.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, kNaN}}, d.occluder.indices = {0, 1, 2};
              }),
              "occluder.positions[2]: is not finite");
    EXPECT_EQ(problem([](BakeSetData& d) {
                  d.manifest.occluder = BakeSetOccluderInfo{"occluder.glb", 2, 10, 0.02, 0.01};
                  d.occluder.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, d.occluder.indices = {0, 1, 2};
              }),
              "occluder: 1 triangles, the manifest says occluder.triangles 2");
    EXPECT_EQ(problem([](BakeSetData& d) { d.manifest.building.lightmap_resolution = 0; }),
              "manifest.building.lightmap_resolution: 0 is not positive");
}

}  // namespace
}  // namespace gusuku

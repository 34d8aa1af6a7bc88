// glTF loading (gusuku/assets/gltf_loader.h) and writing. Small glTF files are built here as JSON text plus a .bin, so
// each expected position, normal and error comes from the test's own arithmetic, not from a previous run.
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fifo_watchdog.h"
#include "gpu_test_support.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"

namespace {

using gusuku::InputError;
using gusuku::TriangleMesh;
using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125;

// Builds a glTF document with one external .bin buffer.
class GltfBuilder {
public:
    GltfBuilder() {
        document_["asset"] = {{"version", "2.0"}};
        document_["bufferViews"] = json::array();
        document_["accessors"] = json::array();
        document_["meshes"] = json::array();
        document_["nodes"] = json::array();
    }

    int addView(const void* bytes, size_t byte_count, size_t stride = 0) {
        while (binary_.size() % 4) binary_.push_back(0);
        json view = {{"buffer", 0}, {"byteOffset", binary_.size()}, {"byteLength", byte_count}};
        if (stride) view["byteStride"] = stride;
        const auto* first = static_cast<const unsigned char*>(bytes);
        binary_.insert(binary_.end(), first, first + byte_count);
        document_["bufferViews"].push_back(view);
        return int(document_["bufferViews"].size() - 1);
    }

    int addAccessor(int view, int component_type, size_t count, const char* type, size_t byte_offset = 0,
                    bool normalized = false) {
        json accessor = {{"bufferView", view}, {"componentType", component_type}, {"count", count},
                         {"type", type},       {"byteOffset", byte_offset}};
        if (normalized) accessor["normalized"] = true;
        document_["accessors"].push_back(accessor);
        return int(document_["accessors"].size() - 1);
    }

    template <typename T>
    int addAccessorOf(const std::vector<T>& values, int component_type, const char* type, size_t components) {
        const int view = addView(values.data(), values.size() * sizeof(T));
        return addAccessor(view, component_type, values.size() / components, type);
    }

    int addFloats(const std::vector<float>& values, const char* type, size_t components) {
        return addAccessorOf(values, kFloat, type, components);
    }

    // A primitive on a new mesh from positions (xyz triples) and optional u32 indices; returns the mesh index.
    int addTriangleMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices = {},
                        const std::vector<float>& normals = {}, int material = -1) {
        json primitive = {{"attributes", {{"POSITION", addFloats(positions, "VEC3", 3)}}}};
        if (!normals.empty()) primitive["attributes"]["NORMAL"] = addFloats(normals, "VEC3", 3);
        if (!indices.empty()) primitive["indices"] = addAccessorOf(indices, kUnsignedInt, "SCALAR", 1);
        if (material >= 0) primitive["material"] = material;
        document_["meshes"].push_back({{"primitives", json::array({primitive})}});
        return int(document_["meshes"].size() - 1);
    }

    int addNode(json node) {
        document_["nodes"].push_back(node);
        return int(document_["nodes"].size() - 1);
    }

    void setScene(const std::vector<int>& roots) {
        document_["scenes"] = json::array({{{"nodes", roots}}});
        document_["scene"] = 0;
    }

    json& document() { return document_; }

    std::string write(const std::string& dir, const std::string& name) {
        document_["buffers"] = json::array({{{"uri", name + ".bin"}, {"byteLength", binary_.size()}}});
        gusuku::writeBytesAtomically(dir + "/" + name + ".bin", binary_.data(), binary_.size());
        const std::string text = document_.dump(1);
        const std::string path = dir + "/" + name + ".gltf";
        gusuku::writeBytesAtomically(path, text.data(), text.size());
        return path;
    }

private:
    json document_;
    std::vector<unsigned char> binary_;
};

const std::vector<float> kTriangle = {1, 2, 3, 4, 5, 6, 7, 8, 10};

void expectVec3Near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

InputError expectInputError(const std::function<void()>& action) {
    try {
        action();
    } catch (const InputError& error) {
        return error;
    }
    ADD_FAILURE() << "no InputError thrown";
    return InputError("", "", "");
}

glm::vec3 faceNormal(const TriangleMesh& mesh, size_t triangle) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * triangle]];
    const glm::vec3 b = mesh.positions[mesh.indices[3 * triangle + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[3 * triangle + 2]];
    return glm::normalize(glm::cross(b - a, c - a));
}

class GltfTest : public ::testing::Test {
protected:
    std::string dir_ = gusuku::testing::makeTemporaryDirectory("gusuku_gltf");
};

TEST(GltfAxes, EnuFromGltfYUpIsARotation) {
    const glm::dmat4 m = gusuku::enuFromGltfYUp();
    const glm::dvec4 p = m * glm::dvec4(1.0, 2.0, 3.0, 1.0);
    EXPECT_EQ(glm::dvec3(p), glm::dvec3(1.0, -3.0, 2.0));
    EXPECT_DOUBLE_EQ(glm::determinant(glm::dmat3(m)), 1.0);
}

TEST(MeshTest, AppendMeshReindexesVerticesMaterialsAndTextures) {
    TriangleMesh first;
    first.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    first.normals.assign(3, {0, 0, 1});
    first.uv0.assign(3, {0, 0});
    first.indices = {0, 1, 2};
    first.triangle_material = {0};
    first.materials.resize(1);
    TriangleMesh second = first;
    for (glm::vec3& p : second.positions) p += glm::vec3(0, 0, 5);
    second.materials[0].base_color_texture = 0;
    second.textures.resize(1);
    second.texture_names = {"albedo.png"};
    gusuku::appendMesh(first, second);
    ASSERT_EQ(first.triangleCount(), 2u);
    EXPECT_EQ(first.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(first.triangle_material, (std::vector<uint32_t>{0, 1}));
    ASSERT_EQ(first.materials.size(), 2u);
    EXPECT_EQ(first.materials[0].base_color_texture, -1);
    EXPECT_EQ(first.materials[1].base_color_texture, 0);
    EXPECT_EQ(first.texture_names, std::vector<std::string>{"albedo.png"});
    const gusuku::Bounds3 bounds = gusuku::meshBounds(first);
    EXPECT_EQ(bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(bounds.max, glm::vec3(1, 1, 5));
    EXPECT_TRUE(gusuku::meshBounds(TriangleMesh{}).empty());
}

TEST_F(GltfTest, YUpTriangleLandsAtEnuXMinusZY) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {0, 1, 0, 0, 1, 0, 0, 1, 0});
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "yup"), options);
    ASSERT_EQ(loaded.triangleCount(), 1u);
    ASSERT_EQ(loaded.vertexCount(), 3u);
    for (size_t v = 0; v < 3; ++v) {
        const float x = kTriangle[3 * v], y = kTriangle[3 * v + 1], z = kTriangle[3 * v + 2];
        expectVec3Near(loaded.positions[v], {x, -z, y});
        expectVec3Near(loaded.normals[v], {0, 0, 1});  // glTF up is ENU up
        EXPECT_EQ(loaded.uv0[v], glm::vec2(0.0f));
    }
    EXPECT_FALSE(loaded.has_uv1);
    ASSERT_EQ(loaded.materials.size(), 1u);  // the default material
    EXPECT_EQ(loaded.materials[0].base_color_factor, glm::vec4(1.0f));
}

TEST_F(GltfTest, NodeHierarchyComposesTranslationRotationScale) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh({1, 0, 0, 0, 1, 0, 0, 0, 1});
    const double s = std::sqrt(0.5);
    // child: 90 degrees about +y maps (x, y, z) -> (z, y, -x); parent: scale 2, then translate (10, 0, 0).
    const int child = builder.addNode({{"mesh", mesh}, {"rotation", {0.0, s, 0.0, s}}});
    const int parent = builder.addNode({{"children", {child}}, {"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}});
    builder.setScene({parent});
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "nodes"), {});
    ASSERT_EQ(loaded.vertexCount(), 3u);
    expectVec3Near(loaded.positions[0], {10, 0, -2});
    expectVec3Near(loaded.positions[1], {10, 2, 0});
    expectVec3Near(loaded.positions[2], {12, 0, 0});
}

TEST_F(GltfTest, NodeMatrixIsColumnMajorAndInstancesRepeat) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    // Column-major translation by (5, 6, 7) as glTF stores it, and a second plain instance.
    const int moved = builder.addNode({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1}}});
    const int plain = builder.addNode({{"mesh", mesh}});
    builder.setScene({moved, plain});
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "matrix"), {});
    ASSERT_EQ(loaded.triangleCount(), 2u);
    expectVec3Near(loaded.positions[0], {6, 8, 10});
    expectVec3Near(loaded.positions[3], {1, 2, 3});
}

TEST_F(GltfTest, MirroringTransformFlipsWindingAndNormalsUseInverseTranspose) {
    GltfBuilder builder;
    // Counter-clockwise seen from +z, normal +z.
    const int mesh = builder.addTriangleMesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {}, {0, 0, 1, 0, 0, 1, 0, 0, 1});
    const int mirrored = builder.addNode({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
    // A slanted triangle with normal (1, 1, 0)/sqrt2 under scale (2, 1, 1): the inverse transpose gives
    // (0.5, 1, 0) normalised; transforming the normal like a position would give (2, 1, 0).
    const float r = std::sqrt(0.5f);
    const int slanted_mesh = builder.addTriangleMesh({1, 0, 0, 0, 1, 0, 1, 0, 1}, {}, {r, r, 0, r, r, 0, r, r, 0});
    const int stretched = builder.addNode({{"mesh", slanted_mesh}, {"scale", {2, 1, 1}}});
    builder.setScene({mirrored, stretched});
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "mirror"), {});
    ASSERT_EQ(loaded.triangleCount(), 2u);
    expectVec3Near(loaded.normals[0], {0, 0, 1});
    EXPECT_GT(glm::dot(faceNormal(loaded, 0), glm::vec3(0, 0, 1)), 0.999f) << "winding not flipped";
    expectVec3Near(loaded.normals[3], glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f)));
    EXPECT_GT(glm::dot(faceNormal(loaded, 1), loaded.normals[3]), 0.999f);
}

TEST_F(GltfTest, MissingNormalsAreFlatFaceNormals) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1}, {0, 1, 2, 1, 3, 2});
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "flat"), {});
    ASSERT_EQ(loaded.triangleCount(), 2u);
    for (size_t t = 0; t < 2; ++t)
        for (size_t corner = 0; corner < 3; ++corner)
            expectVec3Near(loaded.normals[loaded.indices[3 * t + corner]], faceNormal(loaded, t));
    expectVec3Near(loaded.normals[loaded.indices[0]], {0, 0, 1});
}

TEST_F(GltfTest, ReadsSmallIndicesInterleavedStrideAndNormalizedUvs) {
    GltfBuilder builder;
    // Interleaved: position (3 floats) + 4 bytes of padding per vertex, stride 16.
    struct Vertex {
        float position[3];
        uint32_t padding;
    };
    const std::vector<Vertex> vertices = {{{0, 0, 0}, 0}, {{1, 0, 0}, 0}, {{0, 1, 0}, 0}};
    const int view = builder.addView(vertices.data(), vertices.size() * sizeof(Vertex), sizeof(Vertex));
    const int positions = builder.addAccessor(view, kFloat, 3, "VEC3");
    const std::vector<uint16_t> uv_values = {0, 0, 65535, 0, 0, 32768};
    const int uv_view = builder.addView(uv_values.data(), uv_values.size() * 2);
    const int uvs = builder.addAccessor(uv_view, kUnsignedShort, 3, "VEC2", 0, true);
    const std::vector<uint8_t> small_indices = {0, 1, 2};
    const int index_view = builder.addView(small_indices.data(), small_indices.size());
    const int indices8 = builder.addAccessor(index_view, kUnsignedByte, 3, "SCALAR");
    const std::vector<uint16_t> short_indices = {2, 1, 0};
    const int indices16 = builder.addAccessorOf(short_indices, kUnsignedShort, "SCALAR", 1);
    builder.document()["meshes"].push_back(
        {{"primitives",
          {{{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}}, {"indices", indices8}},
           {{"attributes", {{"POSITION", positions}}}, {"indices", indices16}}}}});
    builder.setScene({builder.addNode({{"mesh", 0}})});
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "stride"), {});
    ASSERT_EQ(loaded.triangleCount(), 2u);
    expectVec3Near(loaded.positions[loaded.indices[1]], {1, 0, 0});
    expectVec3Near(loaded.positions[loaded.indices[2]], {0, 1, 0});
    EXPECT_FLOAT_EQ(loaded.uv0[1].x, 1.0f);
    EXPECT_NEAR(loaded.uv0[2].y, 32768.0f / 65535.0f, 1e-7f);
    // The second primitive's first index is 2: vertex (0, 1, 0).
    expectVec3Near(loaded.positions[loaded.indices[3]], {0, 1, 0});
}

TEST_F(GltfTest, CorruptJsonIsInputError) {
    const std::string path = dir_ + "/corrupt.gltf";
    const std::string text = "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {";
    gusuku::writeBytesAtomically(path, text.data(), text.size());
    const InputError error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_EQ(error.file(), path);
    EXPECT_FALSE(error.problem().empty());
}

TEST_F(GltfTest, TruncatedGlbIsInputError) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const TriangleMesh source = gusuku::loadGltf(builder.write(dir_, "whole"), {});
    const std::string path = dir_ + "/whole.glb";
    gusuku::writeGlb(path, source, glm::dmat4(1.0));
    ASSERT_EQ(gusuku::loadGltf(path, {}).triangleCount(), 1u);
    std::string bytes = gusuku::readWholeFile(path);
    bytes.resize(bytes.size() / 2);
    const std::string truncated = dir_ + "/truncated.glb";
    gusuku::writeBytesAtomically(truncated, bytes.data(), bytes.size());
    const InputError error = expectInputError([&] { gusuku::loadGltf(truncated, {}); });
    EXPECT_EQ(error.file(), truncated);
    EXPECT_FALSE(error.problem().empty());
    EXPECT_EQ(expectInputError([&] { gusuku::loadGltf(dir_ + "/absent.glb", {}); }).file(), dir_ + "/absent.glb");
}

TEST_F(GltfTest, EveryTruncationOrByteFlipIsLoadedOrInputError) {
    // Damaged files must never crash the loader or throw anything but InputError.
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {0, 1, 2}, {0, 0, 1, 0, 0, 1, 0, 0, 1});
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const TriangleMesh source = gusuku::loadGltf(builder.write(dir_, "source"), {});
    const std::string whole_path = dir_ + "/whole.glb";
    gusuku::writeGlb(whole_path, source, glm::dmat4(1.0));
    const std::string whole = gusuku::readWholeFile(whole_path);
    const std::string damaged_path = dir_ + "/damaged.glb";
    size_t attempts = 0, rejected = 0;
    const auto load_damaged = [&](const std::string& bytes) {
        gusuku::writeBytesAtomically(damaged_path, bytes.data(), bytes.size());
        ++attempts;
        try {
            gusuku::loadGltf(damaged_path, {});
        } catch (const InputError&) {
            ++rejected;
        }
    };
    for (size_t length = 0; length < whole.size(); length += 7) load_damaged(whole.substr(0, length));
    uint32_t random_state = 12345;
    for (int trial = 0; trial < 300; ++trial) {
        std::string bytes = whole;
        for (int flip = 0; flip < 3; ++flip) {
            random_state = random_state * 1664525u + 1013904223u;
            bytes[(random_state >> 8) % bytes.size()] ^= char(1 + (random_state & 0x7f));
        }
        load_damaged(bytes);
    }
    // Every strict prefix is a truncated .glb: all of those at least must be rejected.
    EXPECT_GE(rejected, (whole.size() + 6) / 7);
    EXPECT_LE(rejected, attempts);
}

TEST_F(GltfTest, IndexOutOfRangeNamesPrimitiveAndIndex) {
    GltfBuilder builder;
    const int good = builder.addTriangleMesh(kTriangle, {0, 1, 2});
    builder.addTriangleMesh(kTriangle, {0, 1, 5});
    // Put the bad primitive second on mesh 0.
    auto& meshes = builder.document()["meshes"];
    meshes[good]["primitives"].push_back(meshes[1]["primitives"][0]);
    meshes.erase(1);
    builder.setScene({builder.addNode({{"mesh", good}})});
    const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "index"), {}); });
    EXPECT_EQ(error.field(), "meshes[0].primitives[1].indices");
    EXPECT_EQ(error.problem(), "index 5 >= vertex count 3");
}

TEST_F(GltfTest, NaNPositionIsInputError) {
    GltfBuilder builder;
    std::vector<float> positions = kTriangle;
    positions[4] = std::numeric_limits<float>::quiet_NaN();
    builder.setScene({builder.addNode({{"mesh", builder.addTriangleMesh(positions)}})});
    const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "nan"), {}); });
    EXPECT_EQ(error.field(), "meshes[0].primitives[0].attributes.POSITION");
    EXPECT_NE(error.problem().find("vertex 1"), std::string::npos) << error.what();
}

TEST_F(GltfTest, AccessorBeyondBufferViewIsInputError) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    builder.document()["accessors"][0]["count"] = 4;  // 48 bytes from a 36-byte view
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "range"), {}); });
    EXPECT_NE(error.field().find("meshes[0].primitives[0].attributes.POSITION"), std::string::npos) << error.what();
}

TEST_F(GltfTest, NonTrianglePrimitivesAreSkippedWithWarning) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    json points = builder.document()["meshes"][mesh]["primitives"][0];
    points["mode"] = 0;
    builder.document()["meshes"][mesh]["primitives"].push_back(points);
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    std::vector<std::string> warnings;
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "points"), {}, &warnings);
    EXPECT_EQ(loaded.triangleCount(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("meshes[0].primitives[1]"), std::string::npos) << warnings[0];
}

TEST_F(GltfTest, MeshWithoutTrianglesIsInputError) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    builder.document()["meshes"][mesh]["primitives"][0]["mode"] = 1;  // LINES
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "lines"), {}); });
}

json texturedMaterial(const std::string& uri) {
    return {{"images", {{{"uri", uri}}}},
            {"textures", {{{"source", 0}}}},
            {"materials",
             {{{"name", "plaster"},
               {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
               {"emissiveFactor", {0.0, 0.5, 0.0}},
               {"doubleSided", true}}}}};
}

TEST_F(GltfTest, MissingTextureIsWarningAndFactorOnly) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {}, 0);
    builder.document().update(texturedMaterial("no_such_texture.png"));
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    std::vector<std::string> warnings;
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "notexture"), {}, &warnings);
    ASSERT_EQ(loaded.materials.size(), 1u);
    const gusuku::Material& material = loaded.materials[0];
    EXPECT_EQ(material.name, "plaster");
    EXPECT_EQ(material.base_color_texture, -1);
    EXPECT_EQ(material.base_color_factor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
    EXPECT_EQ(material.emissive_factor, glm::vec3(0.0f, 0.5f, 0.0f));
    EXPECT_TRUE(material.double_sided);
    EXPECT_TRUE(loaded.textures.empty());
    bool named = false;
    for (const std::string& warning : warnings) named |= warning.find("no_such_texture.png") != std::string::npos;
    EXPECT_TRUE(named) << "no warning names the missing texture";
}

TEST_F(GltfTest, EmbeddedImageOutsideItsBufferIsInputError) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {}, 0);
    const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    const int image_view = builder.addView(png_signature, sizeof(png_signature));
    builder.document()["bufferViews"][image_view]["byteLength"] = 1 << 20;  // far past the buffer's end
    json material = texturedMaterial("unused.png");
    material["images"] = {{{"bufferView", image_view}, {"mimeType", "image/png"}}};
    builder.document().update(material);
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const std::string path = builder.write(dir_, "image_range");
    const InputError error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_NE(std::string(error.what()).find("images[0]"), std::string::npos) << error.what();
}

TEST_F(GltfTest, TextureIsDecodedAsSrgbAndDownsampled) {
    // 8 x 4 PNG: left half sRGB-encoded 0.5 (stored byte 128 after encoding linear srgbDecode(128/255)),
    // right half white. max_texture_size 4 halves it to 4 x 2.
    gusuku::ImageRGBA image;
    image.width = 8;
    image.height = 4;
    image.texels.resize(8 * 4 * 4);
    const float grey = gusuku::srgbDecode(128.0f / 255.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 4; ++c) image.texel(x, y)[c] = c == 3 ? 1.0f : (x < 4 ? grey : 1.0f);
    gusuku::writePngSrgb(dir_ + "/albedo.png", image);
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {}, 0);
    builder.document().update(texturedMaterial("albedo.png"));
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    gusuku::GltfLoadOptions options;
    options.max_texture_size = 4;
    std::vector<std::string> warnings;
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "textured"), options, &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(loaded.textures.size(), 1u);
    EXPECT_EQ(loaded.materials[0].base_color_texture, 0);
    EXPECT_EQ(loaded.textures[0].width, 4);
    EXPECT_EQ(loaded.textures[0].height, 2);
    EXPECT_NEAR(loaded.textures[0].texel(0, 0)[0], grey, 1e-5f);
    EXPECT_NEAR(loaded.textures[0].texel(3, 1)[1], 1.0f, 1e-6f);
}

TEST_F(GltfTest, WriteGlbRoundTrip) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 1}, {6, 5, 1}, {5, 6, 2}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0.6f, 0.8f}, {0, 0.6f, 0.8f}, {0, 0.6f, 0.8f}};
    mesh.uv0 = {{0, 0}, {1, 0}, {0, 1}, {0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 1}};
    mesh.uv1 = {{0.1f, 0.1f}, {0.2f, 0.1f}, {0.1f, 0.2f}, {0.6f, 0.6f}, {0.7f, 0.6f}, {0.6f, 0.7f}};
    mesh.has_uv1 = true;
    mesh.indices = {0, 1, 2, 3, 4, 5};
    mesh.triangle_material = {0, 1};
    gusuku::Material wall;
    wall.name = "wall";
    wall.base_color_factor = {0.8f, 0.7f, 0.6f, 1.0f};
    wall.base_color_texture = 0;
    gusuku::Material lamp;
    lamp.name = "lamp";
    lamp.emissive_factor = {0.5f, 0.4f, 0.3f};
    lamp.double_sided = true;
    lamp.alpha_masked = true;  // an export keeps alphaMode MASK and its cutoff
    lamp.alpha_cutoff = 0.25f;
    mesh.materials = {wall, lamp};
    gusuku::ImageRGBA texture;
    texture.width = 3;
    texture.height = 2;
    texture.texels = {0.0f, 0.1f, 0.2f, 1.0f, 0.3f, 0.4f, 0.5f, 1.0f, 0.6f, 0.7f, 0.8f, 1.0f,
                      0.9f, 1.0f, 0.05f, 1.0f, 0.2f, 0.2f, 0.2f, 1.0f, 0.01f, 0.5f, 0.99f, 1.0f};
    mesh.textures = {texture};
    mesh.texture_names = {"texture"};

    const std::string path = dir_ + "/round.glb";
    gusuku::writeGlb(path, mesh, glm::inverse(gusuku::enuFromGltfYUp()));
    gusuku::GltfLoadOptions options;
    options.enu_from_model = gusuku::enuFromGltfYUp();
    const TriangleMesh loaded = gusuku::loadGltf(path, options);

    ASSERT_EQ(loaded.triangleCount(), mesh.triangleCount());
    ASSERT_EQ(loaded.vertexCount(), mesh.vertexCount());
    ASSERT_TRUE(loaded.has_uv1);
    // Primitives are written per material in material order, so triangle t keeps its corners in order.
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        const uint32_t a = mesh.indices[i], b = loaded.indices[i];
        expectVec3Near(loaded.positions[b], mesh.positions[a]);
        expectVec3Near(loaded.normals[b], mesh.normals[a]);
        EXPECT_EQ(loaded.uv0[b], mesh.uv0[a]);
        EXPECT_EQ(loaded.uv1[b], mesh.uv1[a]);
    }
    ASSERT_EQ(loaded.materials.size(), 2u);
    EXPECT_EQ(loaded.triangle_material, mesh.triangle_material);
    for (size_t m = 0; m < 2; ++m) {
        EXPECT_EQ(loaded.materials[m].name, mesh.materials[m].name);
        EXPECT_EQ(loaded.materials[m].base_color_factor, mesh.materials[m].base_color_factor);
        EXPECT_EQ(loaded.materials[m].emissive_factor, mesh.materials[m].emissive_factor);
        EXPECT_EQ(loaded.materials[m].double_sided, mesh.materials[m].double_sided);
        EXPECT_EQ(loaded.materials[m].alpha_masked, mesh.materials[m].alpha_masked);
        EXPECT_EQ(loaded.materials[m].alpha_cutoff, mesh.materials[m].alpha_masked ? 0.25f : 0.5f);
    }
    ASSERT_EQ(loaded.textures.size(), 1u);
    EXPECT_EQ(loaded.materials[0].base_color_texture, 0);
    EXPECT_EQ(loaded.materials[1].base_color_texture, -1);
    ASSERT_EQ(loaded.textures[0].width, 3);
    ASSERT_EQ(loaded.textures[0].height, 2);
    for (size_t i = 0; i < texture.texels.size(); ++i)  // 8-bit sRGB storage: within one step, encoded
        EXPECT_NEAR(gusuku::srgbEncode(loaded.textures[0].texels[i]), gusuku::srgbEncode(texture.texels[i]),
                    1.0f / 255.0f);
}

}  // namespace

namespace {

using gusuku::testing::fifoWasOpenedDuring;

bool isOneLine(const std::string& message) {
    return message.find('\n') == std::string::npos && message.find("[json.exception") == std::string::npos;
}

}  // namespace

TEST_F(GltfTest, BufferOrImageUriNamingAFifoDeviceOrDirectoryIsRefusedUnopened) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {}, 0);
    builder.document().update(texturedMaterial("pipe.png"));
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const std::string path = builder.write(dir_, "special");
    ASSERT_EQ(mkfifo((dir_ + "/pipe.png").c_str(), 0600), 0);
    InputError error("", "", "");
    EXPECT_FALSE(fifoWasOpenedDuring(dir_ + "/pipe.png", [&] { error = expectInputError([&] { gusuku::loadGltf(path, {}); }); }));
    EXPECT_EQ(error.file(), path);
    EXPECT_EQ(error.field(), "images[0].uri");
    EXPECT_EQ(error.problem(), "\"pipe.png\" is a FIFO (named pipe), not a regular file; not read");

    // The buffer itself: a FIFO, then a link to a character device, then a directory.
    const std::string bin = dir_ + "/special.bin";
    std::filesystem::remove(bin);
    ASSERT_EQ(mkfifo(bin.c_str(), 0600), 0);
    EXPECT_FALSE(fifoWasOpenedDuring(bin, [&] { error = expectInputError([&] { gusuku::loadGltf(path, {}); }); }));
    EXPECT_EQ(error.field(), "buffers[0].uri");
    EXPECT_TRUE(error.problem().find("FIFO") != std::string::npos) << error.what();
    std::filesystem::remove(bin);
    std::filesystem::create_symlink("/dev/zero", bin);
    error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_EQ(error.problem(), "\"special.bin\" is a character device, not a regular file; not read");
    std::filesystem::remove(bin);
    std::filesystem::create_directory(bin);
    error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_EQ(error.problem(), "\"special.bin\" is a directory, not a regular file; not read");

    // The glTF file itself.
    const std::string fifo_gltf = dir_ + "/scene_fifo.gltf";
    ASSERT_EQ(mkfifo(fifo_gltf.c_str(), 0600), 0);
    EXPECT_FALSE(fifoWasOpenedDuring(fifo_gltf, [&] { error = expectInputError([&] { gusuku::loadGltf(fifo_gltf, {}); }); }));
    EXPECT_EQ(error.what(), fifo_gltf + ": is a FIFO (named pipe), not a regular file; not read");
}

// Two nodes per level, each with both nodes of the next level as children: 2^24 paths reach the last level, whose
// nodes hold one triangle each. The file is under 3 KB; expanded it would be 16,777,216 triangles (8.6 GB and
// std::bad_alloc before the limit). It must be refused from the counts alone, before anything is expanded.
TEST_F(GltfTest, SharedChildrenThatExpandPastTheLimitAreRefusedBeforeExpansion) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    constexpr int kLevels = 24;
    for (int level = 0; level < kLevels; ++level) {
        for (int twin = 0; twin < 2; ++twin) {
            json node = json::object();
            if (level + 1 < kLevels)
                node["children"] = {2 * (level + 1), 2 * (level + 1) + 1};
            else
                node["mesh"] = mesh;
            builder.addNode(node);
        }
    }
    builder.setScene({0, 1});
    const std::string path = builder.write(dir_, "dag");
    EXPECT_LT(std::filesystem::file_size(path), 3000u);
    const auto start = std::chrono::steady_clock::now();
    const InputError error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    EXPECT_EQ(error.field(), "nodes");
    EXPECT_EQ(error.problem(), "the scene expands to 16777216 instanced triangles, above the limit 4194304 (a node "
                               "used by several parents repeats its whole subtree); refused before expanding");

    // The same shape without meshes still visits 2^25 nodes: refused by the node limit.
    for (json& node : builder.document()["nodes"]) node.erase("mesh");
    builder.document()["nodes"][0]["mesh"] = mesh;
    const InputError nodes_error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "dag_nodes"), {}); });
    EXPECT_TRUE(nodes_error.problem().find("33554430 node instances, above the limit 1048576") != std::string::npos)
        << nodes_error.what();

    // Below the limits the shared subtree is expanded: 2 levels -> 4 instances of the triangle.
    GltfBuilder small;
    const int small_mesh = small.addTriangleMesh(kTriangle);
    small.addNode({{"children", {2, 3}}});
    small.addNode({{"children", {2, 3}}});
    small.addNode({{"mesh", small_mesh}});
    small.addNode({{"mesh", small_mesh}});
    small.setScene({0, 1});
    EXPECT_EQ(gusuku::loadGltf(small.write(dir_, "dag_small"), {}).triangleCount(), 4u);
}

TEST_F(GltfTest, NonFiniteTransformsAndPositionsBeyondFloatAreRefused) {
    // A translation of 1e39 is a finite double but no float: the vertex would become infinity.
    GltfBuilder far;
    const int far_mesh = far.addTriangleMesh(kTriangle);
    far.setScene({far.addNode({{"mesh", far_mesh}, {"translation", {1e39, 0, 0}}})});
    InputError error = expectInputError([&] { gusuku::loadGltf(far.write(dir_, "far"), {}); });
    EXPECT_EQ(error.field(), "meshes[0].primitives[0].attributes.POSITION");
    EXPECT_EQ(error.problem(), "vertex 0 lies beyond float range after its node transform");

    // Two scales of 1e200 compose to infinity in double.
    GltfBuilder huge;
    const int huge_mesh = huge.addTriangleMesh(kTriangle);
    const int child = huge.addNode({{"mesh", huge_mesh}, {"scale", {1e200, 1e200, 1e200}}});
    huge.setScene({huge.addNode({{"children", {child}}, {"scale", {1e200, 1e200, 1e200}}})});
    error = expectInputError([&] { gusuku::loadGltf(huge.write(dir_, "huge"), {}); });
    EXPECT_EQ(error.field(), "nodes[0]");
    EXPECT_TRUE(error.problem().find("not finite") != std::string::npos) << error.what();

    // A literal that overflows a double (1e999) in a matrix: refused on one line, wherever the parser stops it.
    GltfBuilder overflow;
    const int overflow_mesh = overflow.addTriangleMesh(kTriangle);
    overflow.setScene({overflow.addNode({{"mesh", overflow_mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 7, 0, 0, 1}}})});
    const std::string path = overflow.write(dir_, "overflow");
    std::string text = gusuku::readWholeFile(path);
    const size_t seven = text.find("7,");
    ASSERT_NE(seven, std::string::npos);
    text.replace(seven, 1, "1e999");
    gusuku::writeBytesAtomically(path, text.data(), text.size());
    error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_TRUE(isOneLine(error.what())) << error.what();
}

TEST_F(GltfTest, EmissionBeyondFloatRangeIsRefused) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle, {}, {}, 0);
    builder.document()["materials"] = {{{"name", "glow"}, {"emissiveFactor", {1e39, 0, 0}}}};
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "glow"), {}); });
    EXPECT_EQ(error.field(), "materials[0].emissiveFactor[0]");
    EXPECT_EQ(error.problem(), "1e+39 is beyond float range");
    // Within float range but above the radiance limit (gusuku/assets/image.h kMaxRadiance), and negative.
    builder.document()["materials"][0]["emissiveFactor"] = {0, 1e20, 0};
    EXPECT_EQ(expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "glow"), {}); }).problem(),
              "1e+20 is above the limit 1e+15");
    builder.document()["materials"][0]["emissiveFactor"] = {0, 0, -1};
    EXPECT_EQ(expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "glow"), {}); }).field(),
              "materials[0].emissiveFactor[2]");
}

// alphaMode (issue 21 item 3): OPAQUE (the default) ignores alpha; MASK cuts at alphaCutoff (default 0.5); BLEND
// is read as MASK with a warning that says so; anything else, or a cutoff outside [0, 1], is refused by field.
TEST_F(GltfTest, AlphaModeMaskAndCutoffAreReadAndBlendIsMaskWithWarning) {
    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0, 9, 0, 0, 10, 0, 0, 9, 1, 0,
                                              12, 0, 0, 13, 0, 0, 12, 1, 0});
    builder.document()["meshes"][0]["primitives"] = json::array();
    for (int m = 0; m < 4; ++m)  // one primitive a material, each on its own triangle of the same positions
        builder.document()["meshes"][0]["primitives"].push_back(
            {{"attributes", {{"POSITION", 0}}}, {"indices", builder.addAccessorOf(std::vector<uint32_t>{
                                                   uint32_t(3 * m), uint32_t(3 * m + 1), uint32_t(3 * m + 2)},
                                                   kUnsignedInt, "SCALAR", 1)}, {"material", m}});
    builder.document()["materials"] = {{{"name", "wall"}},
                                       {{"name", "leaves"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.3}},
                                       {{"name", "fence"}, {"alphaMode", "MASK"}},
                                       {{"name", "thatch"}, {"alphaMode", "BLEND"}, {"alphaCutoff", 0.75}}};
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    std::vector<std::string> warnings;
    const TriangleMesh loaded = gusuku::loadGltf(builder.write(dir_, "alpha"), {}, &warnings);
    ASSERT_EQ(loaded.materials.size(), 4u);
    EXPECT_FALSE(loaded.materials[0].alpha_masked);
    EXPECT_TRUE(loaded.materials[1].alpha_masked);
    EXPECT_EQ(loaded.materials[1].alpha_cutoff, 0.3f);
    EXPECT_TRUE(loaded.materials[2].alpha_masked);
    EXPECT_EQ(loaded.materials[2].alpha_cutoff, 0.5f);
    EXPECT_TRUE(loaded.materials[3].alpha_masked);
    EXPECT_EQ(loaded.materials[3].alpha_cutoff, 0.75f);
    int blend_warnings = 0;
    for (const std::string& warning : warnings)
        blend_warnings += warning.find("materials[3].alphaMode: BLEND is treated as MASK") != std::string::npos;
    EXPECT_EQ(blend_warnings, 1) << "one warning names the BLEND material and says it is read as MASK";
    EXPECT_EQ(warnings.size(), 1u);

    builder.document()["materials"][1]["alphaMode"] = "CUTOUT";
    InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "alpha"), {}); });
    EXPECT_EQ(error.field(), "materials[1].alphaMode");
    EXPECT_EQ(error.problem(), "\"CUTOUT\" is not OPAQUE, MASK or BLEND");
    builder.document()["materials"][1]["alphaMode"] = "MASK";
    builder.document()["materials"][1]["alphaCutoff"] = -0.5;
    error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "alpha"), {}); });
    EXPECT_EQ(error.field(), "materials[1].alphaCutoff");
    EXPECT_EQ(error.problem(), "-0.5 is not a number in [0, 1]");
}

// alphaCutoff and alphaMode of the wrong JSON type (issue 39 item 9): tinygltf read them as absent (the default
// cutoff 0.5, OPAQUE) without a word; each is refused naming the material's field and the type found.
TEST_F(GltfTest, AlphaCutoffOrAlphaModeOfTheWrongJsonTypeIsRefusedByField) {
    const std::vector<std::pair<json, std::string>> cutoffs = {
        {"0.3", "is a string"}, {true, "is a boolean"}, {json::array({0.3}), "is an array"}, {nullptr, "is null"}};
    for (const auto& [cutoff, type] : cutoffs) {
        GltfBuilder builder;
        builder.document()["materials"] = {{{"name", "wall"}}, {{"alphaMode", "MASK"}, {"alphaCutoff", cutoff}}};
        builder.setScene({builder.addNode({{"mesh", builder.addTriangleMesh(kTriangle, {}, {}, 1)}})});
        const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "cutoff"), {}); });
        EXPECT_EQ(error.field(), "materials[1].alphaCutoff") << cutoff.dump();
        EXPECT_EQ(error.problem(), type + ", not a number in [0, 1]") << cutoff.dump();
    }
    GltfBuilder builder;
    builder.document()["materials"] = {{{"alphaMode", 5}}};
    builder.setScene({builder.addNode({{"mesh", builder.addTriangleMesh(kTriangle, {}, {}, 0)}})});
    const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "mode"), {}); });
    EXPECT_EQ(error.field(), "materials[0].alphaMode");
    EXPECT_EQ(error.problem(), "is a number, not \"OPAQUE\", \"MASK\" or \"BLEND\"");
}

// A NaN or infinite texture coordinate (issue 39 item 10) is the glTF's fault, named by its attribute and
// accessor, as a NaN position is: found later, the bake blamed its output folder.
TEST_F(GltfTest, NonFiniteTexcoordIsRefusedNamingTheAccessor) {
    for (const char* attribute : {"TEXCOORD_0", "TEXCOORD_1"}) {
        for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
            GltfBuilder builder;
            const int mesh = builder.addTriangleMesh(kTriangle);
            const int uvs = builder.addFloats({0.0f, 0.0f, 1.0f, 0.0f, 0.0f, bad}, "VEC2", 2);
            builder.document()["meshes"][0]["primitives"][0]["attributes"][attribute] = uvs;
            builder.setScene({builder.addNode({{"mesh", mesh}})});
            const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "uv"), {}); });
            EXPECT_EQ(error.field(), std::string("meshes[0].primitives[0].attributes.") + attribute);
            EXPECT_EQ(error.problem(), "accessor " + std::to_string(uvs) + ", vertex 2 is " +
                                           (std::isnan(bad) ? "NaN" : "infinite"));
        }
    }
}

TEST_F(GltfTest, RequiredExtensionsAreNamedAsUnsupported) {
    for (const char* extension : {"KHR_draco_mesh_compression", "KHR_texture_basisu", "KHR_materials_variants"}) {
        GltfBuilder builder;
        const int mesh = builder.addTriangleMesh(kTriangle);
        builder.setScene({builder.addNode({{"mesh", mesh}})});
        builder.document()["extensionsUsed"] = {extension};
        builder.document()["extensionsRequired"] = {extension};
        const InputError error = expectInputError([&] { gusuku::loadGltf(builder.write(dir_, "ext"), {}); });
        EXPECT_EQ(error.field(), "extensionsRequired[0]");
        EXPECT_NE(error.problem().find(std::string("requires ") + (std::string(extension) == "KHR_materials_variants" ? "the extension " : "") + extension + ", which this loader does not support"), std::string::npos) << error.what();
    }
    // A meshopt-compressed file: its buffer has no uri, which tinygltf alone reports as a broken buffer.
    const std::string path = dir_ + "/meshopt.gltf";
    const std::string text = R"({"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_meshopt_compression"],
        "extensionsRequired": ["EXT_meshopt_compression"], "buffers": [{"byteLength": 1200}]})";
    gusuku::writeBytesAtomically(path, text.data(), text.size());
    const InputError error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_EQ(error.problem(), "the file requires EXT_meshopt_compression, which this loader does not support: its "
                               "meshes are compressed; export the glTF without mesh compression");
}

TEST_F(GltfTest, LibraryErrorsBecomeOneLine) {
    // Syntax error (nlohmann's message without its exception id), a missing buffer file (tinygltf's two lines).
    const std::string corrupt = dir_ + "/corrupt_line.gltf";
    const std::string text = "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {";
    gusuku::writeBytesAtomically(corrupt, text.data(), text.size());
    InputError error = expectInputError([&] { gusuku::loadGltf(corrupt, {}); });
    EXPECT_TRUE(isOneLine(error.what())) << error.what();

    GltfBuilder builder;
    const int mesh = builder.addTriangleMesh(kTriangle);
    builder.setScene({builder.addNode({{"mesh", mesh}})});
    const std::string path = builder.write(dir_, "nobin");
    std::filesystem::remove(dir_ + "/nobin.bin");
    error = expectInputError([&] { gusuku::loadGltf(path, {}); });
    EXPECT_TRUE(isOneLine(error.what())) << error.what();
    EXPECT_NE(error.problem().find("nobin.bin"), std::string::npos) << error.what();

    // An accessor without a bufferView (all zeros) declares a count no file bytes bound: limited, not allocated.
    GltfBuilder zeros;
    const int zeros_mesh = zeros.addTriangleMesh(kTriangle);
    zeros.document()["accessors"].push_back({{"componentType", kFloat}, {"count", 4000000000u}, {"type", "VEC3"}});
    zeros.document()["meshes"][zeros_mesh]["primitives"][0]["attributes"]["NORMAL"] = 1;
    zeros.setScene({zeros.addNode({{"mesh", zeros_mesh}})});
    error = expectInputError([&] { gusuku::loadGltf(zeros.write(dir_, "zeros"), {}); });
    EXPECT_NE(error.problem().find("4000000000 elements without a bufferView, above the limit"), std::string::npos)
        << error.what();
}

// Survey meshes in PLY and OBJ (gusuku/assets/survey_mesh.h). Each file is written here byte by byte, so the
// expected positions, fan triangles and colours are the values the test wrote, not a previous run's output.
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"
#include "mini_site.h"

namespace {

using gusuku::InputError;
using gusuku::SurveyMesh;
using gusuku::TriangleMesh;

// A quad (0 1 2 3) and a triangle (1 4 2): the quad's fan is (0 1 2), (0 2 3).
const glm::dvec3 kPositions[5] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}, {4, 1, 0.5}};
const unsigned char kColours[5][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {128, 128, 128}, {255, 255, 255}};
const uint32_t kExpectedTriangles[9] = {0, 1, 2, 0, 2, 3, 1, 4, 2};

enum class Encoding { Ascii, LittleEndian, BigEndian };

template <typename T>
void appendValue(std::string& bytes, T value, Encoding encoding) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (encoding == Encoding::BigEndian)
        for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    bytes.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

/// The quad-and-triangle mesh as PLY: float x y z, optional uchar colours, uchar/int face lists.
std::string plyText(Encoding encoding, bool with_colours) {
    const char* format = encoding == Encoding::Ascii          ? "ascii"
                         : encoding == Encoding::LittleEndian ? "binary_little_endian"
                                                              : "binary_big_endian";
    std::string text = std::string("ply\nformat ") + format + " 1.0\ncomment written by the test\nelement vertex 5\n" +
                       "property float x\nproperty float y\nproperty float z\n";
    if (with_colours) text += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    text += "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {1, 4, 2}};
    for (int v = 0; v < 5; ++v) {
        if (encoding == Encoding::Ascii) {
            text += std::to_string(float(kPositions[v].x)) + " " + std::to_string(float(kPositions[v].y)) + " " +
                    std::to_string(float(kPositions[v].z));
            if (with_colours)
                for (int k = 0; k < 3; ++k) text.append(" ").append(std::to_string(int(kColours[v][k])));
            text += "\n";
        } else {
            for (int k = 0; k < 3; ++k) appendValue(text, float(kPositions[v][k]), encoding);
            if (with_colours)
                for (int k = 0; k < 3; ++k) appendValue(text, kColours[v][k], encoding);
        }
    }
    for (const std::vector<int>& face : faces) {
        if (encoding == Encoding::Ascii) {
            text += std::to_string(face.size());
            for (int index : face) text.append(" ").append(std::to_string(index));
            text += "\n";
        } else {
            appendValue(text, uint8_t(face.size()), encoding);
            for (int index : face) appendValue(text, int32_t(index), encoding);
        }
    }
    return text;
}

class SiteMeshFormatsTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = (std::filesystem::temp_directory_path() /
                ("gusuku_site_mesh_formats_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                 ::testing::UnitTest::GetInstance()->current_test_info()->name()))
                   .string();
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& bytes) {
        const std::string path = dir_ + "/" + name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    }

    std::string dir_;
};

/// The sRGB-encoded byte's linear value (IEC 61966-2-1 table values, not this project's formula).
float linearOfByte(unsigned char byte) {
    if (byte == 0) return 0.0f;
    if (byte == 255) return 1.0f;
    EXPECT_EQ(byte, 128);
    return 0.2158605f;
}

/// Corner k of triangle t equals the file's vertex kExpectedTriangles[3t + k] after `enu_from_model`.
void expectQuadAndTriangle(const TriangleMesh& mesh, const glm::dmat4& enu_from_model = glm::dmat4(1.0)) {
    ASSERT_EQ(mesh.triangleCount(), 3u);
    ASSERT_EQ(mesh.triangle_material.size(), 3u);
    ASSERT_FALSE(mesh.materials.empty());
    for (size_t corner = 0; corner < 9; ++corner) {
        const glm::dvec3 expected = glm::dvec3(enu_from_model * glm::dvec4(kPositions[kExpectedTriangles[corner]], 1.0));
        const glm::vec3 actual = mesh.positions[mesh.indices[corner]];
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], 1e-5) << "corner " << corner << " axis " << k;
    }
    // All three triangles lie in or face up (+z) in the model's frame: counter-clockwise seen from above.
    for (size_t t = 0; t < 3; ++t) EXPECT_GT(mesh.normals[mesh.indices[3 * t]].z, 0.5f) << "triangle " << t;
}

void expectColours(const SurveyMesh& survey) {
    ASSERT_EQ(survey.vertex_colours.size(), survey.mesh.vertexCount());
    for (size_t corner = 0; corner < 9; ++corner)
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(survey.vertex_colours[survey.mesh.indices[corner]][k],
                        linearOfByte(kColours[kExpectedTriangles[corner]][k]), 1e-5)
                << "corner " << corner << " channel " << k;
}

InputError expectInputError(const std::function<void()>& action) {
    try {
        action();
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << error.what();
        return error;
    }
    ADD_FAILURE() << "no InputError thrown";
    return InputError("", "", "");
}

TEST_F(SiteMeshFormatsTest, PlyInEveryEncodingWithAndWithoutColours) {
    for (Encoding encoding : {Encoding::Ascii, Encoding::LittleEndian, Encoding::BigEndian}) {
        for (bool with_colours : {false, true}) {
            SCOPED_TRACE("encoding " + std::to_string(int(encoding)) + (with_colours ? " with colours" : " plain"));
            const std::string path = write("mesh.ply", plyText(encoding, with_colours));
            const SurveyMesh survey = gusuku::loadPlyMesh(path, glm::dmat4(1.0));
            expectQuadAndTriangle(survey.mesh);
            if (with_colours) expectColours(survey);
            else EXPECT_TRUE(survey.vertex_colours.empty());
        }
    }
}

TEST_F(SiteMeshFormatsTest, WindowsLineEndingsAreRead) {
    std::string ply = plyText(Encoding::Ascii, true), obj = "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nv 4 1 0.5\nf 1 2 3 4\nf 2 5 3\n";
    for (std::string* text : {&ply, &obj}) {
        std::string crlf;
        for (char c : *text) {
            if (c == '\n') crlf.push_back('\r');
            crlf.push_back(c);
        }
        *text = crlf;
    }
    const SurveyMesh from_ply = gusuku::loadPlyMesh(write("crlf.ply", ply), glm::dmat4(1.0));
    expectQuadAndTriangle(from_ply.mesh);
    expectColours(from_ply);
    expectQuadAndTriangle(gusuku::loadObjMesh(write("crlf.obj", obj), glm::dmat4(1.0)).mesh);
}

TEST_F(SiteMeshFormatsTest, SiteTransformAppliesToPlyAndObj) {
    // sfm_mesh's similarity: scale 2, a quarter turn about up, then 10 m east.
    const glm::dmat4 enu_from_model = glm::translate(glm::dmat4(1.0), glm::dvec3(10, 0, 0)) *
                                      glm::rotate(glm::dmat4(1.0), M_PI / 2, glm::dvec3(0, 0, 1)) *
                                      glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
    gusuku::GltfLoadOptions options;
    options.enu_from_model = enu_from_model;
    expectQuadAndTriangle(gusuku::loadSiteMesh(write("mesh.ply", plyText(Encoding::LittleEndian, false)), options),
                          enu_from_model);
    expectQuadAndTriangle(gusuku::loadSiteMesh(write("mesh.obj", "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nv 4 1 0.5\n"
                                                                 "f 1 2 3 4\nf 2 5 3\n"),
                                               options),
                          enu_from_model);
}

TEST_F(SiteMeshFormatsTest, ObjFaceFormsNegativeIndicesAndColours) {
    const std::string text =
        "# from a photogrammetry tool\nmtllib site.mtl\no site\ng ground\ns off\nusemtl stone\n"
        "v 0 0 0 1 0 0\nv 2 0 0 0 1 0\nv 2 3 0 0 0 1\nv 0 3 0 0.5019608 0.5019608 0.5019608\n"
        "vt 0 0\nvt 1 0\nvn 0 0 1\n"
        "f 1/1 2/2/1 3//1 4\n"           // the four face forms, one per corner
        "v 4 1 0.5 1 1 1\n"
        "f -4/1 -1//1 -3/2/1\n";         // 2 5 3 relative to the five vertices read so far
    const SurveyMesh survey = gusuku::loadObjMesh(write("mesh.obj", text), glm::dmat4(1.0));
    expectQuadAndTriangle(survey.mesh);
    expectColours(survey);
}

TEST_F(SiteMeshFormatsTest, MaterialTakesTheAreaWeightedMeanColour) {
    // Two triangles: a red one of area 1 and a white one of area 3 -> (1*1 + 3*1, 3, 3) / 4 = (1, 0.75, 0.75).
    const std::string text = "v 0 0 0 1 0 0\nv 1 0 0 1 0 0\nv 0 2 0 1 0 0\n"
                             "v 5 0 0 1 1 1\nv 8 0 0 1 1 1\nv 5 2 0 1 1 1\nf 1 2 3\nf 4 5 6\n";
    const TriangleMesh mesh = gusuku::loadObjMesh(write("mesh.obj", text), glm::dmat4(1.0)).mesh;
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_NEAR(mesh.materials[0].base_color_factor.r, 1.0f, 1e-6);
    EXPECT_NEAR(mesh.materials[0].base_color_factor.g, 0.75f, 1e-6);
    EXPECT_NEAR(mesh.materials[0].base_color_factor.b, 0.75f, 1e-6);
}

TEST_F(SiteMeshFormatsTest, GlbOfTheSameMeshGivesTheSameTriangles) {
    const TriangleMesh from_ply = gusuku::loadPlyMesh(write("mesh.ply", plyText(Encoding::Ascii, false)), glm::dmat4(1.0)).mesh;
    const std::string glb = dir_ + "/mesh.glb";
    gusuku::writeGlb(glb, from_ply, glm::dmat4(1.0));
    const TriangleMesh from_glb = gusuku::loadGltf(glb, {});
    expectQuadAndTriangle(from_glb);
    ASSERT_EQ(from_glb.triangleCount(), from_ply.triangleCount());
    for (size_t corner = 0; corner < from_ply.indices.size(); ++corner)
        EXPECT_EQ(from_glb.positions[from_glb.indices[corner]], from_ply.positions[from_ply.indices[corner]]);
}

TEST_F(SiteMeshFormatsTest, BadPlyIsOneLineNamingTheElement) {
    const std::string good = plyText(Encoding::LittleEndian, false);
    const std::string header_end = "end_header\n";
    const size_t data_start = good.find(header_end) + header_end.size();
    struct Case {
        std::string name, bytes, field, problem;
    };
    std::string out_of_range = good;
    std::memcpy(out_of_range.data() + data_start + 5 * 12 + 1 + 4, "\x07\0\0\0", 4);  // face 0's second index: 7
    std::string nan_vertex = good;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(nan_vertex.data() + data_start + 2 * 12 + 4, &nan, 4);  // vertex 2's y
    std::string lying = good;
    lying.replace(lying.find("element vertex 5"), 16, "element vertex 500000");
    std::string unknown = good;
    unknown.replace(unknown.find("binary_little_endian"), 20, "binary_middle_endian");
    const std::vector<Case> cases = {
        {"truncated", good.substr(0, good.size() - 6), "face 1", "truncated"},
        {"out_of_range", out_of_range, "face 0", "vertex_indices: vertex index 7 is out of range (the file has 5 vertices)"},
        {"nan", nan_vertex, "vertex 2", "y is nan, not a finite number"},
        {"lying", lying, "header line 4", "element vertex claims 500000 items"},
        {"unknown", unknown, "header line 2", "unknown format 'binary_middle_endian'"},
        {"not_ply", "solid cube\n", "header line 1", "not a PLY file"},
        {"ascii_nan", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
         "line 11 (vertex 1)", "y is nan, not a finite number"},
        {"point_cloud", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                        "end_header\n0 0 0\n", "header line 7", "no element face"},
    };
    for (const Case& bad : cases) {
        SCOPED_TRACE(bad.name);
        const std::string path = write(bad.name + ".ply", bad.bytes);
        const InputError error = expectInputError([&] { gusuku::loadPlyMesh(path, glm::dmat4(1.0)); });
        EXPECT_EQ(error.file(), path);
        EXPECT_EQ(error.field(), bad.field) << error.what();
        EXPECT_NE(error.problem().find(bad.problem), std::string::npos) << error.what();
    }
}

TEST_F(SiteMeshFormatsTest, BadObjIsOneLineNamingTheLine) {
    struct Case {
        std::string name, text, field, problem;
    };
    const std::vector<Case> cases = {
        {"out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4", "vertex index 4 is out of range (3 vertices so far)"},
        {"negative_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "line 4", "vertex index -4 is out of range"},
        {"nan", "v 0 0 0\nv nan 0 0\n", "line 2", "x is 'nan', not a finite number"},
        {"two_corners", "v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3", "f has 2 vertices (a face needs 3 or more)"},
        {"zero_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4", "is not a vertex index"},
        {"unknown", "v 0 0 0\ncurv 0 1 2\n", "line 2", "unknown statement 'curv'"},
        {"colour_range", "v 0 0 0 2 0 0\n", "line 1", "r is 2, outside [0, 1]"},
        {"no_faces", "v 0 0 0\n", "", "has no faces"},
    };
    for (const Case& bad : cases) {
        SCOPED_TRACE(bad.name);
        const std::string path = write(bad.name + ".obj", bad.text);
        const InputError error = expectInputError([&] { gusuku::loadObjMesh(path, glm::dmat4(1.0)); });
        EXPECT_EQ(error.file(), path);
        EXPECT_EQ(error.field(), bad.field) << error.what();
        EXPECT_NE(error.problem().find(bad.problem), std::string::npos) << error.what();
    }
}

TEST_F(SiteMeshFormatsTest, SiteJsonTakesAPlySfmMeshThroughCheck) {
    // The mini site, with the quad-and-triangle PLY as its sfm_mesh, scaled 2 and 5 m up.
    const std::string site_path = gusuku::testing::writeMiniSite(dir_);
    nlohmann::json site = nlohmann::json::parse(std::ifstream(site_path));
    write("survey.ply", plyText(Encoding::BigEndian, true));
    site["sfm_mesh"] = {{"path", "survey.ply"}, {"scale", 2}, {"rotation_wxyz", {1, 0, 0, 0}},
                        {"translation_enu_m", {0, 0, 5}}};
    std::ofstream(site_path) << site.dump(2);
    const gusuku::SiteConfig config = gusuku::loadSiteConfig(site_path);
    ASSERT_TRUE(config.sfm_mesh.has_value());
    gusuku::GltfLoadOptions options;
    options.enu_from_model = config.sfm_mesh->enuFromModel();
    expectQuadAndTriangle(gusuku::loadSiteMesh(config.sfm_mesh->path, options), options.enu_from_model);

    const gusuku::testing::CommandResult result = gusuku::testing::runBakeCommand({"check", site_path}, dir_);
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    // 3 triangles, one vertex per corner; z from 5 to 5 + 2 * 0.5.
    EXPECT_NE(result.stdout_text.find("sfm mesh: " + config.sfm_mesh->path + "\n  3 triangles, 9 vertices"),
              std::string::npos) << result.stdout_text;

    site["sfm_mesh"]["path"] = "survey.stl";
    write("survey.stl", "solid\n");
    std::ofstream(site_path) << site.dump(2);
    const InputError error = expectInputError([&] { gusuku::loadSiteConfig(site_path); });
    EXPECT_EQ(error.field(), "/sfm_mesh/path");
    EXPECT_EQ(error.problem(), "\"survey.stl\" does not end in .gltf or .glb or .ply or .obj") << error.what();
}

}  // namespace

#pragma once
// Survey meshes as photogrammetry tools write them: PLY (ASCII, binary little or big endian) and Wavefront OBJ,
// read by the project's own readers (fuzzed: tests/fuzz/fuzz_ply_mesh.cpp, fuzz_obj_mesh.cpp) into the same
// TriangleMesh the glTF path gives for a site mesh without normals: positions in ENU, one vertex per triangle
// corner with the triangle's flat normal, uv0 zeros, one material.
//
// Vertex colours (PLY red/green/blue as uchar or float, OBJ "v x y z r g b") are sRGB-encoded by convention; they
// are kept per corner, linear, in SurveyMesh::vertex_colours. TriangleMesh has no per-vertex colour, so the
// material's base colour becomes their area-weighted mean (the site mesh's albedo for the bake's bounce light);
// without colours it stays white, as a glTF primitive without a material.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "gusuku/assets/gltf_loader.h"
#include "gusuku/maths/mesh.h"

namespace gusuku {

struct SurveyMesh {
    TriangleMesh mesh;
    /// Linear RGB, one per vertex of `mesh` (per triangle corner); empty when the file has no colours.
    std::vector<glm::vec3> vertex_colours;
};

/// What a reader hands to finishSurveyMesh: the file's own vertices and its polygons fan-triangulated
/// (polygon a b c d -> triangles a b c, a c d), indices already checked against positions.
struct SurveyMeshData {
    std::vector<glm::dvec3> positions;     ///< model coordinates, finite
    std::vector<glm::vec3> colours;        ///< sRGB-encoded in [0, 1], one per position, or empty
    std::vector<uint32_t> triangle_indices;
};

/// Triangles a survey mesh may hold: the glTF loader's limit (gusuku/assets/gltf_loader.h), for the same memory.
constexpr uint64_t kMaxSurveyTriangles = kMaxGltfInstancedTriangles;

/// Reads a .ply file. Bad input throws InputError(path, "line 7" or "vertex 12" or "face 3", problem).
SurveyMesh loadPlyMesh(const std::string& path, const glm::dmat4& enu_from_model);
/// Reads a .obj file (v with optional colours, f; vt, vn, vp, usemtl, mtllib, o, g, s, l, p ignored).
SurveyMesh loadObjMesh(const std::string& path, const glm::dmat4& enu_from_model);

/// True when `path` ends in .ply or .obj (any case).
bool isSurveyMeshPath(const std::string& path);
/// The site mesh by its extension: .ply and .obj through the readers above, anything else through loadGltf.
TriangleMesh loadSiteMesh(const std::string& path, const GltfLoadOptions& options,
                          std::vector<std::string>* warnings = nullptr);

/// Positions into ENU, corners un-shared with flat normals, colours linearised and averaged into the material.
/// `path` names the file in errors (a vertex beyond float range after the transform).
SurveyMesh finishSurveyMesh(const std::string& path, SurveyMeshData data, const glm::dmat4& enu_from_model);

/// The whole file as bytes; InputError when it is no regular file or cannot be read.
std::string readSurveyFile(const std::string& path);

/// Appends a polygon (3 or more corners) to the triangles as a fan: a b c d -> a b c, a c d, exact for the convex
/// polygons meshing tools write. False, appending nothing, when the mesh would pass kMaxSurveyTriangles (the
/// reader names where in its file).
bool appendPolygonFan(std::vector<uint32_t>& triangle_indices, const std::vector<uint32_t>& polygon);

}  // namespace gusuku

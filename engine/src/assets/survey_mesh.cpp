#include "gusuku/assets/survey_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "gusuku/formats/input_error.h"
#include "regular_file.h"

namespace gusuku {

namespace {

std::string lowercaseExtensionOf(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string extension = path.substr(dot);
    for (char& c : extension) c = char(std::tolower((unsigned char)c));
    return extension;
}

/// The sRGB transfer function's inverse (IEC 61966-2-1): camera colours are stored encoded.
float linearFromSrgb(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

bool isSurveyMeshPath(const std::string& path) {
    const std::string extension = lowercaseExtensionOf(path);
    return extension == ".ply" || extension == ".obj";
}

bool appendPolygonFan(std::vector<uint32_t>& triangle_indices, const std::vector<uint32_t>& polygon) {
    if (polygon.size() < 3 || triangle_indices.size() / 3 + (polygon.size() - 2) > kMaxSurveyTriangles) return false;
    for (size_t k = 1; k + 1 < polygon.size(); ++k)
        triangle_indices.insert(triangle_indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
    return true;
}

std::string readSurveyFile(const std::string& path) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) throw InputError(path, "", problem);
    std::ifstream stream(path, std::ios::binary);
    if (!stream) throw InputError(path, "", "cannot be opened");
    std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    if (stream.bad()) throw InputError(path, "", "cannot be read");
    return bytes;
}

SurveyMesh finishSurveyMesh(const std::string& path, SurveyMeshData data, const glm::dmat4& enu_from_model) {
    if (data.triangle_indices.empty()) throw InputError(path, "", "has no faces (a site mesh needs triangles)");
    // A mirroring transform turns counter-clockwise faces clockwise; swap two corners to keep them front faces.
    const bool flip_winding = glm::determinant(glm::dmat3(enu_from_model)) < 0.0;
    std::vector<glm::vec3> enu_positions(data.positions.size());
    for (size_t i = 0; i < data.positions.size(); ++i) {
        const glm::dvec3 p = glm::dvec3(enu_from_model * glm::dvec4(data.positions[i], 1.0));
        enu_positions[i] = glm::vec3(p);
        if (!std::isfinite(enu_positions[i].x) || !std::isfinite(enu_positions[i].y) ||
            !std::isfinite(enu_positions[i].z))
            throw InputError(path, "vertex " + std::to_string(i), "lies beyond float range after sfm_mesh's transform");
    }

    SurveyMesh survey;
    TriangleMesh& mesh = survey.mesh;
    const size_t corner_count = data.triangle_indices.size();
    mesh.positions.reserve(corner_count);
    mesh.normals.reserve(corner_count);
    mesh.indices.reserve(corner_count);
    const bool has_colours = !data.colours.empty();
    if (has_colours) survey.vertex_colours.reserve(corner_count);
    glm::dvec3 weighted_colour_sum(0.0);
    double area_sum = 0.0;
    for (size_t t = 0; t + 2 < corner_count; t += 3) {
        uint32_t corner[3] = {data.triangle_indices[t], data.triangle_indices[t + 1], data.triangle_indices[t + 2]};
        if (flip_winding) std::swap(corner[1], corner[2]);
        const glm::vec3 a = enu_positions[corner[0]], b = enu_positions[corner[1]], c = enu_positions[corner[2]];
        const glm::dvec3 cross = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
        const double twice_area = glm::length(cross);
        // A degenerate triangle has no facing; it is kept (its corners may matter to a neighbour) facing up.
        const glm::vec3 normal = twice_area > 0.0 && std::isfinite(twice_area) ? glm::vec3(cross / twice_area)
                                                                                 : glm::vec3(0.0f, 0.0f, 1.0f);
        for (uint32_t vertex : corner) {
            mesh.indices.push_back(uint32_t(mesh.positions.size()));
            mesh.positions.push_back(enu_positions[vertex]);
            mesh.normals.push_back(normal);
            if (has_colours) {
                const glm::vec3 encoded = data.colours[vertex];
                const glm::vec3 linear(linearFromSrgb(encoded.r), linearFromSrgb(encoded.g), linearFromSrgb(encoded.b));
                survey.vertex_colours.push_back(linear);
                if (std::isfinite(twice_area)) weighted_colour_sum += glm::dvec3(linear) * (twice_area / 6.0);
            }
        }
        if (std::isfinite(twice_area)) area_sum += twice_area / 2.0;
    }
    mesh.uv0.assign(mesh.positions.size(), glm::vec2(0.0f));
    mesh.triangle_material.assign(mesh.indices.size() / 3, 0);
    Material material;
    material.name = "survey mesh";
    if (has_colours && area_sum > 0.0) {
        // Each corner carries a third of its triangle's area: the mean over the surface, not over the vertices.
        const glm::dvec3 mean = weighted_colour_sum / area_sum;
        material.base_color_factor = glm::vec4(glm::vec3(mean), 1.0f);
        material.name = "survey mesh (mean vertex colour)";
    }
    mesh.materials.push_back(material);
    return survey;
}

TriangleMesh loadSiteMesh(const std::string& path, const GltfLoadOptions& options, std::vector<std::string>* warnings) {
    const std::string extension = lowercaseExtensionOf(path);
    if (extension == ".ply") return loadPlyMesh(path, options.enu_from_model).mesh;
    if (extension == ".obj") return loadObjMesh(path, options.enu_from_model).mesh;
    return loadGltf(path, options, warnings);
}

}  // namespace gusuku

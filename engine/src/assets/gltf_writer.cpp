// TriangleMesh -> .glb (gusuku/assets/gltf_loader.h, writeGlb): one mesh, one primitive per used material, textures
// embedded as sRGB PNG. Each primitive carries only the vertices its triangles use, so that loading the file
// back gives the same vertex count as was written.
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <tiny_gltf.h>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/glb_positions.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"

namespace gusuku {

namespace {

// Appends to the single binary buffer, keeping every bufferView 4-byte aligned (glTF requires accessor
// offsets aligned to their component size).
class BinaryBuilder {
public:
    explicit BinaryBuilder(tinygltf::Model& model) : model_(model) {
        model_.buffers.emplace_back();
    }

    int addBufferView(const void* bytes, size_t byte_count, int target) {
        std::vector<unsigned char>& data = model_.buffers[0].data;
        while (data.size() % 4 != 0) data.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = data.size();
        view.byteLength = byte_count;
        view.target = target;
        const auto* first = static_cast<const unsigned char*>(bytes);
        data.insert(data.end(), first, first + byte_count);
        model_.bufferViews.push_back(view);
        return int(model_.bufferViews.size() - 1);
    }

    template <typename Vector>
    int addFloatAccessor(const std::vector<Vector>& values, int type, bool with_bounds) {
        tinygltf::Accessor accessor;
        accessor.bufferView = addBufferView(values.data(), values.size() * sizeof(Vector), TINYGLTF_TARGET_ARRAY_BUFFER);
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        accessor.count = values.size();
        accessor.type = type;
        if (with_bounds && !values.empty()) {  // POSITION requires min and max
            Vector low = values[0], high = values[0];
            for (const Vector& v : values)
                for (int c = 0; c < Vector::length(); ++c) {
                    low[c] = std::min(low[c], v[c]);
                    high[c] = std::max(high[c], v[c]);
                }
            for (int c = 0; c < Vector::length(); ++c) {
                accessor.minValues.push_back(low[c]);
                accessor.maxValues.push_back(high[c]);
            }
        }
        model_.accessors.push_back(accessor);
        return int(model_.accessors.size() - 1);
    }

    int addIndexAccessor(const std::vector<uint32_t>& indices) {
        tinygltf::Accessor accessor;
        accessor.bufferView = addBufferView(indices.data(), indices.size() * sizeof(uint32_t),
                                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        accessor.count = indices.size();
        accessor.type = TINYGLTF_TYPE_SCALAR;
        model_.accessors.push_back(accessor);
        return int(model_.accessors.size() - 1);
    }

private:
    tinygltf::Model& model_;
};

/// One node with mesh 0 in the default scene, serialised as .glb and written atomically.
void writeSingleMeshGlb(const std::string& path, tinygltf::Model& model) {
    tinygltf::Node node;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    std::ostringstream glb;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, glb, false, true))
        throw std::runtime_error(path + ": tinygltf could not serialise the mesh");
    const std::string bytes = glb.str();
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

}  // namespace

void writePositionsGlb(const std::string& path, const std::vector<glm::vec3>& positions_enu,
                       const std::vector<uint32_t>& indices, const glm::dmat4& model_from_enu) {
    if (indices.size() % 3 != 0)
        throw std::invalid_argument(path + ": index count " + std::to_string(indices.size()) +
                                    " is not a multiple of 3");
    for (const uint32_t index : indices)
        if (index >= positions_enu.size())
            throw std::invalid_argument(path + ": index " + std::to_string(index) + " out of range");
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "gusuku";
    BinaryBuilder binary(model);

    std::vector<glm::vec3> positions(positions_enu.size());
    for (size_t i = 0; i < positions.size(); ++i)
        positions[i] = glm::vec3(model_from_enu * glm::dvec4(positions_enu[i], 1.0));
    std::vector<uint32_t> model_indices = indices;
    if (glm::determinant(glm::dmat3(model_from_enu)) < 0.0)
        for (size_t t = 0; t + 2 < model_indices.size(); t += 3) std::swap(model_indices[t + 1], model_indices[t + 2]);

    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = binary.addFloatAccessor(positions, TINYGLTF_TYPE_VEC3, true);
    primitive.indices = binary.addIndexAccessor(model_indices);
    tinygltf::Mesh mesh;
    mesh.name = "occluder";
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    writeSingleMeshGlb(path, model);
}

void writeGlb(const std::string& path, const TriangleMesh& mesh, const glm::dmat4& model_from_enu) {
    if (mesh.indices.size() % 3 != 0 || mesh.triangle_material.size() != mesh.triangleCount())
        throw std::invalid_argument(path + ": inconsistent mesh (indices or triangle materials)");
    if (mesh.normals.size() != mesh.positions.size() || mesh.uv0.size() != mesh.positions.size() ||
        (mesh.has_uv1 && mesh.uv1.size() != mesh.positions.size()))
        throw std::invalid_argument(path + ": inconsistent mesh (per-vertex arrays differ in length)");

    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "gusuku";
    BinaryBuilder binary(model);

    // Textures first, so materials can point at them; each is embedded once.
    for (size_t t = 0; t < mesh.textures.size(); ++t) {
        const std::vector<unsigned char> png = encodePngSrgb(mesh.textures[t], true);
        tinygltf::Image image;
        image.name = "texture" + std::to_string(t);
        image.mimeType = "image/png";
        image.bufferView = binary.addBufferView(png.data(), png.size(), 0);
        model.images.push_back(image);
        tinygltf::Texture texture;
        texture.source = int(t);
        model.textures.push_back(texture);
    }
    for (const Material& material : mesh.materials) {
        tinygltf::Material out;
        out.name = material.name;
        const glm::vec4& f = material.base_color_factor;
        out.pbrMetallicRoughness.baseColorFactor = {f.x, f.y, f.z, f.w};
        // Diffuse surfaces only (docs/design.md 6): fully rough dielectric.
        out.pbrMetallicRoughness.metallicFactor = 0.0;
        out.pbrMetallicRoughness.roughnessFactor = 1.0;
        if (material.base_color_texture >= 0) {
            if (size_t(material.base_color_texture) >= mesh.textures.size())
                throw std::invalid_argument(path + ": material '" + material.name + "' points at a missing texture");
            out.pbrMetallicRoughness.baseColorTexture.index = material.base_color_texture;
        }
        out.emissiveFactor = {material.emissive_factor.x, material.emissive_factor.y, material.emissive_factor.z};
        out.doubleSided = material.double_sided;
        if (material.alpha_masked) {  // an opaque material keeps glTF's defaults, so its bytes are as before
            out.alphaMode = "MASK";
            out.alphaCutoff = material.alpha_cutoff;
        }
        model.materials.push_back(out);
    }

    const glm::dmat3 linear_part(model_from_enu);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear_part));
    const bool flip_winding = glm::determinant(linear_part) < 0.0;

    // Triangles grouped by material, in material order.
    std::map<uint32_t, std::vector<size_t>> triangles_of_material;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) triangles_of_material[mesh.triangle_material[t]].push_back(t);

    tinygltf::Mesh out_mesh;
    out_mesh.name = "mesh";
    for (const auto& [material, triangles] : triangles_of_material) {
        if (material >= mesh.materials.size())
            throw std::invalid_argument(path + ": triangle material " + std::to_string(material) + " does not exist");
        std::vector<glm::vec3> positions, normals;
        std::vector<glm::vec2> uv0, uv1;
        std::vector<uint32_t> indices;
        std::map<uint32_t, uint32_t> local_of_vertex;
        for (size_t t : triangles) {
            uint32_t corners[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
            if (flip_winding) std::swap(corners[1], corners[2]);
            for (uint32_t vertex : corners) {
                if (vertex >= mesh.positions.size())
                    throw std::invalid_argument(path + ": index " + std::to_string(vertex) + " out of range");
                auto [entry, inserted] = local_of_vertex.try_emplace(vertex, uint32_t(positions.size()));
                if (inserted) {
                    positions.push_back(glm::vec3(model_from_enu * glm::dvec4(mesh.positions[vertex], 1.0)));
                    glm::dvec3 n = normal_matrix * glm::dvec3(mesh.normals[vertex]);
                    const double length = glm::length(n);
                    normals.push_back(length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f, 1.0f, 0.0f));
                    uv0.push_back(mesh.uv0[vertex]);
                    if (mesh.has_uv1) uv1.push_back(mesh.uv1[vertex]);
                }
                indices.push_back(entry->second);
            }
        }
        tinygltf::Primitive primitive;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        primitive.material = int(material);
        primitive.attributes["POSITION"] = binary.addFloatAccessor(positions, TINYGLTF_TYPE_VEC3, true);
        primitive.attributes["NORMAL"] = binary.addFloatAccessor(normals, TINYGLTF_TYPE_VEC3, false);
        primitive.attributes["TEXCOORD_0"] = binary.addFloatAccessor(uv0, TINYGLTF_TYPE_VEC2, false);
        if (mesh.has_uv1) primitive.attributes["TEXCOORD_1"] = binary.addFloatAccessor(uv1, TINYGLTF_TYPE_VEC2, false);
        primitive.indices = binary.addIndexAccessor(indices);
        out_mesh.primitives.push_back(primitive);
    }
    model.meshes.push_back(out_mesh);
    writeSingleMeshGlb(path, model);
}

}  // namespace gusuku

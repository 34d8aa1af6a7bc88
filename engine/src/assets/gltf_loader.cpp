// glTF 2.0 -> one TriangleMesh in ENU (gusuku/assets/gltf_loader.h). tinygltf parses the JSON and buffers; images are
// kept encoded by a custom loader callback and decoded here through OpenImageIO (gusuku/assets/image.h), so that every
// texture goes through the same colour handling. Every index, range and value read from the file is checked:
// a bad file is an InputError naming the glTF element, never a crash.
#include "gusuku/assets/gltf_loader.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <sstream>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "one_line.h"
#include "gusuku/assets/atomic_file.h"  // kMaxInputFileBytes
#include "regular_file.h"

namespace gusuku {

glm::dmat4 enuFromGltfYUp() {
    // Columns are the images of the glTF axes: +x -> east, +y (up) -> up, +z (towards the viewer) -> south.
    glm::dmat4 enu_from_gltf(1.0);
    enu_from_gltf[0] = glm::dvec4(1.0, 0.0, 0.0, 0.0);
    enu_from_gltf[1] = glm::dvec4(0.0, 0.0, 1.0, 0.0);
    enu_from_gltf[2] = glm::dvec4(0.0, -1.0, 0.0, 0.0);
    return enu_from_gltf;
}

namespace {

// Deeper node nesting than this is taken as a corrupt (or hostile) file rather than a real scene.
constexpr int kMaxNodeDepth = 256;

// --- files tinygltf opens ----------------------------------------------------------------------------------------
// tinygltf's own FileExists opens the file (a FIFO blocks it until a writer appears) and its ReadWholeFile reads
// whatever the path names (/dev/zero never ends). These replacements look at the file's type first.

bool regularFileExists(const std::string& path, void* /*user_data*/) { return regularFileProblem(path).empty(); }

// glTF URIs are relative paths, never shell words: no expansion (older tinygltf ran wordexp on them).
std::string pathAsIs(const std::string& path, void* /*user_data*/) { return path; }

bool readRegularFile(std::vector<unsigned char>* bytes, std::string* error, const std::string& path,
                     void* /*user_data*/) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) {
        if (error) *error += problem;
        return false;
    }
    std::ifstream stream(path, std::ios::binary | std::ios::ate);
    const std::streamoff size = stream ? std::streamoff(stream.tellg()) : std::streamoff(-1);
    if (size < 0) {
        if (error) *error += "cannot be opened for reading";
        return false;
    }
    if (uint64_t(size) > kMaxInputFileBytes) {
        if (error)
            *error += "is " + std::to_string(size) + " bytes, more than the " + std::to_string(kMaxInputFileBytes) +
                      " a file read whole may have";
        return false;
    }
    bytes->resize(size_t(size));
    stream.seekg(0);
    if (size > 0 && !stream.read(reinterpret_cast<char*>(bytes->data()), size)) {
        if (error) *error += "cannot be read";
        return false;
    }
    return true;
}

bool unusedWrite(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
    if (error) *error += "the loader writes no files";
    return false;
}

// --- a look at the JSON before tinygltf reads it -------------------------------------------------------------
// Two things must be decided before tinygltf follows the file: a required extension it cannot honour (a
// meshopt-compressed buffer has no uri, which tinygltf would report as a broken buffer rather than the
// extension), and buffer or image URIs that name a FIFO, a device or a directory (refused with the element that
// names them, before anything is opened).

// The JSON chunk of a .glb (12-byte header, then chunk 0 of type "JSON"), or the whole file of a .gltf.
std::optional<std::string> gltfJsonText(const std::vector<unsigned char>& file_bytes, bool is_glb) {
    if (!is_glb) return std::string(file_bytes.begin(), file_bytes.end());
    if (file_bytes.size() < 20 || std::memcmp(file_bytes.data(), "glTF", 4) != 0) return std::nullopt;
    uint32_t chunk_length = 0;
    std::memcpy(&chunk_length, file_bytes.data() + 12, 4);
    if (std::memcmp(file_bytes.data() + 16, "JSON", 4) != 0 || chunk_length > file_bytes.size() - 20)
        return std::nullopt;
    return std::string(file_bytes.begin() + 20, file_bytes.begin() + 20 + chunk_length);
}

// RFC 3986 percent-decoding, as tinygltf applies to relative URIs.
std::string percentDecoded(const std::string& uri) {
    std::string decoded;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            decoded += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    return decoded;
}

std::string requiredExtensionProblem(const std::string& name) {
    if (name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression")
        return "the file requires " + name + ", which this loader does not support: its meshes are compressed; "
               "export the glTF without mesh compression";
    if (name == "KHR_texture_basisu")
        return "the file requires KHR_texture_basisu, which this loader does not support: its textures are "
               "KTX2/Basis; export them as PNG or JPEG";
    return "the file requires the extension " + name + ", which this loader does not support";
}

const char* jsonTypeName(const nlohmann::json& value) {
    if (value.is_null()) return "null";
    if (value.is_boolean()) return "a boolean";
    if (value.is_number()) return "a number";
    if (value.is_string()) return "a string";
    if (value.is_array()) return "an array";
    return "an object";
}

// tinygltf reads a material's alphaCutoff or alphaMode of the wrong JSON type as absent (so "0.5" or true became
// the default 0.5, and alphaMode 5 OPAQUE) without a word: the types are checked on the JSON itself.
void checkMaterialAlphaTypes(const std::string& path, const nlohmann::json& document) {
    const auto materials = document.find("materials");
    if (materials == document.end() || !materials->is_array()) return;
    for (size_t i = 0; i < materials->size(); ++i) {
        const nlohmann::json& material = (*materials)[i];
        if (!material.is_object()) continue;
        const std::string field = "materials[" + std::to_string(i) + "]";
        if (const auto cutoff = material.find("alphaCutoff"); cutoff != material.end() && !cutoff->is_number())
            throw InputError(path, field + ".alphaCutoff",
                             std::string("is ") + jsonTypeName(*cutoff) + ", not a number in [0, 1]");
        if (const auto mode = material.find("alphaMode"); mode != material.end() && !mode->is_string())
            throw InputError(path, field + ".alphaMode",
                             std::string("is ") + jsonTypeName(*mode) + ", not \"OPAQUE\", \"MASK\" or \"BLEND\"");
    }
}

void checkBeforeParsing(const std::string& path, const std::vector<unsigned char>& file_bytes, bool is_glb) {
    const std::optional<std::string> text = gltfJsonText(file_bytes, is_glb);
    if (!text) return;  // tinygltf reports a malformed container
    const nlohmann::json document = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
    if (!document.is_object()) return;  // and malformed JSON
    if (const auto required = document.find("extensionsRequired");
        required != document.end() && required->is_array())
        for (size_t i = 0; i < required->size(); ++i)
            if ((*required)[i].is_string())
                throw InputError(path, "extensionsRequired[" + std::to_string(i) + "]",
                                 requiredExtensionProblem((*required)[i].get<std::string>()));
    checkMaterialAlphaTypes(path, document);
    const std::filesystem::path base_dir = std::filesystem::path(path).parent_path();
    for (const char* list : {"buffers", "images"}) {
        const auto elements = document.find(list);
        if (elements == document.end() || !elements->is_array()) continue;
        for (size_t i = 0; i < elements->size(); ++i) {
            const nlohmann::json& element = (*elements)[i];
            if (!element.is_object() || !element.contains("uri") || !element["uri"].is_string()) continue;
            const std::string uri = element["uri"].get<std::string>();
            if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
            const std::string file = (base_dir / percentDecoded(uri)).string();
            const std::string problem = regularFileProblem(file);
            if (!problem.empty() && problem != "file not found")
                throw InputError(path, std::string(list) + "[" + std::to_string(i) + "].uri",
                                 "\"" + uri + "\" " + problem);
        }
    }
}

std::string describeCount(uint64_t count) {
    return count == std::numeric_limits<uint64_t>::max() ? "more than 1.8e19" : std::to_string(count);
}

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
    return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max() : a + b;
}

// What the flattened scene would hold, counted from accessor counts without reading or expanding anything.
struct InstanceCount {
    uint64_t nodes = 0;
    uint64_t triangles = 0;
    uint64_t vertices = 0;
    InstanceCount& operator+=(const InstanceCount& other) {
        nodes = saturatingAdd(nodes, other.nodes);
        triangles = saturatingAdd(triangles, other.triangles);
        vertices = saturatingAdd(vertices, other.vertices);
        return *this;
    }
};

// tinygltf image callback: keep the encoded bytes (as_is) instead of decoding them with its built-in stb_image.
// user_data is the Model being loaded. tinygltf hands over an embedded image's bufferView without checking it
// against its buffer, so the range is checked here before a byte is copied.
bool keepEncodedImage(tinygltf::Image* image, const int image_index, std::string* error,
                      std::string* /*warning*/, int /*requested_width*/, int /*requested_height*/,
                      const unsigned char* bytes, int byte_count, void* user_data) {
    if (image->bufferView >= 0) {
        const auto* model = static_cast<const tinygltf::Model*>(user_data);
        bool inside_a_buffer = false;
        const auto address = reinterpret_cast<uintptr_t>(bytes);
        for (const tinygltf::Buffer& buffer : model->buffers) {
            const auto begin = reinterpret_cast<uintptr_t>(buffer.data.data());
            const uintptr_t end = begin + buffer.data.size();
            inside_a_buffer |= byte_count >= 0 && address >= begin && address <= end &&
                               uintptr_t(byte_count) <= end - address;
        }
        if (!inside_a_buffer) {
            if (error)
                *error += "images[" + std::to_string(image_index) + "]: bufferView " +
                          std::to_string(image->bufferView) + " lies outside its buffer\n";
            return false;
        }
    }
    if (bytes != nullptr && byte_count > 0) image->image.assign(bytes, bytes + byte_count);
    image->as_is = true;
    return true;
}

std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
    return text;
}

void addLines(std::vector<std::string>* warnings, const std::string& prefix, const std::string& text) {
    if (!warnings) return;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (!trimmed(line).empty()) warnings->push_back(prefix + trimmed(line));
}

// Where an accessor's elements lie, after every range has been checked.
struct AccessorView {
    const unsigned char* first_element = nullptr;  // nullptr: no bufferView, all elements are zero (glTF spec)
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int component_count = 0;
    bool normalized = false;
};

// One primitive's vertices in model space, before the node transform.
struct PrimitiveData {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  // empty when the primitive has none
    std::vector<glm::vec2> uv0;       // empty when absent
    std::vector<glm::vec2> uv1;       // empty when absent
    std::vector<uint32_t> indices;
};

class GltfFlattener {
public:
    GltfFlattener(const std::string& path, const tinygltf::Model& model, const GltfLoadOptions& options,
                  std::vector<std::string>* warnings)
        : path_(path), model_(model), options_(options), warnings_(warnings),
          base_dir_(std::filesystem::path(path).parent_path()) {}

    TriangleMesh flatten() {
        const std::vector<int> roots = rootNodes();
        checkInstanceCount(roots);
        for (int root : roots) visitNode(root, options_.enu_from_model, 0);
        if (mesh_.indices.empty())
            throw InputError(path_, "", "no triangles in the scene (a building needs at least one triangle)");
        if (primitives_without_uv1_ > 0 || primitives_with_uv1_ == 0) {
            if (primitives_with_uv1_ > 0)
                warn("TEXCOORD_1 present on " + std::to_string(primitives_with_uv1_) + " primitives but missing on " +
                     std::to_string(primitives_without_uv1_) + "; ignoring TEXCOORD_1");
            mesh_.uv1.clear();
            mesh_.has_uv1 = false;
        } else {
            mesh_.has_uv1 = true;
        }
        return std::move(mesh_);
    }

private:
    void warn(const std::string& message) {
        if (warnings_) warnings_->push_back(path_ + ": " + message);
    }

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw InputError(path_, field, problem);
    }

    std::vector<int> rootNodes() const {
        std::vector<int> roots;
        const auto& scenes = model_.scenes;
        if (model_.defaultScene >= 0) {
            if (size_t(model_.defaultScene) >= scenes.size())
                fail("scene", "default scene " + std::to_string(model_.defaultScene) + " does not exist (" +
                                  std::to_string(scenes.size()) + " scenes)");
            roots = scenes[size_t(model_.defaultScene)].nodes;
        } else if (!scenes.empty()) {
            for (const tinygltf::Scene& scene : scenes) roots.insert(roots.end(), scene.nodes.begin(), scene.nodes.end());
        } else {
            // No scenes at all: every node that is nobody's child is a root.
            std::vector<bool> is_child(model_.nodes.size(), false);
            for (const tinygltf::Node& node : model_.nodes)
                for (int child : node.children)
                    if (child >= 0 && size_t(child) < is_child.size()) is_child[size_t(child)] = true;
            for (size_t i = 0; i < model_.nodes.size(); ++i)
                if (!is_child[i]) roots.push_back(int(i));
        }
        return roots;
    }

    // Instances of a node shared by several parents multiply along the hierarchy: a few kilobytes of JSON can
    // describe billions of triangles. The whole expansion is counted (each node once, memoised) and refused
    // above the options' limits before a vertex is read.
    void checkInstanceCount(const std::vector<int>& roots) {
        std::vector<std::optional<InstanceCount>> subtree(model_.nodes.size());
        InstanceCount total;
        for (int root : roots) total += countSubtree(root, 0, subtree);
        const std::string limit_note = " (a node used by several parents repeats its whole subtree); refused "
                                       "before expanding";
        if (total.triangles > options_.max_instanced_triangles)
            fail("nodes", "the scene expands to " + describeCount(total.triangles) +
                              " instanced triangles, above the limit " +
                              std::to_string(options_.max_instanced_triangles) + limit_note);
        if (total.nodes > kMaxNodeInstances)
            fail("nodes", "the scene expands to " + describeCount(total.nodes) + " node instances, above the limit " +
                              std::to_string(kMaxNodeInstances) + limit_note);
        if (total.vertices > options_.max_instanced_vertices)
            fail("nodes", "the scene expands to " + describeCount(total.vertices) +
                              " instanced vertices, above the limit " +
                              std::to_string(options_.max_instanced_vertices) + limit_note);
    }

    InstanceCount countSubtree(int node_index, int depth, std::vector<std::optional<InstanceCount>>& subtree) {
        const std::string field = "nodes[" + std::to_string(node_index) + "]";
        if (node_index < 0 || size_t(node_index) >= model_.nodes.size())
            fail(field, "node does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
        if (subtree[size_t(node_index)]) return *subtree[size_t(node_index)];
        if (depth > kMaxNodeDepth || !nodes_on_path_.insert(node_index).second)
            fail(field, "node hierarchy has a cycle or is deeper than " + std::to_string(kMaxNodeDepth));
        const tinygltf::Node& node = model_.nodes[size_t(node_index)];
        InstanceCount count;
        count.nodes = 1;
        if (node.mesh >= 0 && size_t(node.mesh) < model_.meshes.size()) count += meshCount(node.mesh);
        for (int child : node.children) count += countSubtree(child, depth + 1, subtree);
        nodes_on_path_.erase(node_index);
        subtree[size_t(node_index)] = count;
        return count;
    }

    // Triangles and vertices one instance of a mesh adds (a primitive without normals gets one vertex per
    // triangle corner). Broken references count 0 here; reading them later names the problem.
    InstanceCount meshCount(int mesh_index) const {
        const auto accessor_count = [&](int accessor) -> uint64_t {
            return accessor >= 0 && size_t(accessor) < model_.accessors.size()
                       ? uint64_t(model_.accessors[size_t(accessor)].count)
                       : 0;
        };
        InstanceCount count;
        for (const tinygltf::Primitive& primitive : model_.meshes[size_t(mesh_index)].primitives) {
            if (primitive.mode >= 0 && primitive.mode != TINYGLTF_MODE_TRIANGLES) continue;
            const auto position = primitive.attributes.find("POSITION");
            const uint64_t vertex_count = position == primitive.attributes.end() ? 0 : accessor_count(position->second);
            const uint64_t corner_count = primitive.indices >= 0 ? accessor_count(primitive.indices) : vertex_count;
            const bool has_normals = primitive.attributes.count("NORMAL") > 0;
            count.triangles = saturatingAdd(count.triangles, corner_count / 3);
            count.vertices = saturatingAdd(count.vertices, has_normals ? vertex_count : corner_count);
        }
        return count;
    }

    // Every number of a node's transform must be finite: JSON cannot say NaN, but tinygltf reads an overflowing
    // literal (1e999) as infinity.
    void checkFinite(const std::vector<double>& numbers, const std::string& field) const {
        for (size_t i = 0; i < numbers.size(); ++i)
            if (!std::isfinite(numbers[i]))
                fail(field + "[" + std::to_string(i) + "]", std::isnan(numbers[i]) ? "is NaN" : "is not finite");
    }

    glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& field) const {
        checkFinite(node.matrix, field + ".matrix");
        checkFinite(node.translation, field + ".translation");
        checkFinite(node.rotation, field + ".rotation");
        checkFinite(node.scale, field + ".scale");
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(field + ".matrix", "expected 16 numbers");
            return glm::make_mat4(node.matrix.data());  // both column-major
        }
        glm::dmat4 translation(1.0), rotation(1.0), scale(1.0);
        if (!node.translation.empty()) {
            if (node.translation.size() != 3) fail(field + ".translation", "expected 3 numbers");
            translation[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
        }
        if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) fail(field + ".rotation", "expected 4 numbers");
            // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z).
            glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            const double length = glm::length(q);
            if (!(length > 0.0) || !std::isfinite(length)) fail(field + ".rotation", "not a valid quaternion");
            rotation = glm::mat4_cast(q / length);
        }
        if (!node.scale.empty()) {
            if (node.scale.size() != 3) fail(field + ".scale", "expected 3 numbers");
            scale[0][0] = node.scale[0];
            scale[1][1] = node.scale[1];
            scale[2][2] = node.scale[2];
        }
        return translation * rotation * scale;
    }

    void visitNode(int node_index, const glm::dmat4& enu_from_parent, int depth) {
        const std::string field = "nodes[" + std::to_string(node_index) + "]";
        if (node_index < 0 || size_t(node_index) >= model_.nodes.size())
            fail(field, "node does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
        if (depth > kMaxNodeDepth || !nodes_on_path_.insert(node_index).second)
            fail(field, "node hierarchy has a cycle or is deeper than " + std::to_string(kMaxNodeDepth));
        const tinygltf::Node& node = model_.nodes[size_t(node_index)];
        const glm::dmat4 enu_from_node = enu_from_parent * localTransform(node, field);
        for (int column = 0; column < 4; ++column)
            for (int row = 0; row < 4; ++row)
                if (!std::isfinite(enu_from_node[column][row]))
                    fail(field, "its transform, composed with its parents' and the placement, is not finite "
                                "(a scale or translation near the double range)");
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model_.meshes.size())
                fail(field + ".mesh", "mesh " + std::to_string(node.mesh) + " does not exist");
            addMesh(node.mesh, enu_from_node);
        }
        for (int child : node.children) visitNode(child, enu_from_node, depth + 1);
        nodes_on_path_.erase(node_index);
    }

    // --- accessors -------------------------------------------------------------------------------------------

    AccessorView viewAccessor(int accessor_index, const std::string& field) const {
        if (accessor_index < 0 || size_t(accessor_index) >= model_.accessors.size())
            fail(field, "accessor " + std::to_string(accessor_index) + " does not exist (" +
                            std::to_string(model_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& accessor = model_.accessors[size_t(accessor_index)];
        const std::string accessor_field = field + " (accessors[" + std::to_string(accessor_index) + "])";
        if (accessor.sparse.isSparse) fail(accessor_field, "sparse accessors are not supported");
        AccessorView view;
        view.count = accessor.count;
        view.component_type = accessor.componentType;
        view.component_count = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
        view.normalized = accessor.normalized;
        const int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
        if (view.component_count <= 0 || component_size <= 0)
            fail(accessor_field, "unknown type or componentType");
        const size_t element_size = size_t(view.component_count) * size_t(component_size);
        if (accessor.bufferView < 0) {
            // All zeros, and no bytes in the file to bound the count: the instancing limits bound it instead.
            const uint64_t most = std::max(options_.max_instanced_vertices, 3 * options_.max_instanced_triangles);
            if (uint64_t(view.count) > most)
                fail(accessor_field, std::to_string(view.count) + " elements without a bufferView, above the limit " +
                                         std::to_string(most));
            return view;
        }
        if (size_t(accessor.bufferView) >= model_.bufferViews.size())
            fail(accessor_field, "bufferView " + std::to_string(accessor.bufferView) + " does not exist");
        const tinygltf::BufferView& buffer_view = model_.bufferViews[size_t(accessor.bufferView)];
        const std::string view_field = "bufferViews[" + std::to_string(accessor.bufferView) + "]";
        if (buffer_view.buffer < 0 || size_t(buffer_view.buffer) >= model_.buffers.size())
            fail(view_field, "buffer " + std::to_string(buffer_view.buffer) + " does not exist");
        const tinygltf::Buffer& buffer = model_.buffers[size_t(buffer_view.buffer)];
        if (buffer_view.byteOffset > buffer.data.size() ||
            buffer_view.byteLength > buffer.data.size() - buffer_view.byteOffset)
            fail(view_field, "range [" + std::to_string(buffer_view.byteOffset) + ", " +
                                 std::to_string(buffer_view.byteOffset + buffer_view.byteLength) +
                                 ") exceeds buffer " + std::to_string(buffer_view.buffer) + " of " +
                                 std::to_string(buffer.data.size()) + " bytes");
        view.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element_size;
        if (view.stride < element_size)
            fail(view_field, "byteStride " + std::to_string(view.stride) + " is smaller than an element (" +
                                 std::to_string(element_size) + " bytes)");
        if (accessor.byteOffset > buffer_view.byteLength)
            fail(accessor_field, "byteOffset " + std::to_string(accessor.byteOffset) + " is beyond " + view_field);
        if (view.count > 0) {
            const size_t last_end = accessor.byteOffset + (view.count - 1) * view.stride + element_size;
            // Guard against the multiplication wrapping before comparing.
            if (view.count - 1 > buffer_view.byteLength / view.stride + 1 || last_end > buffer_view.byteLength)
                fail(accessor_field, std::to_string(view.count) + " elements from byteOffset " +
                                         std::to_string(accessor.byteOffset) + " exceed " + view_field + " (" +
                                         std::to_string(buffer_view.byteLength) + " bytes)");
        }
        view.first_element = buffer.data.data() + buffer_view.byteOffset + accessor.byteOffset;
        return view;
    }

    // Reads float vectors (or, when allow_normalized, normalized unsigned byte/short ones, as texture
    // coordinates may be) of exactly `component_count` components.
    template <typename Vector>
    std::vector<Vector> readVectors(int accessor_index, const std::string& field, bool allow_normalized) const {
        constexpr int kComponents = Vector::length();
        const AccessorView view = viewAccessor(accessor_index, field);
        if (view.component_count != kComponents)
            fail(field, "expected " + std::to_string(kComponents) + " components per element, found " +
                            std::to_string(view.component_count));
        const bool is_float = view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
        const bool is_unorm8 = view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && view.normalized;
        const bool is_unorm16 = view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && view.normalized;
        if (!is_float && !(allow_normalized && (is_unorm8 || is_unorm16)))
            fail(field, "unsupported componentType " + std::to_string(view.component_type) +
                            (allow_normalized ? " (float, or normalized unsigned byte/short expected)"
                                              : " (float expected)"));
        std::vector<Vector> values(view.count, Vector(0));
        if (!view.first_element) return values;
        for (size_t i = 0; i < view.count; ++i) {
            const unsigned char* element = view.first_element + i * view.stride;
            for (int c = 0; c < kComponents; ++c) {
                if (is_float) {
                    float value;
                    std::memcpy(&value, element + size_t(c) * 4, 4);
                    values[i][c] = value;
                } else if (is_unorm8) {
                    values[i][c] = float(element[c]) / 255.0f;
                } else {
                    uint16_t value;
                    std::memcpy(&value, element + size_t(c) * 2, 2);
                    values[i][c] = float(value) / 65535.0f;
                }
            }
        }
        return values;
    }

    std::vector<uint32_t> readIndices(int accessor_index, const std::string& field) const {
        const AccessorView view = viewAccessor(accessor_index, field);
        if (view.component_count != 1) fail(field, "indices must be SCALAR");
        std::vector<uint32_t> indices(view.count, 0);
        if (!view.first_element) return indices;
        for (size_t i = 0; i < view.count; ++i) {
            const unsigned char* element = view.first_element + i * view.stride;
            switch (view.component_type) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = element[0]; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    uint16_t value;
                    std::memcpy(&value, element, 2);
                    indices[i] = value;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&indices[i], element, 4); break;
                default:
                    fail(field, "unsupported index componentType " + std::to_string(view.component_type) +
                                    " (unsigned byte, short or int expected)");
            }
        }
        return indices;
    }

    // --- primitives ------------------------------------------------------------------------------------------

    PrimitiveData readPrimitive(const tinygltf::Primitive& primitive, const std::string& field) const {
        PrimitiveData data;
        const auto attribute = [&](const char* name) {
            auto found = primitive.attributes.find(name);
            return found == primitive.attributes.end() ? -1 : found->second;
        };
        const int position_accessor = attribute("POSITION");
        if (position_accessor < 0) fail(field + ".attributes", "no POSITION attribute");
        const std::string position_field = field + ".attributes.POSITION";
        for (const glm::vec3& p : readVectors<glm::vec3>(position_accessor, position_field, false)) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                fail(position_field, "vertex " + std::to_string(data.positions.size()) + " is " +
                                         (std::isnan(p.x + p.y + p.z) ? "NaN" : "infinite"));
            data.positions.emplace_back(p);
        }
        const size_t vertex_count = data.positions.size();
        const auto check_count = [&](size_t count, const std::string& attribute_field) {
            if (count != vertex_count)
                fail(attribute_field, std::to_string(count) + " elements, but POSITION has " +
                                          std::to_string(vertex_count));
        };
        if (int normal_accessor = attribute("NORMAL"); normal_accessor >= 0) {
            const std::string normal_field = field + ".attributes.NORMAL";
            for (const glm::vec3& n : readVectors<glm::vec3>(normal_accessor, normal_field, false))
                data.normals.emplace_back(n);
            check_count(data.normals.size(), normal_field);
        }
        // A NaN or infinite texture coordinate is the file's fault: found later, the lightmap texel it makes
        // was blamed on the bake's output folder.
        const auto read_uvs = [&](int accessor, const std::string& uv_field) {
            std::vector<glm::vec2> uvs = readVectors<glm::vec2>(accessor, uv_field, true);
            for (size_t i = 0; i < uvs.size(); ++i)
                if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y))
                    fail(uv_field, "accessor " + std::to_string(accessor) + ", vertex " + std::to_string(i) +
                                       " is " + (std::isnan(uvs[i].x + uvs[i].y) ? "NaN" : "infinite"));
            check_count(uvs.size(), uv_field);
            return uvs;
        };
        if (int uv0_accessor = attribute("TEXCOORD_0"); uv0_accessor >= 0)
            data.uv0 = read_uvs(uv0_accessor, field + ".attributes.TEXCOORD_0");
        if (int uv1_accessor = attribute("TEXCOORD_1"); uv1_accessor >= 0)
            data.uv1 = read_uvs(uv1_accessor, field + ".attributes.TEXCOORD_1");
        const std::string index_field = field + ".indices";
        if (primitive.indices >= 0) {
            data.indices = readIndices(primitive.indices, index_field);
            for (uint32_t index : data.indices)
                if (index >= vertex_count)
                    fail(index_field, "index " + std::to_string(index) + " >= vertex count " +
                                          std::to_string(vertex_count));
        } else {
            data.indices.resize(vertex_count);
            for (size_t i = 0; i < vertex_count; ++i) data.indices[i] = uint32_t(i);
        }
        if (data.indices.size() % 3 != 0)
            fail(primitive.indices >= 0 ? index_field : position_field,
                 std::to_string(data.indices.size()) + " vertices do not make whole triangles");
        return data;
    }

    void addMesh(int mesh_index, const glm::dmat4& enu_from_mesh) {
        const tinygltf::Mesh& gltf_mesh = model_.meshes[size_t(mesh_index)];
        const glm::dmat3 linear_part(enu_from_mesh);
        // Normals transform with the inverse transpose; a mirroring transform (negative determinant) turns
        // counter-clockwise triangles clockwise, so their winding is flipped to keep front faces front.
        const double determinant = glm::determinant(linear_part);
        if (!(std::abs(determinant) > 0.0) || !std::isfinite(determinant))
            fail("meshes[" + std::to_string(mesh_index) + "]", "its node transform is singular");
        const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear_part));
        const bool flip_winding = determinant < 0.0;

        for (size_t p = 0; p < gltf_mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& primitive = gltf_mesh.primitives[p];
            const std::string field = "meshes[" + std::to_string(mesh_index) + "].primitives[" + std::to_string(p) + "]";
            const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES) {
                warn(field + ": mode " + std::to_string(mode) + " is not TRIANGLES (4); skipped");
                continue;
            }
            PrimitiveData data = readPrimitive(primitive, field);
            if (data.indices.empty()) continue;
            const uint32_t material = materialFor(primitive.material, field);
            appendPrimitive(data, enu_from_mesh, normal_matrix, flip_winding, material, field);
        }
    }

    void appendPrimitive(PrimitiveData& data, const glm::dmat4& enu_from_mesh, const glm::dmat3& normal_matrix,
                         bool flip_winding, uint32_t material, const std::string& field) {
        if (flip_winding)
            for (size_t t = 0; t + 2 < data.indices.size(); t += 3) std::swap(data.indices[t + 1], data.indices[t + 2]);

        std::vector<glm::vec3> positions(data.positions.size());
        for (size_t i = 0; i < positions.size(); ++i) {
            positions[i] = glm::vec3(enu_from_mesh * glm::dvec4(data.positions[i], 1.0));
            if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
                fail(field + ".attributes.POSITION", "vertex " + std::to_string(i) +
                                                         " lies beyond float range after its node transform");
        }

        const bool has_normals = !data.normals.empty();
        if (!has_normals) {
            // Flat normals need one vertex per triangle corner: un-share the vertices.
            PrimitiveData unshared;
            std::vector<glm::vec3> unshared_positions;
            for (uint32_t index : data.indices) {
                unshared_positions.push_back(positions[index]);
                if (!data.uv0.empty()) unshared.uv0.push_back(data.uv0[index]);
                if (!data.uv1.empty()) unshared.uv1.push_back(data.uv1[index]);
            }
            unshared.indices.resize(data.indices.size());
            for (size_t i = 0; i < unshared.indices.size(); ++i) unshared.indices[i] = uint32_t(i);
            positions = std::move(unshared_positions);
            data.uv0 = std::move(unshared.uv0);
            data.uv1 = std::move(unshared.uv1);
            data.indices = std::move(unshared.indices);
        }

        std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
        std::vector<bool> normal_is_valid(positions.size(), false);
        if (has_normals) {
            size_t unusable_normals = 0;
            for (size_t i = 0; i < normals.size(); ++i) {
                const glm::dvec3 n = normal_matrix * data.normals[i];
                const double length = glm::length(n);
                if (length > 1e-20 && std::isfinite(length)) {
                    normals[i] = glm::vec3(n / length);
                    normal_is_valid[i] = true;
                } else {
                    ++unusable_normals;
                }
            }
            // Bad normals are repaired, not fatal: a photogrammetry export often has a few.
            if (unusable_normals > 0)
                warn(field + ".attributes.NORMAL: " + std::to_string(unusable_normals) +
                     " zero, NaN or infinite normals replaced by face normals");
        }
        // Face normals (counter-clockwise in ENU, after any winding flip) for vertices without a usable one.
        for (size_t t = 0; t + 2 < data.indices.size(); t += 3) {
            const uint32_t a = data.indices[t], b = data.indices[t + 1], c = data.indices[t + 2];
            if (normal_is_valid[a] && normal_is_valid[b] && normal_is_valid[c]) continue;
            glm::vec3 face = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
            const float length = glm::length(face);
            face = length > 0.0f ? face / length : glm::vec3(0.0f, 0.0f, 1.0f);
            for (uint32_t v : {a, b, c})
                if (!normal_is_valid[v]) normals[v] = face;
        }

        const uint32_t vertex_offset = uint32_t(mesh_.positions.size());
        mesh_.positions.insert(mesh_.positions.end(), positions.begin(), positions.end());
        mesh_.normals.insert(mesh_.normals.end(), normals.begin(), normals.end());
        if (data.uv0.empty()) data.uv0.assign(positions.size(), glm::vec2(0.0f));
        mesh_.uv0.insert(mesh_.uv0.end(), data.uv0.begin(), data.uv0.end());
        if (data.uv1.empty()) {
            ++primitives_without_uv1_;
            data.uv1.assign(positions.size(), glm::vec2(0.0f));
        } else {
            ++primitives_with_uv1_;
        }
        mesh_.uv1.insert(mesh_.uv1.end(), data.uv1.begin(), data.uv1.end());
        for (uint32_t index : data.indices) mesh_.indices.push_back(index + vertex_offset);
        mesh_.triangle_material.insert(mesh_.triangle_material.end(), data.indices.size() / 3, material);
    }

    // --- materials and textures ------------------------------------------------------------------------------

    uint32_t materialFor(int gltf_material, const std::string& primitive_field) {
        if (auto found = material_of_gltf_.find(gltf_material); found != material_of_gltf_.end())
            return found->second;
        Material material;
        if (gltf_material < 0) {
            material.name = "default";  // glTF's default material: white, no texture
        } else {
            if (size_t(gltf_material) >= model_.materials.size())
                fail(primitive_field + ".material", "material " + std::to_string(gltf_material) + " does not exist");
            const tinygltf::Material& source = model_.materials[size_t(gltf_material)];
            const std::string field = "materials[" + std::to_string(gltf_material) + "]";
            material.name = source.name.empty() ? field : source.name;
            const auto& pbr = source.pbrMetallicRoughness;
            checkFactors(pbr.baseColorFactor, field + ".pbrMetallicRoughness.baseColorFactor");
            checkFactors(source.emissiveFactor, field + ".emissiveFactor");
            if (pbr.baseColorFactor.size() == 4)
                material.base_color_factor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                                       pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
            if (source.emissiveFactor.size() == 3)
                material.emissive_factor =
                    glm::vec3(source.emissiveFactor[0], source.emissiveFactor[1], source.emissiveFactor[2]);
            material.double_sided = source.doubleSided;
            readAlphaMode(source, field, material);
            if (pbr.baseColorTexture.index >= 0) {
                const std::string texture_field = field + ".pbrMetallicRoughness.baseColorTexture";
                if (pbr.baseColorTexture.texCoord != 0)
                    warn(texture_field + ": uses TEXCOORD_" + std::to_string(pbr.baseColorTexture.texCoord) +
                         "; read with TEXCOORD_0");
                material.base_color_texture = textureFor(pbr.baseColorTexture.index, texture_field);
            }
        }
        const uint32_t index = uint32_t(mesh_.materials.size());
        mesh_.materials.push_back(std::move(material));
        material_of_gltf_[gltf_material] = index;
        return index;
    }

    // alphaMode MASK cuts holes at alphaCutoff. BLEND has no order-independent meaning for a lightmap bake or a
    // depth-tested frame, so it is read as MASK at the cutoff (what a foliage card exported as BLEND means).
    void readAlphaMode(const tinygltf::Material& source, const std::string& field, Material& material) {
        if (source.alphaMode == "OPAQUE") return;
        if (source.alphaMode != "MASK" && source.alphaMode != "BLEND")
            fail(field + ".alphaMode", "\"" + source.alphaMode + "\" is not OPAQUE, MASK or BLEND");
        const float cutoff = float(source.alphaCutoff);
        if (!(std::isfinite(cutoff) && cutoff >= 0.0f && cutoff <= 1.0f)) {
            std::ostringstream problem;
            problem << source.alphaCutoff << " is not a number in [0, 1]";
            fail(field + ".alphaCutoff", problem.str());
        }
        if (source.alphaMode == "BLEND")
            warn(field + ".alphaMode: BLEND is treated as MASK with alphaCutoff " + std::to_string(cutoff) +
                 " (no blending: texels below it are holes, the rest opaque)");
        material.alpha_masked = true;
        material.alpha_cutoff = cutoff;
    }

    // Colour factors become floats (and emission is radiance the tracer adds up): each must be finite and >= 0
    // as a float, so 1e39, beyond float range, is refused rather than turned into infinity.
    void checkFactors(const std::vector<double>& factors, const std::string& field) const {
        for (size_t i = 0; i < factors.size(); ++i) {
            const float value = float(factors[i]);
            if (std::isfinite(value) && value >= 0.0f && value <= kMaxRadiance) continue;
            std::ostringstream problem;
            problem << factors[i]
                    << (std::isnan(factors[i])     ? " is NaN"
                        : factors[i] < 0.0         ? " is negative"
                        : !std::isfinite(value)    ? " is beyond float range"
                                                   : " is above the limit 1e+15");
            fail(field + "[" + std::to_string(i) + "]", problem.str());
        }
    }

    int textureFor(int texture_index, const std::string& field) {
        if (texture_index < 0 || size_t(texture_index) >= model_.textures.size())
            fail(field + ".index", "texture " + std::to_string(texture_index) + " does not exist");
        const int image_index = model_.textures[size_t(texture_index)].source;
        if (image_index < 0) {
            warn(field + ": texture " + std::to_string(texture_index) +
                 " has no image source (an extension?); using the base colour factor only");
            return -1;
        }
        if (size_t(image_index) >= model_.images.size())
            fail("textures[" + std::to_string(texture_index) + "].source",
                 "image " + std::to_string(image_index) + " does not exist");
        if (auto found = texture_of_image_.find(image_index); found != texture_of_image_.end()) return found->second;

        const tinygltf::Image& image = model_.images[size_t(image_index)];
        const std::string image_field = "images[" + std::to_string(image_index) + "]";
        std::string name = image.uri.empty() ? path_ + " " + image_field + (image.name.empty() ? "" : " " + image.name)
                                             : (base_dir_ / image.uri).string();
        int texture = -1;
        if (image.image.empty()) {
            warn(image_field + ": cannot read '" + (image.uri.empty() ? image.name : image.uri) +
                 "'; using the base colour factor only");
        } else {
            try {
                // Downsampled while decoding (never held at full size), to max_texture_size or kMaxImageSide.
                ImageRGBA decoded =
                    readImageFromMemory(name, image.image, ImageEncoding::Srgb, options_.max_texture_size);
                texture = int(mesh_.textures.size());
                mesh_.textures.push_back(std::move(decoded));
                mesh_.texture_names.push_back(name);
            } catch (const InputError& error) {
                warn(image_field + ": " + error.what() + "; using the base colour factor only");
            }
        }
        texture_of_image_[image_index] = texture;
        return texture;
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    const GltfLoadOptions& options_;
    std::vector<std::string>* warnings_;
    std::filesystem::path base_dir_;
    TriangleMesh mesh_;
    std::map<int, uint32_t> material_of_gltf_;
    std::map<int, int> texture_of_image_;
    std::set<int> nodes_on_path_;
    size_t primitives_with_uv1_ = 0;
    size_t primitives_without_uv1_ = 0;
};

// nlohmann's messages carry ids ("[json.exception.parse_error.101] "), which mean nothing to a user.
std::string withoutJsonExceptionIds(std::string text) {
    for (size_t start; (start = text.find("[json.exception.")) != std::string::npos;) {
        const size_t end = text.find("] ", start);
        if (end == std::string::npos) break;
        text.erase(start, end + 2 - start);
    }
    return text;
}

bool hasGlbExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".glb";
}

}  // namespace

TriangleMesh loadGltf(const std::string& path, const GltfLoadOptions& options, std::vector<std::string>* warnings) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) throw InputError(path, "", problem);
    std::vector<unsigned char> file_bytes;
    std::string read_error;
    if (!readRegularFile(&file_bytes, &read_error, path, nullptr)) throw InputError(path, "", read_error);
    const bool is_glb = hasGlbExtension(path);
    try {
        checkBeforeParsing(path, file_bytes, is_glb);

        tinygltf::TinyGLTF parser;
        parser.SetFsCallbacks({&regularFileExists, &pathAsIs, &readRegularFile, &unusedWrite, nullptr});
        tinygltf::Model model;
        parser.SetImageLoader(&keepEncodedImage, &model);
        std::string error, warning;
        const std::string base_dir = std::filesystem::path(path).parent_path().string();
        const bool parsed =
            is_glb ? parser.LoadBinaryFromMemory(&model, &error, &warning, file_bytes.data(),
                                                 unsigned(std::min<size_t>(file_bytes.size(), UINT32_MAX)), base_dir)
                   : parser.LoadASCIIFromString(&model, &error, &warning,
                                                reinterpret_cast<const char*>(file_bytes.data()),
                                                unsigned(std::min<size_t>(file_bytes.size(), UINT32_MAX)), base_dir);
        if (!parsed) throw InputError(path, "", withoutJsonExceptionIds(oneLine(error.empty() ? "cannot parse glTF" : error)));
        addLines(warnings, path + ": ", warning);

        GltfFlattener flattener(path, model, options, warnings);
        return flattener.flatten();
    } catch (const std::bad_alloc&) {
        // The limits above should make this unreachable; if memory still runs out, say so on one line.
        throw InputError(path, "", "out of memory while loading (the file's declared sizes exceed this machine)");
    }
}

}  // namespace gusuku

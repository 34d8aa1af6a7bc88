#include "bake_inputs.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"

namespace gusuku::bake {

namespace {

namespace fs = std::filesystem;

uint32_t littleEndianWord(const std::string& bytes, size_t offset) {
    uint32_t value = 0;
    for (int i = 3; i >= 0; --i) value = (value << 8) | uint32_t(static_cast<unsigned char>(bytes[offset + size_t(i)]));
    return value;
}

// A glTF's JSON text: the whole file, or a GLB's first chunk (header: magic, version, length; chunk: length, type).
std::string gltfJsonText(const std::string& path, const std::string& bytes) {
    if (bytes.size() < 4 || bytes.compare(0, 4, "glTF") != 0) return bytes;
    if (bytes.size() < 20) throw InputError(path, "", "GLB file is shorter than its header");
    const size_t chunk_length = littleEndianWord(bytes, 12);
    if (littleEndianWord(bytes, 16) != 0x4E4F534Au || 20 + chunk_length > bytes.size())
        throw InputError(path, "", "GLB file does not start with a JSON chunk");
    return bytes.substr(20, chunk_length);
}

// RFC 3986 percent-decoding: glTF URIs escape spaces and other characters.
std::string percentDecoded(const std::string& uri) {
    std::string text;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            text += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            text += uri[i];
        }
    }
    return text;
}

}  // namespace

std::vector<std::string> gltfExternalFiles(const std::string& gltf_path) {
    const std::string bytes = readWholeFile(gltf_path);
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(gltfJsonText(gltf_path, bytes));
    } catch (const nlohmann::json::exception& error) {
        throw InputError(gltf_path, "", std::string("not a glTF: ") + error.what());
    }
    std::vector<std::string> files;
    const fs::path folder = fs::absolute(gltf_path).parent_path();
    for (const char* array : {"buffers", "images"}) {
        if (!document.is_object() || !document.contains(array) || !document[array].is_array()) continue;
        for (const nlohmann::json& entry : document[array]) {
            if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
            const std::string uri = entry["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            files.push_back((folder / percentDecoded(uri)).lexically_normal().string());
        }
    }
    return files;
}

std::vector<std::string> bakeInputFiles(const SiteConfig& site) {
    std::vector<std::string> files = {fs::absolute(site.file).lexically_normal().string(), site.building.path};
    for (const std::string& file : gltfExternalFiles(site.building.path)) files.push_back(file);
    if (site.sfm_mesh) {
        files.push_back(site.sfm_mesh->path);
        // A PLY or OBJ survey mesh is one file (an OBJ's .mtl and textures are not read).
        if (!isSurveyMeshPath(site.sfm_mesh->path))
            for (const std::string& file : gltfExternalFiles(site.sfm_mesh->path)) files.push_back(file);
    }
    // Every photo of a bracket is an input (the first is the sky's path).
    for (const SkyConfig* sky : {&site.sunny_sky, site.overcast_sky ? &*site.overcast_sky : nullptr}) {
        if (!sky) continue;
        files.push_back(sky->path);
        for (const SkyPhotoConfig& photo : sky->photos) files.push_back(photo.path);
    }
    std::vector<std::string> unique;
    for (const std::string& file : files)
        if (std::find(unique.begin(), unique.end(), file) == unique.end()) unique.push_back(file);
    return unique;
}

}  // namespace gusuku::bake

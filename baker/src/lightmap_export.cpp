// gusuku-bake export (gusuku_bake/lightmap_export.h): building.glb as the bake wrote it, plus one slot's lightmap
// bound through MOZ_lightmap and the slot's sun as a KHR_lights_punctual light. The building's own bytes (meshes,
// materials, textures) are carried over through tinygltf unchanged, so TEXCOORD_1 is gusuku's lightmap charts.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tiny_gltf.h>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_export.h"
#include "gusuku_bake/output_guard.h"

namespace gusuku::bake {

namespace {

namespace fs = std::filesystem;

constexpr int kGlLinear = 9729;        // glTF sampler filters: no mipmaps, which would blend across charts
constexpr int kGlClampToEdge = 33071;  // the charts' padding is dilated, so the edge texel is the right one

void checkOutputPath(const std::string& output_path) {
    std::string extension = fs::path(output_path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".glb") throw InputError(output_path, "", "the export is a glTF binary: name it .glb");
    std::error_code error;
    if (fs::is_directory(output_path, error)) throw InputError(output_path, "", "is a directory, not a .glb file");
}

// The export may not replace an input of the set's bake (its building model, site.json, a sky photo) nor lie
// inside any bake set or pack (gusuku_bake/output_guard.h): the manifest's inputs are read for that first.
void guardOutput(const std::string& bakeset_folder, const std::string& output_path) {
    OutputRequest request;
    request.output = output_path;
    request.field = "";
    request.command = "export";
    request.kind = OutputKind::kFile;
    request.read_sets = {bakeset_folder};
    const std::string manifest_path = bakeset_folder + "/manifest.json";
    std::error_code error;
    if (fs::exists(manifest_path, error)) {
        const BakeSetManifest manifest = readBakeSetManifest(manifest_path);
        for (const BakeSetInput& input : manifest.inputs)
            request.inputs.push_back(resolveBakeSetInputPath(bakeset_folder, manifest, input.path));
    }
    refuseUnsafeOutput(request);
}

size_t findSlot(const std::string& bakeset_folder, const BakeSetManifest& manifest, const std::string& name) {
    std::string names;
    for (size_t s = 0; s < manifest.slots.size(); ++s) {
        if (manifest.slots[s].name == name) return s;
        names += (s ? ", " : "") + manifest.slots[s].name;
    }
    throw InputError(bakeset_folder + "/manifest.json", "/slots",
                     "no slot " + quotedForMessage(name) + " (its slots: " + names + ")");
}

// Images stay encoded in their bufferViews: the export copies them, it never needs their texels.
bool keepImageEncoded(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                      void*) {
    return true;
}

tinygltf::Model readBuildingGlb(const std::string& path) {
    const std::string bytes = readWholeFile(path);
    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&keepImageEncoded, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    if (!parser.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                     unsigned(bytes.size()), ""))
        throw InputError(path, "", "cannot parse as glTF binary: " + error.substr(0, error.find('\n')));
    if (model.buffers.size() != 1 || !model.buffers[0].uri.empty())
        throw InputError(path, "/buffers", "a bake set's building.glb holds exactly one embedded buffer");
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
            if (!model.meshes[m].primitives[p].attributes.count("TEXCOORD_1"))
                throw InputError(path, "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p),
                                 "has no TEXCOORD_1 (the lightmap charts)");
    return model;
}

int appendBufferView(tinygltf::Model& model, const std::vector<unsigned char>& bytes) {
    std::vector<unsigned char>& data = model.buffers[0].data;
    while (data.size() % 4 != 0) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = bytes.size();
    data.insert(data.end(), bytes.begin(), bytes.end());
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
}

int addLightmapTexture(tinygltf::Model& model, const LinearLightmap8& lightmap, const std::string& slot) {
    tinygltf::Image image;
    image.name = "lightmap " + slot;
    image.mimeType = "image/png";
    image.bufferView = appendBufferView(model, encodePng8(lightmap.width, lightmap.height, 3, lightmap.rgb8));
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = kGlLinear;
    sampler.minFilter = kGlLinear;
    sampler.wrapS = sampler.wrapT = kGlClampToEdge;
    model.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.name = image.name;
    texture.source = int(model.images.size() - 1);
    texture.sampler = int(model.samplers.size() - 1);
    model.textures.push_back(texture);
    return int(model.textures.size() - 1);
}

// Every material gets the extension; a primitive without one gets a rough dielectric of its own (glTF's default
// material is metallic, which a lightmap's diffuse light would not show on).
size_t bindLightmap(tinygltf::Model& model, int texture, double intensity) {
    for (tinygltf::Mesh& mesh : model.meshes)
        for (tinygltf::Primitive& primitive : mesh.primitives)
            if (primitive.material < 0) {
                tinygltf::Material plain;
                plain.name = "default";
                plain.pbrMetallicRoughness.metallicFactor = 0.0;
                plain.pbrMetallicRoughness.roughnessFactor = 1.0;
                model.materials.push_back(plain);
                primitive.material = int(model.materials.size() - 1);
            }
    tinygltf::Value::Object lightmap;
    lightmap["index"] = tinygltf::Value(texture);
    lightmap["texCoord"] = tinygltf::Value(1);
    lightmap["intensity"] = tinygltf::Value(intensity);
    for (tinygltf::Material& material : model.materials) material.extensions[kLightmapExtension] = tinygltf::Value(lightmap);
    if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), kLightmapExtension) ==
        model.extensionsUsed.end())
        model.extensionsUsed.push_back(kLightmapExtension);
    return model.materials.size();
}

// The node's rotation takes a light's local -Z (its direction of travel, KHR_lights_punctual) onto -s, s the
// direction towards the sun in glTF axes: glTF (x, y, z) = ENU (x, z, -y).
std::vector<double> rotationFromMinusZ(const glm::dvec3& travel) {
    const glm::dvec3 from(0.0, 0.0, -1.0);
    const double cosine = glm::dot(from, travel);
    if (cosine < -1.0 + 1e-12) return {0.0, 1.0, 0.0, 0.0};  // opposite: half a turn about Y
    const glm::dvec3 axis = glm::cross(from, travel);
    const double w = 1.0 + cosine;
    const double norm = std::sqrt(w * w + glm::dot(axis, axis));
    return {axis.x / norm, axis.y / norm, axis.z / norm, w / norm};
}

bool addSunLight(tinygltf::Model& model, const BakeSetSlot& slot) {
    if (!slot.sun.present || !slot.sun.position) return false;
    const glm::dvec3 rgb = slot.sun.irradiance_rgb;
    const double brightest = std::max({rgb.x, rgb.y, rgb.z});
    if (!(brightest > 0.0)) return false;
    // Intensity times colour is E_sun on a plane facing the sun, in the lightmap's units (three.js and the
    // extension's readers take a directional light's intensity as that irradiance), so the two add as they do in
    // gusuku's runtime: rho / pi * (E_ind + V E_sun max(0, n . s)).
    tinygltf::Light light;
    light.name = "sun " + slot.name;
    light.type = "directional";
    light.intensity = brightest;
    light.color = {rgb.x / brightest, rgb.y / brightest, rgb.z / brightest};
    model.lights.push_back(light);
    const glm::dvec3 s = slot.sun.position->direction_enu;
    tinygltf::Node node;
    node.name = light.name;
    node.rotation = rotationFromMinusZ(-glm::normalize(glm::dvec3(s.x, s.z, -s.y)));
    tinygltf::Value::Object reference;
    reference["light"] = tinygltf::Value(int(model.lights.size() - 1));
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(reference);
    model.nodes.push_back(node);
    if (model.scenes.empty()) model.scenes.emplace_back();
    model.scenes[size_t(std::max(model.defaultScene, 0))].nodes.push_back(int(model.nodes.size() - 1));
    return true;
}

void addExportNotes(tinygltf::Model& model, const BakeSetSlot& slot) {
    tinygltf::Value::Object notes;
    notes["slot"] = tinygltf::Value(slot.name);
    notes["lightmap"] = tinygltf::Value(std::string(
        "MOZ_lightmap: indirect irradiance E_ind (no direct sun), linear 8-bit PNG on TEXCOORD_1, "
        "irradiance = byte / 255 * intensity; radiance = albedo / pi * (E_ind + E_sun max(0, n . s))"));
    notes["units"] = tinygltf::Value(std::string("the sky map's linear Rec.709 radiance units times steradians"));
    if (!slot.local_time.empty()) notes["local_time"] = tinygltf::Value(slot.local_time);
    model.asset.generator = "gusuku-bake export";
    tinygltf::Value::Object extras;
    extras["gusuku"] = tinygltf::Value(notes);
    model.asset.extras = tinygltf::Value(extras);
}

std::string serialiseGlb(tinygltf::Model& model, const std::string& output_path) {
    std::ostringstream glb;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, glb, false, true))
        throw InputError(output_path, "", "tinygltf could not serialise the export");
    return glb.str();
}

double coarseValidTexelFraction(const BakeSetImage& lightmap, double intensity) {
    size_t valid = 0, coarse = 0;
    for (size_t t = 0; t + 3 < lightmap.rgba.size(); t += 4) {
        if (lightmap.rgba[t + 3] < 0.5f) continue;
        ++valid;
        const double brightest = std::max({lightmap.rgba[t], lightmap.rgba[t + 1], lightmap.rgba[t + 2]});
        if (brightest < 0.1 * intensity) ++coarse;  // under 25.5 steps of intensity / 255: over 2 % error
    }
    return valid ? double(coarse) / double(valid) : 0.0;
}

}  // namespace

LightmapExportReport exportLightmappedGlb(const std::string& bakeset_folder, const std::string& slot_name,
                                          const std::string& output_path) {
    checkOutputPath(output_path);
    guardOutput(bakeset_folder, output_path);
    const BakeSetData bakeset = loadBakeSet(bakeset_folder);
    const size_t slot_index = findSlot(bakeset_folder, bakeset.manifest, slot_name);
    const BakeSetSlot& slot = bakeset.manifest.slots[slot_index];
    const BakeSetImage& lightmap_image = bakeset.slots[slot_index].building;
    tinygltf::Model model = readBuildingGlb(bakeset_folder + "/" + bakeset.manifest.building.mesh);

    const LinearLightmap8 lightmap = quantiseLightmapLinear8(lightmap_image);
    LightmapExportReport report;
    report.output_path = output_path;
    report.slot = slot.name;
    report.lightmap_width = lightmap.width;
    report.lightmap_height = lightmap.height;
    report.intensity = lightmap.intensity;
    report.materials = bindLightmap(model, addLightmapTexture(model, lightmap, slot.name), lightmap.intensity);
    report.sun_light = addSunLight(model, slot);
    report.coarse_valid_texel_fraction = coarseValidTexelFraction(lightmap_image, lightmap.intensity);
    addExportNotes(model, slot);
    const std::string bytes = serialiseGlb(model, output_path);
    try {
        writeBytesAtomically(output_path, bytes.data(), bytes.size());
    } catch (const std::exception& error) {
        const std::string message = error.what();
        // writeBytesAtomically's messages already name the output; others (a parent that is a file) may not.
        throw InputError(output_path, "", "cannot write: " +
                                              (message.rfind(output_path + ": ", 0) == 0
                                                   ? message.substr(output_path.size() + 2)
                                                   : message));
    }
    report.bytes = bytes.size();
    return report;
}

}  // namespace gusuku::bake

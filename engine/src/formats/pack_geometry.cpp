// pack.bin's writer and reader (pack_geometry.h).

#include "gusuku/formats/pack_geometry.h"

#include <cmath>
#include <cstring>

#include "gusuku/formats/input_error.h"

namespace gusuku {
namespace {

// Version 1: opaque materials of 20 bytes. Version 2 (alpha-masked materials, issue 21 item 3) appends each
// material's alpha cutoff (negative: opaque), 24 bytes; the writer writes version 1 while every material is opaque,
// so a pack of an opaque building keeps its bytes, and either version is read.
constexpr char kMagic[8] = {'G', 'S', 'K', 'P', 'A', 'C', 'K', '1'};
constexpr char kMagicMasked[8] = {'G', 'S', 'K', 'P', 'A', 'C', 'K', '2'};
constexpr uint64_t kMaskedMaterialBytes = 24;
constexpr uint32_t kLargestTextureSide = 16384;
constexpr int kCountFields = 10;
const char* const kCountNames[kCountFields] = {"positions", "normals", "uv0", "uv1", "indices",
                                               "triangle_materials", "materials", "textures",
                                               "occluder_positions", "occluder_indices"};
// Bytes of one element of each counted array.
constexpr uint64_t kElementBytes[kCountFields] = {12, 12, 8, 8, 4, 4, 20, 8, 12, 4};

class Writer {
public:
    void bytes(const void* data, size_t count) {
        const uint8_t* from = static_cast<const uint8_t*>(data);
        out.insert(out.end(), from, from + count);
    }
    void u32(uint32_t value) {
        for (int shift = 0; shift < 32; shift += 8) out.push_back(uint8_t(value >> shift));
    }
    void f32(float value) {
        uint32_t bits;
        std::memcpy(&bits, &value, 4);
        u32(bits);
    }
    std::vector<uint8_t> out;
};

class Reader {
public:
    Reader(const uint8_t* bytes, size_t size, const std::string& file) : bytes_(bytes), size_(size), file_(file) {}
    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw InputError(file_, field, problem);
    }
    uint32_t u32() {  // the caller has checked that the arrays fit: see decodePackGeometry
        const uint8_t* at = bytes_ + offset_;
        offset_ += 4;
        return uint32_t(at[0]) | uint32_t(at[1]) << 8 | uint32_t(at[2]) << 16 | uint32_t(at[3]) << 24;
    }
    float f32(const std::string& field) {
        const uint32_t bits = u32();
        float value;
        std::memcpy(&value, &bits, 4);
        if (!std::isfinite(value)) fail(field, "is not a finite number");
        return value;
    }
    size_t offset() const { return offset_; }
    size_t size() const { return size_; }

private:
    const uint8_t* bytes_;
    size_t size_;
    size_t offset_ = sizeof kMagic;
    const std::string& file_;
};

std::string indexed(const char* array, size_t index) { return std::string(array) + "[" + std::to_string(index) + "]"; }

void readBuilding(Reader& reader, const uint32_t counts[kCountFields], bool with_alpha_cutoffs, BakeSetMesh& mesh) {
    for (uint32_t i = 0; i < counts[0]; ++i)
        mesh.positions.push_back({reader.f32(indexed("positions", i)), reader.f32(indexed("positions", i)),
                                  reader.f32(indexed("positions", i))});
    for (uint32_t i = 0; i < counts[1]; ++i)
        mesh.normals.push_back({reader.f32(indexed("normals", i)), reader.f32(indexed("normals", i)),
                                reader.f32(indexed("normals", i))});
    for (uint32_t i = 0; i < counts[2]; ++i) mesh.uv0.push_back({reader.f32(indexed("uv0", i)), reader.f32(indexed("uv0", i))});
    for (uint32_t i = 0; i < counts[3]; ++i) mesh.uv1.push_back({reader.f32(indexed("uv1", i)), reader.f32(indexed("uv1", i))});
    for (uint32_t i = 0; i < counts[4]; ++i) {
        mesh.indices.push_back(reader.u32());
        if (mesh.indices.back() >= counts[0])
            reader.fail(indexed("indices", i), std::to_string(mesh.indices.back()) + " is not below the " +
                                                   std::to_string(counts[0]) + " positions");
    }
    for (uint32_t i = 0; i < counts[5]; ++i) {
        mesh.triangle_material.push_back(reader.u32());
        if (mesh.triangle_material.back() >= counts[6])
            reader.fail(indexed("triangle_materials", i), std::to_string(mesh.triangle_material.back()) +
                                                              " is not below the " + std::to_string(counts[6]) + " materials");
    }
    for (uint32_t i = 0; i < counts[6]; ++i) {
        BakeSetMaterial material;
        for (int channel = 0; channel < 4; ++channel) material.base_color_factor[channel] = reader.f32(indexed("materials", i));
        material.base_color_texture = int(int32_t(reader.u32()));
        if (material.base_color_texture < -1 || material.base_color_texture >= int(counts[7]))
            reader.fail(indexed("materials", i) + ".texture", std::to_string(material.base_color_texture) +
                                                                  " is not -1 or below the " + std::to_string(counts[7]) + " textures");
        if (with_alpha_cutoffs) {
            const float cutoff = reader.f32(indexed("materials", i) + ".alpha_cutoff");
            if (cutoff > 1.0f)
                reader.fail(indexed("materials", i) + ".alpha_cutoff", std::to_string(cutoff) + " is above 1");
            material.alpha_masked = cutoff >= 0.0f;
            if (material.alpha_masked) material.alpha_cutoff = cutoff;
        }
        mesh.materials.push_back(material);
    }
    for (uint32_t i = 0; i < counts[7]; ++i) {
        BakeSetTexture texture;
        const uint32_t width = reader.u32(), height = reader.u32();
        if (width == 0 || height == 0 || width > kLargestTextureSide || height > kLargestTextureSide)
            reader.fail(indexed("textures", i), std::to_string(width) + " x " + std::to_string(height) +
                                                    " is not within 1 to 16384 a side");
        texture.width = int(width);
        texture.height = int(height);
        mesh.textures.push_back(texture);
    }
}

}  // namespace

std::vector<uint8_t> encodePackGeometry(const PackGeometry& geometry) {
    const BakeSetMesh& mesh = geometry.building;
    bool any_masked = false;
    for (const BakeSetMaterial& material : mesh.materials) any_masked |= material.alpha_masked;
    Writer writer;
    writer.bytes(any_masked ? kMagicMasked : kMagic, sizeof kMagic);
    writer.f32(geometry.lightmap_scale);
    const size_t counts[kCountFields] = {mesh.positions.size(), mesh.normals.size(), mesh.uv0.size(),
                                         mesh.uv1.size(), mesh.indices.size(), mesh.triangle_material.size(),
                                         mesh.materials.size(), mesh.textures.size(),
                                         geometry.occluder.positions.size(), geometry.occluder.indices.size()};
    for (size_t count : counts) writer.u32(uint32_t(count));
    for (const glm::vec3& value : mesh.positions) for (int c = 0; c < 3; ++c) writer.f32(value[c]);
    for (const glm::vec3& value : mesh.normals) for (int c = 0; c < 3; ++c) writer.f32(value[c]);
    for (const glm::vec2& value : mesh.uv0) for (int c = 0; c < 2; ++c) writer.f32(value[c]);
    for (const glm::vec2& value : mesh.uv1) for (int c = 0; c < 2; ++c) writer.f32(value[c]);
    for (uint32_t index : mesh.indices) writer.u32(index);
    for (uint32_t material : mesh.triangle_material) writer.u32(material);
    for (const BakeSetMaterial& material : mesh.materials) {
        for (int c = 0; c < 4; ++c) writer.f32(material.base_color_factor[c]);
        writer.u32(uint32_t(int32_t(material.base_color_texture)));
        if (any_masked) writer.f32(material.alpha_masked ? material.alpha_cutoff : -1.0f);
    }
    for (const BakeSetTexture& texture : mesh.textures) {
        writer.u32(uint32_t(texture.width));
        writer.u32(uint32_t(texture.height));
    }
    for (const glm::vec3& value : geometry.occluder.positions) for (int c = 0; c < 3; ++c) writer.f32(value[c]);
    for (uint32_t index : geometry.occluder.indices) writer.u32(index);
    return writer.out;
}

PackGeometry decodePackGeometry(const uint8_t* bytes, size_t size, const std::string& file) {
    Reader reader(bytes, size, file);
    const size_t header_bytes = sizeof kMagic + 4 + 4 * kCountFields;
    if (size < header_bytes)
        reader.fail("header", "the file has " + std::to_string(size) + " bytes, fewer than the " +
                                  std::to_string(header_bytes) + " of its header (truncated?)");
    const bool with_alpha_cutoffs = std::memcmp(bytes, kMagicMasked, sizeof kMagicMasked) == 0;
    if (!with_alpha_cutoffs && std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
        reader.fail("magic", "is neither GSKPACK1 nor GSKPACK2 (not a gusuku pack.bin)");
    PackGeometry geometry;
    geometry.lightmap_scale = reader.f32("lightmap_scale");
    int exponent = 0;
    if (!(geometry.lightmap_scale >= 1.0f) || std::frexp(geometry.lightmap_scale, &exponent) != 0.5f)
        reader.fail("lightmap_scale", std::to_string(geometry.lightmap_scale) + " is not a power of 2 of at least 1");
    uint32_t counts[kCountFields];
    uint64_t expected = header_bytes;  // at most 10 x 2^32 x 20 bytes: no overflow in 64 bits
    for (int field = 0; field < kCountFields; ++field) {
        counts[field] = reader.u32();
        const bool materials = field == 6;
        expected += uint64_t(counts[field]) *
                    (materials && with_alpha_cutoffs ? kMaskedMaterialBytes : kElementBytes[field]);
    }
    if (expected != size)
        reader.fail("counts", "their arrays take " + std::to_string(expected) + " bytes with the header, but the file has " +
                                  std::to_string(size) + " (truncated, or counts that do not add up)");
    for (int field = 1; field <= 3; ++field)
        if (counts[field] != 0 && counts[field] != counts[0])
            reader.fail(kCountNames[field], std::to_string(counts[field]) + " is neither 0 nor one per position (" +
                                                std::to_string(counts[0]) + ")");
    if (counts[4] % 3 != 0) reader.fail("indices", std::to_string(counts[4]) + " is not three per triangle");
    if (counts[5] != counts[4] / 3)
        reader.fail("triangle_materials", std::to_string(counts[5]) + " is not one per triangle (" +
                                              std::to_string(counts[4] / 3) + ")");
    if (counts[9] % 3 != 0) reader.fail("occluder_indices", std::to_string(counts[9]) + " is not three per triangle");
    readBuilding(reader, counts, with_alpha_cutoffs, geometry.building);
    for (uint32_t i = 0; i < counts[8]; ++i)
        geometry.occluder.positions.push_back({reader.f32(indexed("occluder_positions", i)),
                                               reader.f32(indexed("occluder_positions", i)),
                                               reader.f32(indexed("occluder_positions", i))});
    for (uint32_t i = 0; i < counts[9]; ++i) {
        geometry.occluder.indices.push_back(reader.u32());
        if (geometry.occluder.indices.back() >= counts[8])
            reader.fail(indexed("occluder_indices", i), std::to_string(geometry.occluder.indices.back()) +
                                                            " is not below the " + std::to_string(counts[8]) + " occluder positions");
    }
    return geometry;
}

}  // namespace gusuku

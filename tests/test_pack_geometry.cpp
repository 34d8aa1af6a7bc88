// pack.bin, the runtime pack's geometry (gusuku/formats/pack_geometry.h): a textured, two-material mesh with an
// occluder round-trips exactly, its bytes are where the documented layout puts them, and bad files are refused in
// one line naming the file and the field.

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_output_checks.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/pack_geometry.h"

namespace gusuku {
namespace {

PackGeometry quadWithTwoMaterials() {
    PackGeometry geometry;
    geometry.lightmap_scale = 4.0f;
    BakeSetMesh& mesh = geometry.building;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
    mesh.normals = {{0, -1, 0}, {0, -1, 0}, {0, -1, 0}, {0, -1, 0}};
    mesh.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.uv1 = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.9f, 0.9f}, {0.1f, 0.9f}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.triangle_material = {0, 1};
    mesh.materials = {{{0.8f, 0.7f, 0.6f, 1.0f}, 0}, {{0.5f, 0.5f, 0.5f, 1.0f}, -1}};
    mesh.textures = {{2, 3, {}}};
    geometry.occluder.positions = {{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}};
    geometry.occluder.indices = {0, 1, 2};
    return geometry;
}

TEST(PackGeometry, RoundTripsAndLaysOutItsHeaderAsDocumented) {
    const std::vector<uint8_t> file = encodePackGeometry(quadWithTwoMaterials());
    // 8 magic + 4 scale + 10 x 4 counts, then 4 x 12 + 4 x 12 + 4 x 8 + 4 x 8 + 6 x 4 + 2 x 4 + 2 x 20 + 1 x 8 +
    // 3 x 12 + 3 x 4 bytes of arrays.
    EXPECT_EQ(file.size(), 52u + 48 + 48 + 32 + 32 + 24 + 8 + 40 + 8 + 36 + 12);
    EXPECT_EQ(std::string(file.begin(), file.begin() + 8), "GSKPACK1");
    float scale;
    std::memcpy(&scale, file.data() + 8, 4);
    EXPECT_EQ(scale, 4.0f);
    uint32_t counts[10];
    std::memcpy(counts, file.data() + 12, 40);
    const uint32_t expected[10] = {4, 4, 4, 4, 6, 2, 2, 1, 3, 3};
    for (int field = 0; field < 10; ++field) EXPECT_EQ(counts[field], expected[field]) << "count " << field;

    const PackGeometry back = decodePackGeometry(file.data(), file.size(), "pack.bin");
    const PackGeometry original = quadWithTwoMaterials();
    EXPECT_EQ(back.lightmap_scale, 4.0f);
    gusuku::testing::expectSameMeshGeometry(back.building, original.building);
    ASSERT_EQ(back.building.materials.size(), 2u);
    EXPECT_EQ(back.building.materials[0].base_color_factor, original.building.materials[0].base_color_factor);
    EXPECT_EQ(back.building.materials[0].base_color_texture, 0);
    EXPECT_EQ(back.building.materials[1].base_color_texture, -1);
    ASSERT_EQ(back.building.textures.size(), 1u);
    EXPECT_EQ(back.building.textures[0].width, 2);
    EXPECT_EQ(back.building.textures[0].height, 3);
    EXPECT_EQ(back.occluder.positions, original.occluder.positions);
    EXPECT_EQ(back.occluder.indices, original.occluder.indices);
}

// An alpha-masked material (issue 21 item 3) makes the file GSKPACK2, four bytes more a material (its cutoff, -1
// for the opaque one), and comes back masked at its cutoff; a cutoff above 1 is refused by field.
TEST(PackGeometry, AlphaMaskedMaterialsRoundTripAsVersion2) {
    PackGeometry geometry = quadWithTwoMaterials();
    geometry.building.materials[1].alpha_masked = true;
    geometry.building.materials[1].alpha_cutoff = 0.375f;
    std::vector<uint8_t> file = encodePackGeometry(geometry);
    EXPECT_EQ(file.size(), encodePackGeometry(quadWithTwoMaterials()).size() + 2 * 4);
    EXPECT_EQ(std::string(file.begin(), file.begin() + 8), "GSKPACK2");
    const PackGeometry back = decodePackGeometry(file.data(), file.size(), "pack.bin");
    ASSERT_EQ(back.building.materials.size(), 2u);
    EXPECT_FALSE(back.building.materials[0].alpha_masked);
    EXPECT_TRUE(back.building.materials[1].alpha_masked);
    EXPECT_EQ(back.building.materials[1].alpha_cutoff, 0.375f);
    geometry.building.materials[1].alpha_cutoff = 1.5f;
    file = encodePackGeometry(geometry);
    try {
        decodePackGeometry(file.data(), file.size(), "pack.bin");
        ADD_FAILURE() << "a cutoff of 1.5 was read";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "pack.bin: materials[1].alpha_cutoff: 1.500000 is above 1");
    }
}

std::string refusal(const std::vector<uint8_t>& file) {
    try {
        decodePackGeometry(file.data(), file.size(), "pack.bin");
        return "";
    } catch (const InputError& error) {
        return error.what();
    }
}

TEST(PackGeometry, BadFilesAreRefusedNamingTheField) {
    auto with = [](auto change) {
        PackGeometry geometry = quadWithTwoMaterials();
        change(geometry);
        return refusal(encodePackGeometry(geometry));
    };
    const std::vector<uint8_t> good = encodePackGeometry(quadWithTwoMaterials());
    EXPECT_EQ(refusal(good), "");
    EXPECT_EQ(refusal(std::vector<uint8_t>(good.begin(), good.begin() + 30)).rfind("pack.bin: header: the file has 30 bytes", 0), 0u);
    std::vector<uint8_t> magic = good;
    magic[0] = 'X';
    EXPECT_EQ(refusal(magic), "pack.bin: magic: is neither GSKPACK1 nor GSKPACK2 (not a gusuku pack.bin)");
    EXPECT_EQ(refusal(std::vector<uint8_t>(good.begin(), good.end() - 1)).rfind("pack.bin: counts: their arrays take", 0), 0u);
    EXPECT_EQ(with([](PackGeometry& g) { g.building.indices[4] = 9; }),
              "pack.bin: indices[4]: 9 is not below the 4 positions");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.triangle_material[1] = 2; }),
              "pack.bin: triangle_materials[1]: 2 is not below the 2 materials");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.materials[1].base_color_texture = 1; }),
              "pack.bin: materials[1].texture: 1 is not -1 or below the 1 textures");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.positions[2].y = NAN; }), "pack.bin: positions[2]: is not a finite number");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.normals.pop_back(); }),
              "pack.bin: normals: 3 is neither 0 nor one per position (4)");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.triangle_material.pop_back(); }),
              "pack.bin: triangle_materials: 1 is not one per triangle (2)");
    EXPECT_EQ(with([](PackGeometry& g) { g.building.textures[0].width = 0; }),
              "pack.bin: textures[0]: 0 x 3 is not within 1 to 16384 a side");
    EXPECT_EQ(with([](PackGeometry& g) { g.lightmap_scale = 3.0f; }).rfind("pack.bin: lightmap_scale: 3.0", 0), 0u);
    EXPECT_EQ(with([](PackGeometry& g) { g.occluder.indices[2] = 3; }),
              "pack.bin: occluder_indices[2]: 3 is not below the 3 occluder positions");
}

}  // namespace
}  // namespace gusuku

// The format table (gusuku/formats/format_table.h) walked row by row: every row round-trips through the KTX2
// writer and reader (the header's vkFormat, typeSize, block dimensions and bytes read here by hand), the GPU
// layer's byte counts are the table's, and the lightmap rows are the C and C++ enums, checked against values
// written down here from vulkan_core.h and gusuku.h rather than read from the table.

#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/formats/format_table.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {
namespace {

uint32_t u32At(const std::vector<uint8_t>& bytes, size_t at) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
}

TEST(FormatTable, EveryRowRoundTripsThroughTheKtx2WriterAndReader) {
    for (const formats::FormatRow& row : formats::kFormatRows) {
        SCOPED_TRACE(row.name);
        // 7 x 5 texels: a partial block on both sides for every block size.
        Ktx2Image image{Ktx2Format(row.vk_format), 7, 5, {}};
        const uint64_t bytes = formats::levelBytes(row, 7, 5);
        for (uint64_t byte = 0; byte < bytes; ++byte) image.texels.push_back(uint8_t(byte * 13 + 5));
        const std::vector<uint8_t> file = encodeKtx2(image);
        ASSERT_GE(file.size(), 124u);
        EXPECT_EQ(u32At(file, 12), row.vk_format);       // vkFormat
        EXPECT_EQ(u32At(file, 16), row.ktx2_type_size);  // typeSize
        const uint32_t side_minus_1 = row.block_side - 1;
        EXPECT_EQ(u32At(file, 120), side_minus_1 | side_minus_1 << 8);  // DFD texelBlockDimension0, 1
        EXPECT_EQ(u32At(file, 124), row.block_bytes);                   // DFD bytesPlane0
        const Ktx2Image read = decodeKtx2(file.data(), file.size(), "row.ktx2", Ktx2Format(row.vk_format));
        EXPECT_EQ(read.texels, image.texels);
        EXPECT_EQ(ktx2FormatName(row.vk_format), row.vk_name);
        EXPECT_EQ(ktx2BlockSide(Ktx2Format(row.vk_format)), row.block_side);
        EXPECT_EQ(ktx2IsBlockFormat(Ktx2Format(row.vk_format)), formats::isBlockCodec(row.codec));
        // The GPU layer's upload sizes are the table's.
        EXPECT_EQ(levelByteCount(VkFormat(row.vk_format), 7, 5), bytes);
    }
}

TEST(FormatTable, BlockAndTexelSizesAreTheFormatsOwn) {
    // Known sizes of a 1024^2 lightmap: 4 bytes a texel (E5B9G9R9), 8 (RGBA16F), 16 (RGBA32F); 16-byte ASTC
    // blocks, 256^2 of 4x4 and 171^2 of 6x6 (1024 / 6 rounded up).
    const std::vector<std::pair<uint32_t, uint64_t>> known = {{123u, 4194304u},        {97u, 8388608u},
                                                              {109u, 16777216u},       {1000066000u, 1048576u},
                                                              {1000066004u, 467856u}, {166u, 467856u},
                                                              {43u, 4194304u}};
    for (const auto& [vk_format, bytes] : known) {
        const formats::FormatRow* row = formats::findFormat(vk_format);
        ASSERT_NE(row, nullptr) << vk_format;
        EXPECT_EQ(formats::levelBytes(*row, 1024, 1024), bytes) << row->name;
    }
}

TEST(FormatTable, TheLightmapRowsAreTheCAndCppEnums) {
    struct Known {
        int c_value;
        LightmapFormat cpp_value;
        uint32_t vk_format;
        const char* name;
    };
    // gusuku.h's and runtime.h's enumerators with the VkFormat each stands for (vulkan_core.h).
    const std::vector<Known> known = {
        {GUSUKU_LIGHTMAP_E5B9G9R9, LightmapFormat::kE5b9g9r9, 123u, "e5b9g9r9"},
        {GUSUKU_LIGHTMAP_RGBA16F, LightmapFormat::kRgba16f, 97u, "rgba16f"},
        {GUSUKU_LIGHTMAP_RGBA32F, LightmapFormat::kRgba32f, 109u, "rgba32f"},
        {GUSUKU_LIGHTMAP_ASTC_4X4_HDR, LightmapFormat::kAstc4x4Hdr, 1000066000u, "astc 4x4 hdr"},
        {GUSUKU_LIGHTMAP_ASTC_6X6_HDR, LightmapFormat::kAstc6x6Hdr, 1000066004u, "astc 6x6 hdr"},
    };
    std::set<int> listed;
    for (const Known& entry : known) {
        SCOPED_TRACE(entry.name);
        EXPECT_EQ(entry.c_value, int(entry.cpp_value));
        const formats::FormatRow* row = formats::findLightmapFormat(entry.c_value);
        ASSERT_NE(row, nullptr);
        EXPECT_EQ(row->vk_format, entry.vk_format);
        EXPECT_STREQ(row->name, entry.name);
        EXPECT_EQ(formats::findLightmapFormatNamed(entry.name), row);
        listed.insert(entry.c_value);
    }
    // Every lightmap row is one of them, and kAuto none.
    for (const formats::FormatRow& row : formats::kFormatRows)
        if (row.family == formats::FormatFamily::kLightmap) {
            EXPECT_EQ(listed.count(row.c_enum), 1u) << row.name;
        }
    EXPECT_EQ(formats::findLightmapFormat(GUSUKU_LIGHTMAP_AUTO), nullptr);
    EXPECT_EQ(int(LightmapFormat::kAuto), GUSUKU_LIGHTMAP_AUTO);
}

TEST(FormatTable, EachPackFileSuffixIsItsOwnAndTheAstcRowsNeedTheirDeviceFeature) {
    std::set<std::string> suffixes;
    for (const formats::FormatRow& row : formats::kFormatRows) {
        if (row.pack_suffix != nullptr) {
            EXPECT_TRUE(suffixes.insert(row.pack_suffix).second) << row.pack_suffix;
        }
        if (row.codec == formats::TexelCodec::kAstcHdr) {
            EXPECT_EQ(row.feature, formats::DeviceFeature::kAstcHdr);
        }
        if (row.codec == formats::TexelCodec::kAstcLdrSrgb) {
            EXPECT_EQ(row.feature, formats::DeviceFeature::kAstcLdr);
        }
    }
    // The files docs/bakeset.md names.
    EXPECT_EQ(suffixes, (std::set<std::string>{"_astc", "_astc6x6"}));
}

}  // namespace
}  // namespace gusuku

// The runtime pack's KTX 2.0 containers (gusuku/formats/ktx2.h): the bytes at the offsets the KTX 2.0
// specification gives them (read here by hand, not by the reader under test), a round trip of every format, and
// each kind of bad file refused in one line naming the file and the field.

#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"

namespace gusuku {
namespace {

uint32_t u32At(const std::vector<uint8_t>& bytes, size_t at) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);  // little-endian host, as the test machines are
    return value;
}
uint64_t u64At(const std::vector<uint8_t>& bytes, size_t at) {
    uint64_t value = 0;
    std::memcpy(&value, bytes.data() + at, 8);
    return value;
}
void setU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value) { std::memcpy(bytes.data() + at, &value, 4); }
void setU64(std::vector<uint8_t>& bytes, size_t at, uint64_t value) { std::memcpy(bytes.data() + at, &value, 8); }

Ktx2Image lightmap() {
    Ktx2Image image{Ktx2Format::kE5b9g9r9Ufloat, 3, 2, {}};
    for (int byte = 0; byte < 3 * 2 * 4; ++byte) image.texels.push_back(uint8_t(byte * 7 + 1));
    return image;
}

TEST(Ktx2, FieldsLieWhereTheSpecificationPutsThem) {
    const std::vector<uint8_t> file = encodeKtx2(lightmap());
    const uint8_t identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
    ASSERT_GE(file.size(), 104u);
    EXPECT_EQ(std::memcmp(file.data(), identifier, 12), 0);
    EXPECT_EQ(u32At(file, 12), 123u);  // vkFormat VK_FORMAT_E5B9G9R9_UFLOAT_PACK32
    EXPECT_EQ(u32At(file, 16), 4u);    // typeSize of a PACK32 format
    EXPECT_EQ(u32At(file, 20), 3u);    // pixelWidth
    EXPECT_EQ(u32At(file, 24), 2u);    // pixelHeight
    EXPECT_EQ(u32At(file, 28), 0u);    // pixelDepth: 2D
    EXPECT_EQ(u32At(file, 32), 0u);    // layerCount: not an array
    EXPECT_EQ(u32At(file, 36), 1u);    // faceCount
    EXPECT_EQ(u32At(file, 40), 1u);    // levelCount
    EXPECT_EQ(u32At(file, 44), 0u);    // supercompressionScheme: none
    EXPECT_EQ(u32At(file, 48), 104u);  // dfdByteOffset: after the header, index and one level entry
    // DFD: total size, then a basic block of 24 bytes + 16 per sample; E5B9G9R9 has 6 samples (3 mantissas,
    // 3 exponents): 4 + 24 + 96 = 124.
    EXPECT_EQ(u32At(file, 52), 124u);
    EXPECT_EQ(u32At(file, 104), 124u);
    EXPECT_EQ(u32At(file, 108), 0u);                  // vendor 0 (Khronos), descriptor type 0 (basic)
    EXPECT_EQ(u32At(file, 112), 2u | 120u << 16);     // version 2 (DFD 1.3), block size 120
    EXPECT_EQ(u32At(file, 116), 1u | 1u << 8 | 1u << 16);  // RGBSDA, BT.709 primaries, linear transfer
    EXPECT_EQ(u32At(file, 124), 4u);                  // bytesPlane0: 4 bytes a texel
    EXPECT_EQ(u32At(file, 132), 0u | 8u << 16 | 0u << 24);  // sample 0: bits 0-8 (length - 1 = 8), red
    EXPECT_EQ(u32At(file, 148), 27u | 4u << 16 | 0x20u << 24);  // sample 1: bits 27-31, red, exponent
    EXPECT_EQ(u32At(file, 156), 15u);                 // the exponent's bias as its lower limit
    const uint32_t kvd_offset = u32At(file, 56), kvd_length = u32At(file, 60);
    EXPECT_EQ(kvd_offset, 104u + 124u);
    const std::string kvd(file.begin() + kvd_offset, file.begin() + kvd_offset + kvd_length);
    EXPECT_NE(kvd.find(std::string("KTXorientation\0rd\0", 18)), std::string::npos);
    EXPECT_NE(kvd.find("KTXwriter"), std::string::npos);
    EXPECT_EQ(u64At(file, 64), 0u);  // no supercompression global data
    EXPECT_EQ(u64At(file, 72), 0u);
    const uint64_t level_offset = u64At(file, 80), level_length = u64At(file, 88);
    EXPECT_EQ(level_offset % 4, 0u);
    EXPECT_GE(level_offset, kvd_offset + kvd_length);
    EXPECT_EQ(level_length, 24u);
    EXPECT_EQ(u64At(file, 96), 24u);  // uncompressedByteLength
    EXPECT_EQ(file.size(), level_offset + level_length);
    EXPECT_EQ(std::vector<uint8_t>(file.begin() + level_offset, file.end()), lightmap().texels);
}

TEST(Ktx2, EveryPackFormatRoundTrips) {
    for (Ktx2Format format : {Ktx2Format::kR8Unorm, Ktx2Format::kR8g8b8a8Srgb, Ktx2Format::kR32g32b32a32Sfloat,
                              Ktx2Format::kE5b9g9r9Ufloat}) {
        Ktx2Image image{format, 5, 3, std::vector<uint8_t>(15 * ktx2TexelBytes(format))};
        for (size_t byte = 0; byte < image.texels.size(); ++byte) image.texels[byte] = uint8_t(byte * 13);
        const std::vector<uint8_t> file = encodeKtx2(image);
        EXPECT_EQ(u64At(file, 80) % (format == Ktx2Format::kR32g32b32a32Sfloat ? 16 : 4), 0u) << ktx2FormatName(uint32_t(format));
        const Ktx2Image back = decodeKtx2(file.data(), file.size(), "image.ktx2", format);
        EXPECT_EQ(back.width, 5u);
        EXPECT_EQ(back.height, 3u);
        EXPECT_EQ(back.texels, image.texels) << ktx2FormatName(uint32_t(format));
    }
}

// ASTC 4x4 HDR: a 5 x 3 image is 2 x 1 blocks of 16 bytes; typeSize 1 (block-compressed), the DFD one ASTC-model
// sample over the 128-bit block, signed float, with 4 x 4 texel blocks.
TEST(Ktx2, AstcBlocksLieWhereTheSpecificationPutsThem) {
    Ktx2Image image{Ktx2Format::kAstc4x4Sfloat, 5, 3, std::vector<uint8_t>(2 * 16)};
    for (size_t byte = 0; byte < image.texels.size(); ++byte) image.texels[byte] = uint8_t(byte * 29 + 3);
    EXPECT_EQ(ktx2LevelBytes(Ktx2Format::kAstc4x4Sfloat, 5, 3), 32u);
    EXPECT_EQ(ktx2LevelBytes(Ktx2Format::kAstc4x4Sfloat, 284, 284), 71u * 71u * 16u);
    const std::vector<uint8_t> file = encodeKtx2(image);
    EXPECT_EQ(u32At(file, 12), 1000066000u);  // vkFormat VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK
    EXPECT_EQ(u32At(file, 16), 1u);           // typeSize of a block-compressed format
    EXPECT_EQ(u32At(file, 20), 5u);           // pixelWidth and pixelHeight in texels, not blocks
    EXPECT_EQ(u32At(file, 24), 3u);
    EXPECT_EQ(u32At(file, 40), 1u);           // levelCount: no mips (docs/runtime.md says why)
    EXPECT_EQ(u32At(file, 52), 44u);          // DFD: 4 + 24 + one sample of 16
    EXPECT_EQ(u32At(file, 112), 2u | 40u << 16);
    EXPECT_EQ(u32At(file, 116), 162u | 1u << 8 | 1u << 16);  // KHR_DF_MODEL_ASTC, BT.709, linear
    EXPECT_EQ(u32At(file, 120), 3u | 3u << 8);               // texelBlockDimension0/1: 4 - 1
    EXPECT_EQ(u32At(file, 124), 16u);                        // bytesPlane0: 16 bytes a block
    EXPECT_EQ(u32At(file, 132), 0u | 127u << 16 | 0xC0u << 24);  // bits 0-127, ASTC_DATA, float | signed
    EXPECT_EQ(u32At(file, 140), 0xBF800000u);                    // sampleLower -1.0
    const uint64_t level_offset = u64At(file, 80);
    EXPECT_EQ(level_offset % 16, 0u);  // lcm(block size 16, 4)
    EXPECT_EQ(u64At(file, 88), 32u);
    EXPECT_EQ(file.size(), level_offset + 32);
    const Ktx2Image back = decodeKtx2(file.data(), file.size(), "building_noon_astc.ktx2", Ktx2Format::kAstc4x4Sfloat);
    EXPECT_EQ(back.width, 5u);
    EXPECT_EQ(back.height, 3u);
    EXPECT_EQ(back.texels, image.texels);
    std::vector<uint8_t> short_level = file;
    setU64(short_level, 88, 16);
    setU64(short_level, 96, 16);
    short_level.resize(level_offset + 16);
    try {
        decodeKtx2(short_level.data(), short_level.size(), "building_noon_astc.ktx2", Ktx2Format::kAstc4x4Sfloat);
        ADD_FAILURE() << "a level of one block for 2 x 1 blocks was read";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).rfind("building_noon_astc.ktx2: levels[0].byteLength: 16 is not 5 x 3 texels "
                                                  "in 4 x 4 blocks of 16 bytes (32)", 0), 0u) << error.what();
    }
    EXPECT_THROW(encodeKtx2({Ktx2Format::kAstc4x4Sfloat, 5, 3, std::vector<uint8_t>(5 * 3)}), std::invalid_argument);
}

// The one-line message reading `file` gives, or "" when it reads.
std::string refusal(const std::vector<uint8_t>& file, Ktx2Format expected = Ktx2Format::kE5b9g9r9Ufloat) {
    try {
        decodeKtx2(file.data(), file.size(), "building_noon.ktx2", expected);
        return "";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
        return error.what();
    }
}

TEST(Ktx2, BadFilesAreRefusedNamingTheFileAndField) {
    const std::vector<uint8_t> good = encodeKtx2(lightmap());
    ASSERT_EQ(refusal(good), "");
    auto edited = [&](auto change) {
        std::vector<uint8_t> file = good;
        change(file);
        return refusal(file);
    };
    auto starts = [](const std::string& message, const std::string& prefix) {
        EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    };
    starts(refusal(std::vector<uint8_t>(good.begin(), good.begin() + 60)), "building_noon.ktx2: header: the file has 60 bytes");
    starts(refusal(std::vector<uint8_t>(good.begin(), good.end() - 5)), "building_noon.ktx2: levels[0]: bytes");
    starts(edited([](auto& file) { file[1] = 'X'; }), "building_noon.ktx2: identifier: is not the KTX 2.0 identifier");
    starts(refusal(good, Ktx2Format::kR32g32b32a32Sfloat),
           "building_noon.ktx2: vkFormat: VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 is not VK_FORMAT_R32G32B32A32_SFLOAT");
    starts(edited([](auto& file) { setU32(file, 16, 2); }), "building_noon.ktx2: typeSize: 2 is not 4");
    starts(edited([](auto& file) { setU32(file, 32, 4); }), "building_noon.ktx2: layerCount: 4 is not 0");
    starts(edited([](auto& file) { setU32(file, 40, 3); }), "building_noon.ktx2: levelCount: 3 is not 1");
    starts(edited([](auto& file) { setU32(file, 44, 2); }), "building_noon.ktx2: supercompressionScheme: 2 is not 0");
    starts(edited([](auto& file) { setU32(file, 20, 4); }), "building_noon.ktx2: levels[0].byteLength: 24 is not 4 x 2 texels");
    starts(edited([](auto& file) { setU64(file, 88, 20); }), "building_noon.ktx2: levels[0].byteLength: 20 is not 3 x 2");
    starts(edited([](auto& file) { setU64(file, 96, 99); }), "building_noon.ktx2: levels[0].uncompressedByteLength: 99");
    starts(edited([](auto& file) { setU64(file, 80, u64At(file, 80) + 2); }),
           "building_noon.ktx2: levels[0].byteOffset: ");
    starts(edited([](auto& file) { setU64(file, 80, 1ull << 40); }), "building_noon.ktx2: levels[0]: bytes 1099511627776 to");
    starts(edited([](auto& file) { setU64(file, 80, 200); }), "building_noon.ktx2: levels[0].byteOffset: 200 overlaps");
    starts(edited([](auto& file) { file.resize(file.size() + 8); }), "building_noon.ktx2: levels[0]: the file has 8 bytes after");
    starts(edited([](auto& file) { setU32(file, 132, 0); }), "building_noon.ktx2: dfd word 7: does not describe");
    starts(edited([](auto& file) { setU32(file, 52, 60); }), "building_noon.ktx2: dfdByteLength: 60 is not 124");
    starts(edited([](auto& file) { setU32(file, 60, 3000); }), "building_noon.ktx2: kvd: bytes");
    starts(edited([](auto& file) { setU32(file, u32At(file, 56), 1000); }), "building_noon.ktx2: kvd entry 0: its 1000 bytes");
    starts(edited([](auto& file) {
               const size_t at = std::string(file.begin(), file.end()).find(std::string("rd\0", 3));
               file[at + 1] = 'u';
           }),
           "building_noon.ktx2: kvd KTXorientation: 'ru' is not rd");
    // Without KTXorientation a reader may flip the image; with its key's NUL lost the key runs into the value.
    starts(edited([](auto& file) { setU32(file, 60, 0); }), "building_noon.ktx2: kvd: has no KTXorientation");
    starts(edited([](auto& file) {
               const size_t at = std::string(file.begin(), file.end()).find("KTXorientation");
               file[at] = 'k';  // "kTXorientation": an ordinary key (not KTX's), so the orientation is missing
           }),
           "building_noon.ktx2: kvd: has no KTXorientation");
    starts(edited([](auto& file) {
               const size_t at = std::string(file.begin(), file.end()).find(std::string("KTXorientation\0", 15));
               file[at + 14] = 'r';  // "KTXorientationrrd\0": the key's NUL lost
           }),
           "building_noon.ktx2: kvd entry 0: key 'KTXorientationrrd' is not one the KTX 2.0 specification defines");
    starts(edited([](auto& file) {
               const size_t at = std::string(file.begin(), file.end()).find(std::string("rd\0", 3));
               file[at + 2] = 'x';  // the value's NUL lost
           }),
           "building_noon.ktx2: kvd KTXorientation: its value does not end in a NUL");
}

}  // namespace
}  // namespace gusuku

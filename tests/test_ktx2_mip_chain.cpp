// The runtime pack's KTX 2.0 mip chains (gusuku/formats/ktx2.h), as the ASTC 6x6 sRGB base-colour textures use them:
// the level index, the DFD's block dimensions and transfer, and the levels' layout (smallest first, each aligned)
// read here by hand at the KTX 2.0 specification's offsets; a round trip of every level; each kind of bad chain
// refused in one line naming the file and the field.

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

// A 13 x 7 texture's chain of ASTC 6x6 blocks: levels 13x7 (3 x 2 blocks), 6x3, 3x1, 1x1 (one block each), every
// byte telling its level and place.
Ktx2Image chain() {
    Ktx2Image image{Ktx2Format::kAstc6x6Srgb, 13, 7, {}, {}};
    const uint32_t blocks[4] = {6, 1, 1, 1};
    for (uint32_t level = 0; level < 4; ++level) {
        std::vector<uint8_t> texels;
        for (uint32_t byte = 0; byte < blocks[level] * 16; ++byte) texels.push_back(uint8_t(level * 64 + byte));
        if (level == 0) image.texels = texels;
        else image.smaller_levels.push_back(texels);
    }
    return image;
}

std::string refusal(const std::vector<uint8_t>& file) {
    try {
        decodeKtx2MipChain(file.data(), file.size(), "texture_0_astc.ktx2", Ktx2Format::kAstc6x6Srgb);
        return "";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
        return error.what();
    }
}

void expectStart(const std::string& message, const std::string& prefix) {
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\n  expected to start with: " << prefix;
}

TEST(Ktx2MipChain, LevelsLieSmallestFirstAtTheSpecificationsOffsets) {
    EXPECT_EQ(ktx2FullLevelCount(13, 7), 4u);
    EXPECT_EQ(ktx2FullLevelCount(2048, 1024), 12u);
    EXPECT_EQ(ktx2FullLevelCount(1, 1), 1u);
    EXPECT_EQ(ktx2LevelBytes(Ktx2Format::kAstc6x6Srgb, 13, 7), 6u * 16u);
    EXPECT_EQ(ktx2LevelBytes(Ktx2Format::kAstc6x6Srgb, 2048, 2048), 342u * 342u * 16u);
    const Ktx2Image image = chain();
    const std::vector<uint8_t> file = encodeKtx2(image);
    ASSERT_GE(file.size(), 176u);
    EXPECT_EQ(u32At(file, 12), 166u);  // vkFormat VK_FORMAT_ASTC_6x6_SRGB_BLOCK
    EXPECT_EQ(u32At(file, 16), 1u);    // typeSize of a block format
    EXPECT_EQ(u32At(file, 40), 4u);    // levelCount: the full chain
    const size_t dfd = 80 + 4 * 24;    // after the header and four level entries
    EXPECT_EQ(u32At(file, 48), dfd);
    EXPECT_EQ(u32At(file, dfd + 12), 162u | 1u << 8 | 2u << 16);  // model ASTC, BT.709 primaries, sRGB transfer
    EXPECT_EQ(u32At(file, dfd + 16), 5u | 5u << 8);               // texelBlockDimension 6 x 6 (each minus 1)
    EXPECT_EQ(u32At(file, dfd + 20), 16u);                         // bytesPlane0: a block's 16 bytes
    // The levels: from the smallest (3) to the largest (0), each at a 16-byte boundary after the one before,
    // level 0 ending the file; each holds its own bytes.
    size_t previous_end = 0;
    for (uint32_t level = 4; level-- > 0;) {
        const uint64_t offset = u64At(file, 80 + 24 * level), length = u64At(file, 88 + 24 * level);
        EXPECT_EQ(u64At(file, 96 + 24 * level), length);  // uncompressedByteLength
        EXPECT_EQ(offset % 16, 0u) << level;
        EXPECT_GE(offset, previous_end) << level;
        previous_end = size_t(offset + length);
        const std::vector<uint8_t>& texels = level == 0 ? image.texels : image.smaller_levels[level - 1];
        ASSERT_EQ(length, texels.size()) << level;
        EXPECT_EQ(std::memcmp(file.data() + offset, texels.data(), texels.size()), 0) << level;
        if (level == 3) EXPECT_GT(offset, 200u);  // after the DFD and key/value data
    }
    EXPECT_EQ(previous_end, file.size());
}

TEST(Ktx2MipChain, EveryLevelComesBackAndASingleLevelReaderRefusesAChain) {
    const Ktx2Image image = chain();
    const std::vector<uint8_t> file = encodeKtx2(image);
    const Ktx2Image back = decodeKtx2MipChain(file.data(), file.size(), "texture_0_astc.ktx2", Ktx2Format::kAstc6x6Srgb);
    EXPECT_EQ(back.width, 13u);
    EXPECT_EQ(back.height, 7u);
    EXPECT_EQ(back.texels, image.texels);
    EXPECT_EQ(back.smaller_levels, image.smaller_levels);
    try {
        decodeKtx2(file.data(), file.size(), "texture_0_astc.ktx2", Ktx2Format::kAstc6x6Srgb);
        ADD_FAILURE() << "a chain was read as one level";
    } catch (const InputError& error) {
        expectStart(error.what(), "texture_0_astc.ktx2: levelCount: 4 is not 1");
    }
    // An RGBA8 chain too (the format's texels, 4-byte aligned).
    Ktx2Image rgba{Ktx2Format::kR8g8b8a8Srgb, 3, 2, std::vector<uint8_t>(3 * 2 * 4, 9), {std::vector<uint8_t>(4, 7)}};
    const std::vector<uint8_t> rgba_file = encodeKtx2(rgba);
    const Ktx2Image rgba_back =
        decodeKtx2MipChain(rgba_file.data(), rgba_file.size(), "texture.ktx2", Ktx2Format::kR8g8b8a8Srgb);
    EXPECT_EQ(rgba_back.smaller_levels, rgba.smaller_levels);
}

TEST(Ktx2MipChain, BadChainsAreRefusedNamingTheField) {
    const std::vector<uint8_t> file = encodeKtx2(chain());
    {
        std::vector<uint8_t> bytes = file;
        setU32(bytes, 40, 3);  // levelCount short of the chain
        expectStart(refusal(bytes), "texture_0_astc.ktx2: levelCount: 3 is not 4 (the full mip chain of its sides)");
    }
    {
        std::vector<uint8_t> bytes = file;
        setU64(bytes, 80 + 24 * 2 + 8, 32);  // level 2 claims two blocks
        setU64(bytes, 80 + 24 * 2 + 16, 32);
        expectStart(refusal(bytes), "texture_0_astc.ktx2: levels[2].byteLength: 32 is not 3 x 1 texels in 6 x 6 blocks");
    }
    {
        std::vector<uint8_t> bytes = file;
        setU64(bytes, 80 + 24 * 1, u64At(file, 80 + 24 * 2));  // level 1 on top of level 2
        expectStart(refusal(bytes), "texture_0_astc.ktx2: levels[1].byteOffset: ");
        EXPECT_NE(refusal(bytes).find("overlaps what precedes it"), std::string::npos) << refusal(bytes);
    }
    {
        std::vector<uint8_t> bytes = file;
        bytes.resize(bytes.size() - 16);  // level 0 cut short
        expectStart(refusal(bytes), "texture_0_astc.ktx2: levels[0]: bytes ");
    }
    {
        std::vector<uint8_t> bytes = file;
        bytes.push_back(0);
        expectStart(refusal(bytes), "texture_0_astc.ktx2: levels[0]: the file has 1 bytes after its largest level");
    }
    {
        std::vector<uint8_t> bytes(file.begin(), file.begin() + 120);  // the level index cut off
        expectStart(refusal(bytes), "texture_0_astc.ktx2: level index: bytes 80 to 176 lie outside the file");
    }
    Ktx2Image partial = chain();
    partial.smaller_levels.pop_back();
    EXPECT_THROW(encodeKtx2(partial), std::invalid_argument);
    Ktx2Image wrong = chain();
    wrong.smaller_levels[0].push_back(0);
    EXPECT_THROW(encodeKtx2(wrong), std::invalid_argument);
}

}  // namespace
}  // namespace gusuku

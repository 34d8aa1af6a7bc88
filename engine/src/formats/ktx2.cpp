// KTX 2.0 containers for the runtime pack (ktx2.h): the layout written from the KTX 2.0 specification's file
// structure, the DFD from the Data Format Specification 1.3's basic descriptor block.

#include "gusuku/formats/ktx2.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "gusuku/formats/format_table.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {
namespace {

constexpr uint8_t kIdentifier[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
constexpr size_t kHeaderBytes = 80;       // identifier 12, header 9 x 4, index 4 x 4 + 2 x 8
constexpr size_t kLevelEntryBytes = 24;   // byteOffset, byteLength, uncompressedByteLength (u64 each)
// The DFD follows the level index: one entry a level.
size_t dfdOffsetFor(uint32_t level_count) { return kHeaderBytes + kLevelEntryBytes * level_count; }
constexpr char kWriter[] = "gusuku runtime pack";

// Data Format Specification 1.3 values.
constexpr uint32_t kModelRgbsda = 1, kModelAstc = 162, kPrimariesBt709 = 1, kTransferLinear = 1, kTransferSrgb = 2;
constexpr uint32_t kChannelAlpha = 15, kQualifierLinear = 0x10, kQualifierExponent = 0x20;
constexpr uint32_t kQualifierSigned = 0x40, kQualifierFloat = 0x80;
constexpr uint32_t kFloatMinusOne = 0xBF800000u, kFloatOne = 0x3F800000u;
// The limits the Data Format Specification's float block formats (BC6H, ASTC HDR) are described with.
constexpr uint32_t kBlockFloatUpper = 0x7F800000u;

struct Sample {
    uint32_t bit_offset, bit_length, channel_type, lower, upper;
};

constexpr uint32_t kHalfMinusOne = 0xBC00u, kHalfOne = 0x3C00u;

// The format table's row of a format (gusuku/formats/format_table.h); a format no row describes is the caller's
// mistake (encodeKtx2 checks the image's; decoding compares the file's with `expected` first).
const formats::FormatRow& rowOf(Ktx2Format format) {
    const formats::FormatRow* row = formats::findFormat(uint32_t(format));
    if (row == nullptr) throw std::invalid_argument("ktx2: " + ktx2FormatName(uint32_t(format)) + " has no format row");
    return *row;
}

// The KTX 2.0 specification's typeSize: 1 for block-compressed formats, else the component's size (the table's).
uint32_t typeSizeOf(Ktx2Format format) { return rowOf(format).ktx2_type_size; }

bool isKnown(uint32_t vk_format) { return formats::findFormat(vk_format) != nullptr; }

// The DFD's samples, by how the row's texels are laid out (its codec).
std::vector<Sample> samplesOf(Ktx2Format format) {
    switch (rowOf(format).codec) {
        case formats::TexelCodec::kUnorm8: return {{0, 8, 0, 0, 255}};
        case formats::TexelCodec::kRgba8Unorm:
            return {{0, 8, 0, 0, 255}, {8, 8, 1, 0, 255}, {16, 8, 2, 0, 255}, {24, 8, kChannelAlpha, 0, 255}};
        case formats::TexelCodec::kRgba8Srgb:
            return {{0, 8, 0, 0, 255}, {8, 8, 1, 0, 255}, {16, 8, 2, 0, 255},
                    {24, 8, kChannelAlpha | kQualifierLinear, 0, 255}};
        case formats::TexelCodec::kHalfFloat: {
            // Half floats: the limits -1 and 1 in the sample's own 16 bits.
            const uint32_t real = kQualifierFloat | kQualifierSigned;
            return {{0, 16, 0 | real, kHalfMinusOne, kHalfOne}, {16, 16, 1 | real, kHalfMinusOne, kHalfOne},
                    {32, 16, 2 | real, kHalfMinusOne, kHalfOne},
                    {48, 16, kChannelAlpha | real, kHalfMinusOne, kHalfOne}};
        }
        case formats::TexelCodec::kFloat32: {
            const uint32_t real = kQualifierFloat | kQualifierSigned;
            return {{0, 32, 0 | real, kFloatMinusOne, kFloatOne}, {32, 32, 1 | real, kFloatMinusOne, kFloatOne},
                    {64, 32, 2 | real, kFloatMinusOne, kFloatOne},
                    {96, 32, kChannelAlpha | real, kFloatMinusOne, kFloatOne}};
        }
        case formats::TexelCodec::kSharedExponent: {
            // Each channel: its 9-bit mantissa, then the shared 5-bit exponent (bias 15) as an exponent sample;
            // the limits are those libktx's vk2dfd gives the format (mantissa upper 8448, exponent 15 to 31).
            std::vector<Sample> samples;
            for (uint32_t channel = 0; channel < 3; ++channel) {
                samples.push_back({9 * channel, 9, channel, 0, 8448});
                samples.push_back({27, 5, channel | kQualifierExponent, 15, 31});
            }
            return samples;
        }
        case formats::TexelCodec::kAstcHdr:
            // One sample over the 128-bit block, channel ASTC_DATA (0), signed float (the Data Format
            // Specification's compressed-format table for the HDR ASTC formats).
            return {{0, 128, 0 | kQualifierFloat | kQualifierSigned, kFloatMinusOne, kBlockFloatUpper}};
        case formats::TexelCodec::kAstcLdrSrgb:
            // One sample over the block, channel ASTC_DATA, unsigned normalised (limits 0 and 0xFFFFFFFF, as
            // vk2dfd gives the LDR ASTC formats); the sRGB transfer is the descriptor's, not the sample's.
            return {{0, 128, 0, 0, 0xFFFFFFFFu}};
    }
    return {};
}

// The DFD as written: dfdTotalSize, then one basic descriptor block.
std::vector<uint32_t> dfdWords(Ktx2Format format) {
    const std::vector<Sample> samples = samplesOf(format);
    const uint32_t block_bytes = 24 + 16 * uint32_t(samples.size());
    const formats::TexelCodec codec = rowOf(format).codec;
    const bool srgb = codec == formats::TexelCodec::kRgba8Srgb || codec == formats::TexelCodec::kAstcLdrSrgb;
    const uint32_t transfer = srgb ? kTransferSrgb : kTransferLinear;
    const bool astc = ktx2IsBlockFormat(format);
    const uint32_t side = ktx2BlockSide(format);
    const uint32_t block_dimensions = astc ? (side - 1) | (side - 1) << 8 : 0;  // texelBlockDimension0..3, minus 1
    std::vector<uint32_t> words = {4 + block_bytes, 0, 2u | block_bytes << 16,
                                   (astc ? kModelAstc : kModelRgbsda) | kPrimariesBt709 << 8 | transfer << 16,
                                   block_dimensions, ktx2TexelBytes(format), 0};
    for (const Sample& sample : samples) {
        words.push_back(sample.bit_offset | (sample.bit_length - 1) << 16 | sample.channel_type << 24);
        words.push_back(0);  // sample position 0, 0, 0, 0
        words.push_back(sample.lower);
        words.push_back(sample.upper);
    }
    return words;
}

// Key/value data: KTXorientation then KTXwriter (sorted by key, as the specification requires), each entry
// padded to 4 bytes.
std::vector<uint8_t> keyValueData() {
    std::vector<uint8_t> bytes;
    auto entry = [&](const std::string& key, const std::string& value) {
        const uint32_t length = uint32_t(key.size() + 1 + value.size() + 1);
        for (int shift = 0; shift < 32; shift += 8) bytes.push_back(uint8_t(length >> shift));
        bytes.insert(bytes.end(), key.begin(), key.end());
        bytes.push_back(0);
        bytes.insert(bytes.end(), value.begin(), value.end());
        bytes.push_back(0);
        while (bytes.size() % 4 != 0) bytes.push_back(0);
    };
    entry("KTXorientation", "rd");
    entry("KTXwriter", kWriter);
    return bytes;
}

// The specification's level alignment without supercompression: lcm(texel block size, 4).
size_t levelAlignment(Ktx2Format format) { return std::lcm(size_t(ktx2TexelBytes(format)), size_t(4)); }

// The keys KTX 2.0 defines (section 5.3); a key starting "KTX" is reserved to them.
bool isKtxDefinedKey(const std::string& key) {
    for (const char* defined : {"KTXcubemapIncomplete", "KTXorientation", "KTXglFormat", "KTXdxgiFormat__",
                                "KTXmetalPixelFormat", "KTXswizzle", "KTXwriter", "KTXwriterScParams",
                                "KTXastcDecodeMode", "KTXanimData"})
        if (key == defined) return true;
    return false;
}
// Those whose value is a NUL-terminated string (the others hold binary numbers).
bool ktxKeyHasTextValue(const std::string& key) {
    return key == "KTXorientation" || key == "KTXswizzle" || key == "KTXwriter" || key == "KTXwriterScParams" ||
           key == "KTXastcDecodeMode";
}

size_t alignedUp(size_t value, size_t alignment) { return (value + alignment - 1) / alignment * alignment; }

void putU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value) {
    for (int index = 0; index < 4; ++index) bytes[at + index] = uint8_t(value >> (8 * index));
}
void putU64(std::vector<uint8_t>& bytes, size_t at, uint64_t value) {
    for (int index = 0; index < 8; ++index) bytes[at + index] = uint8_t(value >> (8 * index));
}
uint32_t getU32(const uint8_t* bytes) {
    return uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24;
}
uint64_t getU64(const uint8_t* bytes) { return uint64_t(getU32(bytes)) | uint64_t(getU32(bytes + 4)) << 32; }

}  // namespace

std::string ktx2FormatName(uint32_t vk_format) {
    const formats::FormatRow* row = formats::findFormat(vk_format);
    return row != nullptr ? row->vk_name : "VkFormat " + std::to_string(vk_format);
}

bool ktx2IsBlockFormat(Ktx2Format format) {
    const formats::FormatRow* row = formats::findFormat(uint32_t(format));
    return row != nullptr && formats::isBlockCodec(row->codec);
}

uint32_t ktx2BlockSide(Ktx2Format format) {
    const formats::FormatRow* row = formats::findFormat(uint32_t(format));
    return row != nullptr ? row->block_side : 1;
}

uint32_t ktx2FullLevelCount(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    for (uint32_t side = std::max(width, height); side > 1; side >>= 1) ++levels;
    return levels;
}

uint32_t ktx2TexelBytes(Ktx2Format format) {
    const formats::FormatRow* row = formats::findFormat(uint32_t(format));
    return row != nullptr ? row->block_bytes : 0;
}

uint64_t ktx2LevelBytes(Ktx2Format format, uint32_t width, uint32_t height) {
    const uint64_t side = ktx2BlockSide(format);
    return (uint64_t(width) + side - 1) / side * ((uint64_t(height) + side - 1) / side) * ktx2TexelBytes(format);
}

namespace {

uint32_t levelSide(uint32_t side, uint32_t level) { return std::max(1u, side >> level); }

// Level `level`'s texels of `image` (0: texels; then smaller_levels).
const std::vector<uint8_t>& levelTexels(const Ktx2Image& image, uint32_t level) {
    return level == 0 ? image.texels : image.smaller_levels[level - 1];
}

}  // namespace

std::vector<uint8_t> encodeKtx2(const Ktx2Image& image) {
    if (!isKnown(uint32_t(image.format))) throw std::invalid_argument("encodeKtx2: unknown format");
    if (image.width == 0 || image.height == 0) throw std::invalid_argument("encodeKtx2: a side is 0");
    const uint32_t level_count = uint32_t(1 + image.smaller_levels.size());
    if (level_count != 1 && level_count != ktx2FullLevelCount(image.width, image.height))
        throw std::invalid_argument("encodeKtx2: smaller_levels is neither empty nor the rest of the full chain");
    std::vector<size_t> level_bytes(level_count);
    for (uint32_t level = 0; level < level_count; ++level) {
        level_bytes[level] = size_t(ktx2LevelBytes(image.format, levelSide(image.width, level),
                                                   levelSide(image.height, level)));
        if (levelTexels(image, level).size() != level_bytes[level])
            throw std::invalid_argument("encodeKtx2: level " + std::to_string(level) +
                                        " is not its width x height texels (or blocks) of the format");
    }
    const std::vector<uint32_t> dfd = dfdWords(image.format);
    const std::vector<uint8_t> kvd = keyValueData();
    const size_t dfd_offset = dfdOffsetFor(level_count);
    const size_t kvd_offset = dfd_offset + dfd.size() * 4;
    // The levels, smallest first (the specification's order), each aligned.
    std::vector<size_t> level_offsets(level_count);
    size_t end = kvd_offset + kvd.size();
    for (uint32_t level = level_count; level-- > 0;) {
        level_offsets[level] = alignedUp(end, levelAlignment(image.format));
        end = level_offsets[level] + level_bytes[level];
    }
    std::vector<uint8_t> bytes(end, 0);
    std::memcpy(bytes.data(), kIdentifier, sizeof kIdentifier);
    const uint32_t header[9] = {uint32_t(image.format), typeSizeOf(image.format), image.width, image.height, 0, 0, 1,
                                level_count, 0};
    for (int field = 0; field < 9; ++field) putU32(bytes, 12 + 4 * field, header[field]);
    putU32(bytes, 48, uint32_t(dfd_offset));
    putU32(bytes, 52, uint32_t(dfd.size() * 4));
    putU32(bytes, 56, uint32_t(kvd_offset));
    putU32(bytes, 60, uint32_t(kvd.size()));
    putU64(bytes, 64, 0);  // no supercompression global data
    putU64(bytes, 72, 0);
    for (uint32_t level = 0; level < level_count; ++level) {
        const size_t entry = kHeaderBytes + kLevelEntryBytes * level;
        putU64(bytes, entry, level_offsets[level]);
        putU64(bytes, entry + 8, level_bytes[level]);
        putU64(bytes, entry + 16, level_bytes[level]);
        std::memcpy(bytes.data() + level_offsets[level], levelTexels(image, level).data(), level_bytes[level]);
    }
    for (size_t word = 0; word < dfd.size(); ++word) putU32(bytes, dfd_offset + 4 * word, dfd[word]);
    std::memcpy(bytes.data() + kvd_offset, kvd.data(), kvd.size());
    return bytes;
}

namespace {

// Reads the parts of one container, each checked before it is used.
class Ktx2Reader {
public:
    Ktx2Reader(const uint8_t* bytes, size_t size, const std::string& file) : bytes_(bytes), size_(size), file_(file) {}

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw InputError(file_, field, problem);
    }

    void need(size_t offset, size_t length, const std::string& field) const {
        if (offset > size_ || length > size_ - offset)
            fail(field, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                            " lie outside the file of " + std::to_string(size_) + " bytes (truncated?)");
    }
    uint32_t u32(size_t offset) const { return getU32(bytes_ + offset); }
    uint64_t u64(size_t offset) const { return getU64(bytes_ + offset); }

    void expectU32(size_t offset, const std::string& field, uint32_t expected, const std::string& why) const {
        const uint32_t value = u32(offset);
        if (value != expected) fail(field, std::to_string(value) + " is not " + std::to_string(expected) + " (" + why + ")");
    }

    // Returns the level count: 1, or with `mip_chain` the full chain's.
    uint32_t checkHeader(Ktx2Format expected, bool mip_chain) const {
        if (size_ < kHeaderBytes + kLevelEntryBytes)
            fail("header", "the file has " + std::to_string(size_) + " bytes, fewer than the 104 of a KTX2 header, "
                           "index and one level entry (truncated?)");
        if (std::memcmp(bytes_, kIdentifier, sizeof kIdentifier) != 0)
            fail("identifier", "is not the KTX 2.0 identifier (not a KTX2 file)");
        const uint32_t format = u32(12);
        if (format != uint32_t(expected))
            fail("vkFormat", ktx2FormatName(format) + " is not " + ktx2FormatName(uint32_t(expected)) +
                                 ", the format this file holds in a runtime pack");
        expectU32(16, "typeSize", typeSizeOf(expected), "the format's type size");
        if (u32(20) == 0 || u32(24) == 0) fail("pixelWidth/pixelHeight", "a side is 0");
        expectU32(28, "pixelDepth", 0, "a 2D image");
        expectU32(32, "layerCount", 0, "one image, not an array");
        expectU32(36, "faceCount", 1, "not a cube map");
        const uint32_t level_count = mip_chain ? ktx2FullLevelCount(u32(20), u32(24)) : 1;
        expectU32(40, "levelCount", level_count,
                  mip_chain ? "the full mip chain of its sides" : "the pack holds one level of this file");
        expectU32(44, "supercompressionScheme", 0, "the pack is not supercompressed");
        if (u64(64) != 0 || u64(72) != 0) fail("sgdByteOffset/sgdByteLength", "is not 0 (no supercompression)");
        need(kHeaderBytes, kLevelEntryBytes * level_count, "level index");
        return level_count;
    }

    // The DFD must be, word for word, the one the format is written with. Returns where it ends.
    size_t checkDfd(Ktx2Format format, uint32_t level_count) const {
        const std::vector<uint32_t> expected = dfdWords(format);
        const uint32_t offset = u32(48), length = u32(52);
        if (offset != dfdOffsetFor(level_count))
            fail("dfdByteOffset", std::to_string(offset) + " is not " + std::to_string(dfdOffsetFor(level_count)) +
                                      " (right after the level index)");
        if (length != expected.size() * 4)
            fail("dfdByteLength", std::to_string(length) + " is not " + std::to_string(expected.size() * 4) +
                                      ", the descriptor of " + ktx2FormatName(uint32_t(format)));
        need(offset, length, "dfd");
        for (size_t word = 0; word < expected.size(); ++word)
            if (u32(offset + 4 * word) != expected[word])
                fail("dfd word " + std::to_string(word), "does not describe " + ktx2FormatName(uint32_t(format)) +
                                                             " (" + std::to_string(u32(offset + 4 * word)) + ", expected " +
                                                             std::to_string(expected[word]) + ")");
        return offset + length;
    }

    // Key/value entries well formed inside their region, which follows the DFD: each key ends in its NUL, each of
    // the specification's own keys (KTX...) is one it defines and its text value ends in a NUL too, and
    // KTXorientation is there and "rd" (row 0 at the top, as the pack writes; without it a reader may flip the
    // image). A key whose NUL was lost runs into its value ("KTXorientationrd"), an unknown KTX key, so it is
    // refused rather than skipped. Returns where the region ends.
    size_t checkKeyValueData(size_t dfd_end) const {
        const uint32_t offset = u32(56), length = u32(60);
        if (length == 0) fail("kvd", "has no KTXorientation (the key/value data is empty)");
        if (offset < dfd_end) fail("kvdByteOffset", std::to_string(offset) + " overlaps the DFD (ends at " + std::to_string(dfd_end) + ")");
        need(offset, length, "kvd");
        size_t at = offset;
        const size_t end = size_t(offset) + length;
        bool has_orientation = false;
        for (int entry = 0; at < end; ++entry) {
            const std::string field = "kvd entry " + std::to_string(entry);
            if (end - at < 4) fail(field, "its length runs past the key/value data");
            const uint32_t entry_bytes = u32(at);
            if (entry_bytes > end - at - 4) fail(field, "its " + std::to_string(entry_bytes) + " bytes run past the key/value data");
            const char* text = reinterpret_cast<const char*>(bytes_ + at + 4);
            const void* nul = std::memchr(text, 0, entry_bytes);
            if (nul == nullptr) fail(field, "its key has no terminating NUL");
            const std::string key(text, static_cast<const char*>(nul));
            std::string value(static_cast<const char*>(nul) + 1, text + entry_bytes);
            if (key.rfind("KTX", 0) == 0) {
                if (!isKtxDefinedKey(key))
                    fail(field, "key " + quotedForMessage(key) + " is not one the KTX 2.0 specification defines (a key "
                                "that lost its NUL runs into its value)");
                if (ktxKeyHasTextValue(key) && (value.empty() || value.back() != '\0'))
                    fail("kvd " + key, "its value does not end in a NUL");
            }
            while (!value.empty() && value.back() == '\0') value.pop_back();  // string values end in NUL
            if (key == "KTXorientation") {
                if (value.rfind("rd", 0) != 0)
                    fail("kvd KTXorientation", quotedForMessage(value) + " is not rd (row 0 at the top, as the pack writes)");
                has_orientation = true;
            }
            at = alignedUp(at + 4 + entry_bytes, 4);
        }
        if (!has_orientation) fail("kvd", "has no KTXorientation (the pack writes \"rd\": row 0 at the top)");
        return end;
    }

    // Every level, the smallest first in the file: each after what precedes it (the header, DFD and key/value
    // data, then the smaller level), and level 0 ending the file.
    Ktx2Image levels(Ktx2Format format, size_t parts_end, uint32_t level_count) const {
        Ktx2Image image{format, u32(20), u32(24), {}, {}};
        image.smaller_levels.resize(level_count - 1);
        size_t previous_end = parts_end;
        for (uint32_t level = level_count; level-- > 0;) {
            std::vector<uint8_t>& texels = level == 0 ? image.texels : image.smaller_levels[level - 1];
            previous_end = readLevel(format, level, levelSide(image.width, level), levelSide(image.height, level),
                                     previous_end, texels);
        }
        if (previous_end != size_)
            fail("levels[0]", "the file has " + std::to_string(size_ - previous_end) +
                                  " bytes after its largest level (levels do not add up to the file)");
        return image;
    }

private:
    // Level `level` (width x height) into `texels`; returns where it ends.
    size_t readLevel(Ktx2Format format, uint32_t level, uint32_t width, uint32_t height, size_t previous_end,
                     std::vector<uint8_t>& texels) const {
        const std::string field = "levels[" + std::to_string(level) + "]";
        const size_t entry = kHeaderBytes + kLevelEntryBytes * level;
        const uint64_t offset = u64(entry), length = u64(entry + 8);
        const uint64_t expected = ktx2LevelBytes(format, width, height);
        const uint32_t side = ktx2BlockSide(format);
        const std::string unit = side > 1 ? " texels in " + std::to_string(side) + " x " + std::to_string(side) +
                                                " blocks of "
                                          : std::string(" texels of ");
        if (length != expected)
            fail(field + ".byteLength", std::to_string(length) + " is not " + std::to_string(width) + " x " +
                                            std::to_string(height) + unit + std::to_string(ktx2TexelBytes(format)) +
                                            " bytes (" + std::to_string(expected) + ")");
        if (u64(entry + 16) != length)
            fail(field + ".uncompressedByteLength", std::to_string(u64(entry + 16)) + " is not its byteLength " +
                                                        std::to_string(length) + " (no supercompression)");
        if (offset % levelAlignment(format) != 0)
            fail(field + ".byteOffset", std::to_string(offset) + " is not a multiple of " +
                                            std::to_string(levelAlignment(format)));
        if (offset < previous_end)
            fail(field + ".byteOffset", std::to_string(offset) + " overlaps what precedes it (the header, DFD, "
                                        "key/value data and smaller levels end at " + std::to_string(previous_end) + ")");
        if (offset > size_ || length > size_ - offset)
            fail(field, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                            " lie outside the file of " + std::to_string(size_) + " bytes (truncated?)");
        texels.assign(bytes_ + offset, bytes_ + offset + length);
        return size_t(offset + length);
    }

public:

private:
    const uint8_t* bytes_;
    size_t size_;
    const std::string& file_;
};

}  // namespace

namespace {

Ktx2Image decode(const uint8_t* bytes, size_t size, const std::string& file, Ktx2Format expected, bool mip_chain) {
    const Ktx2Reader reader(bytes, size, file);
    const uint32_t level_count = reader.checkHeader(expected, mip_chain);
    const size_t dfd_end = reader.checkDfd(expected, level_count);
    const size_t parts_end = reader.checkKeyValueData(dfd_end);
    return reader.levels(expected, parts_end, level_count);
}

}  // namespace

Ktx2Image decodeKtx2(const uint8_t* bytes, size_t size, const std::string& file, Ktx2Format expected) {
    return decode(bytes, size, file, expected, false);
}

Ktx2Image decodeKtx2MipChain(const uint8_t* bytes, size_t size, const std::string& file, Ktx2Format expected) {
    return decode(bytes, size, file, expected, true);
}

}  // namespace gusuku

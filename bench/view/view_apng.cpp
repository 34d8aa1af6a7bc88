// An animated PNG from PNG files (see view_apng.h; the chunks are the APNG specification's, version 1.0).

#include "view_apng.h"

#include <array>
#include <cstring>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/formats/input_error.h"

namespace gusuku::view {

namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

struct Chunk {
    std::string type;
    std::string data;
};

uint32_t crc32(const std::string& type, const std::string& data) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> values{};
        for (uint32_t index = 0; index < 256; ++index) {
            uint32_t value = index;
            for (int bit = 0; bit < 8; ++bit) value = (value & 1) ? 0xedb88320u ^ (value >> 1) : value >> 1;
            values[index] = value;
        }
        return values;
    }();
    uint32_t crc = 0xffffffffu;
    for (const std::string* part : {&type, &data})
        for (unsigned char byte : *part) crc = table[(crc ^ byte) & 0xff] ^ (crc >> 8);
    return crc ^ 0xffffffffu;
}

void appendBigEndian(std::string& out, uint32_t value, int bytes = 4) {
    for (int shift = (bytes - 1) * 8; shift >= 0; shift -= 8) out.push_back(char((value >> shift) & 0xff));
}

uint32_t readBigEndian(const std::string& bytes, size_t offset) {
    uint32_t value = 0;
    for (size_t index = 0; index < 4; ++index) value = (value << 8) | uint32_t(uint8_t(bytes[offset + index]));
    return value;
}

void appendChunk(std::string& out, const std::string& type, const std::string& data) {
    appendBigEndian(out, uint32_t(data.size()));
    out += type;
    out += data;
    appendBigEndian(out, crc32(type, data));
}

std::vector<Chunk> readChunks(const std::string& path) {
    const std::string bytes = readWholeFile(path);
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) throw InputError(path, "", "is not a PNG");
    std::vector<Chunk> chunks;
    for (size_t offset = 8; offset + 12 <= bytes.size();) {
        const uint32_t length = readBigEndian(bytes, offset);
        if (offset + 12 + size_t(length) > bytes.size()) throw InputError(path, "", "a chunk runs past the file's end");
        chunks.push_back({bytes.substr(offset + 4, 4), bytes.substr(offset + 8, length)});
        offset += 12 + size_t(length);
    }
    if (chunks.empty() || chunks.front().type != "IHDR") throw InputError(path, "", "does not start with IHDR");
    return chunks;
}

}  // namespace

void writeApng(const std::vector<std::string>& frame_pngs, const std::string& out_path, uint16_t delay_numerator,
               uint16_t delay_denominator) {
    if (frame_pngs.empty()) throw InputError(out_path, "", "no frames to write");
    std::string out(reinterpret_cast<const char*>(kSignature), 8);
    std::string ihdr;
    uint32_t sequence = 0;
    for (size_t index = 0; index < frame_pngs.size(); ++index) {
        const std::vector<Chunk> chunks = readChunks(frame_pngs[index]);
        if (index == 0) {
            ihdr = chunks.front().data;
            appendChunk(out, "IHDR", ihdr);
            std::string actl;
            appendBigEndian(actl, uint32_t(frame_pngs.size()));
            appendBigEndian(actl, 0);  // plays: 0 loops for ever
            appendChunk(out, "acTL", actl);
            // The first frame's ancillary chunks before its image data (colour space, gamma) describe them all.
            for (size_t chunk = 1; chunk < chunks.size() && chunks[chunk].type != "IDAT"; ++chunk)
                appendChunk(out, chunks[chunk].type, chunks[chunk].data);
        } else if (chunks.front().data != ihdr) {
            throw InputError(frame_pngs[index], "", "has another size or pixel format than the first frame");
        }
        std::string fctl;
        appendBigEndian(fctl, sequence++);
        fctl += ihdr.substr(0, 8);  // width and height: the whole canvas
        appendBigEndian(fctl, 0);   // x offset
        appendBigEndian(fctl, 0);   // y offset
        appendBigEndian(fctl, delay_numerator, 2);
        appendBigEndian(fctl, delay_denominator, 2);
        fctl.push_back(0);  // dispose: none (the next frame covers the canvas)
        fctl.push_back(0);  // blend: source (replace, alpha included)
        appendChunk(out, "fcTL", fctl);
        for (const Chunk& chunk : chunks) {
            if (chunk.type != "IDAT") continue;
            if (index == 0) {
                appendChunk(out, "IDAT", chunk.data);  // the default image, what a plain PNG reader shows
            } else {
                std::string fdat;
                appendBigEndian(fdat, sequence++);
                appendChunk(out, "fdAT", fdat + chunk.data);
            }
        }
    }
    appendChunk(out, "IEND", "");
    writeBytesAtomically(out_path, out.data(), out.size());
}

}  // namespace gusuku::view

#pragma once
// FNV-1a 64-bit content hashes: cheap fingerprints of a bake's inputs, so a resumed bake can prove that its
// checkpoint belongs to the same inputs and the manifest can record what was baked. Not cryptographic.

#include <cstdint>
#include <string>

namespace gusuku::bake {

class ContentHash {
public:
    ContentHash& addBytes(const void* bytes, size_t byte_count);
    ContentHash& addString(const std::string& text);  ///< length-prefixed, so ("ab","c") != ("a","bc")
    ContentHash& addFile(const std::string& path);    ///< throws InputError when the file cannot be read
    template <typename T> ContentHash& addValue(const T& value) { return addBytes(&value, sizeof value); }
    uint64_t value() const { return state_; }
    std::string hex() const;  ///< 16 lowercase hex digits

private:
    uint64_t state_ = 14695981039346656037ull;
};

/// Hex FNV-1a 64 of a whole file.
std::string hashFileHex(const std::string& path);

}  // namespace gusuku::bake

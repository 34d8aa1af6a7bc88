#include "gusuku_bake/content_hash.h"

#include <cstdio>

#include "gusuku/assets/atomic_file.h"

namespace gusuku::bake {

ContentHash& ContentHash::addBytes(const void* bytes, size_t byte_count) {
    const auto* data = static_cast<const unsigned char*>(bytes);
    for (size_t i = 0; i < byte_count; ++i) {
        state_ ^= data[i];
        state_ *= 1099511628211ull;
    }
    return *this;
}

ContentHash& ContentHash::addString(const std::string& text) {
    const uint64_t length = text.size();
    addValue(length);
    return addBytes(text.data(), text.size());
}

ContentHash& ContentHash::addFile(const std::string& path) {
    return addString(readWholeFile(path));
}

std::string ContentHash::hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
    return text;
}

std::string hashFileHex(const std::string& path) { return ContentHash().addFile(path).hex(); }

}  // namespace gusuku::bake

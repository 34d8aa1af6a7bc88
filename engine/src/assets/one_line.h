#pragma once
// Library messages (tinygltf, OpenImageIO, libpng) often span several lines; an InputError's problem is one line
// (FILE: FIELD: PROBLEM), so they are folded here. Private to gusuku_assets.

#include <string>

namespace gusuku {

/// The non-empty lines of `text`, trimmed and joined with "; ".
inline std::string oneLine(const std::string& text) {
    std::string folded, line;
    const auto flush = [&] {
        const size_t first = line.find_first_not_of(" \t\r");
        const size_t last = line.find_last_not_of(" \t\r");
        if (first != std::string::npos) folded += (folded.empty() ? "" : "; ") + line.substr(first, last - first + 1);
        line.clear();
    };
    for (const char c : text) {
        if (c == '\n')
            flush();
        else
            line += c;
    }
    flush();
    return folded;
}

}  // namespace gusuku

#pragma once
// A small JSON reader (RFC 8259) for the runtime pack's manifest and Open-Meteo's answers, so that
// gusuku_pack_loader and gusuku_weather need the C++ standard library alone (a phone build has no nlohmann-json).
// Library gusuku_json, private to those two (this header is not installed). Strict: one value and nothing after it but white space, no
// duplicate keys, strings valid UTF-8 escapes, numbers as RFC 8259 writes them (read locale-independently),
// nesting at most 64 deep. Errors are InputError(file, "byte N", problem), N counted
// from 0.

#include <string>
#include <vector>

namespace gusuku::json_detail {

struct JsonValue {
    enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };
    Type type = Type::kNull;
    bool boolean = false;
    double number = 0.0;
    std::string text;
    std::vector<JsonValue> items;     ///< kArray; kObject: the members' values, in file order
    std::vector<std::string> keys;    ///< kObject: the members' names, one per items entry (a vector of pairs of
                                      ///< an incomplete type does not compile with every standard library)

    /// The member named `key`, or null when there is none (kObject only).
    const JsonValue* find(const std::string& key) const;
};

JsonValue parseJson(const std::string& text, const std::string& file);

}  // namespace gusuku::json_detail

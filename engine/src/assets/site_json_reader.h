#pragma once
// Checked reading of a JSON configuration file (site.json): every field's type and range is checked, unknown
// names are rejected, and every problem becomes InputError(file, "/json/pointer", problem). Private to the
// engine; the format itself lives in site.cpp.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gusuku::json_reader {

/// A closed or open interval of allowed numbers, e.g. [-90, 90] or (0, 1000].
struct NumberRange {
    double min = 0.0;
    double max = 0.0;
    bool min_open = false;  ///< true: min itself is not allowed
    bool max_open = false;  ///< true: max itself is not allowed
    bool contains(double number) const;
    std::string describe() const;  ///< "[-90, 90]", "(0, 1000]"
};

/// The shortest text that reads back as `number` ("200", "0.25", "1e+06").
std::string formatNumber(double number);

/// RFC 6901 escaping of one pointer token ("~" -> "~0", "/" -> "~1").
std::string escapePointerToken(const std::string& token);

/// Parses a whole document. Syntax errors become InputError(file, "byte N", parser message); a name that
/// appears twice in one object (which the JSON parser would silently resolve to the last) is an error too.
nlohmann::json parseDocument(const std::string& file, const std::string& text);

/// One JSON object being read. Rejects names not in `known_fields` on construction, so a misspelt optional
/// field cannot silently fall back to its default.
class ObjectReader {
public:
    ObjectReader(std::string file, const nlohmann::json& object, std::string pointer,
                 std::initializer_list<const char*> known_fields);

    const std::string& file() const { return file_; }
    const std::string& pointer() const { return pointer_; }
    std::string fieldPointer(const std::string& name) const;
    bool has(const std::string& name) const;

    [[noreturn]] void fail(const std::string& name, const std::string& problem) const;

    /// Required field (missing -> error).
    const nlohmann::json& required(const std::string& name) const;

    double number(const std::string& name, const NumberRange& range) const;
    double number(const std::string& name, const NumberRange& range, double default_value) const;
    std::optional<double> optionalNumber(const std::string& name, const NumberRange& range) const;
    /// A whole number (1e2 and 100.0 are accepted; 100.5 is not) within [min, max].
    int64_t integer(const std::string& name, int64_t min, int64_t max, int64_t default_value) const;
    std::string string(const std::string& name) const;
    /// A required array of exactly `count` numbers, each within `range`.
    std::vector<double> numberArray(const std::string& name, size_t count, const NumberRange& range) const;
    /// A required array (elements unchecked); the caller reads each element.
    const nlohmann::json& array(const std::string& name) const;

    ObjectReader object(const std::string& name, std::initializer_list<const char*> known_fields) const;
    std::optional<ObjectReader> optionalObject(const std::string& name,
                                               std::initializer_list<const char*> known_fields) const;

private:
    std::string file_;
    const nlohmann::json* object_;
    std::string pointer_;
};

/// Checks that `value` (at `pointer`) is a finite number within `range`; returns it.
double checkedNumber(const std::string& file, const std::string& pointer, const nlohmann::json& value,
                     const NumberRange& range);
/// Checks that `value` is a string; returns it.
std::string checkedString(const std::string& file, const std::string& pointer, const nlohmann::json& value);

/// "a string", "a number", "an object", ... for "expected X, found Y" messages.
std::string describeJsonType(const nlohmann::json& value);

}  // namespace gusuku::json_reader

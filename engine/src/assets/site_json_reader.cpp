#include "site_json_reader.h"

#include <charconv>
#include <cmath>
#include <set>

#include "gusuku/formats/input_error.h"

namespace gusuku::json_reader {

bool NumberRange::contains(double number) const {
    const bool above_min = min_open ? number > min : number >= min;
    const bool below_max = max_open ? number < max : number <= max;
    return above_min && below_max;
}

std::string NumberRange::describe() const {
    return std::string(min_open ? "(" : "[") + formatNumber(min) + ", " + formatNumber(max) +
           (max_open ? ")" : "]");
}

std::string formatNumber(double number) {
    // Whole numbers print in full ("1000000", not "1e+06"): range messages read better that way.
    if (number == std::floor(number) && std::fabs(number) < 1e15) return std::to_string(int64_t(number));
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), number);
    return std::string(buffer, result.ptr);
}

std::string escapePointerToken(const std::string& token) {
    std::string escaped;
    for (const char c : token) {
        if (c == '~')
            escaped += "~0";
        else if (c == '/')
            escaped += "~1";
        else
            escaped += c;
    }
    return escaped;
}

std::string describeJsonType(const nlohmann::json& value) {
    switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return "a number";
    default: return "an unsupported value";
    }
}

namespace {

/// Where the parser is, for naming a duplicated key by its JSON pointer.
struct ContainerFrame {
    bool is_object = false;
    std::set<std::string> keys;  ///< objects: the names seen so far
    std::string current_key;     ///< objects: the member being parsed
    size_t index = 0;            ///< arrays: the element being parsed
};

std::string pointerOf(const std::vector<ContainerFrame>& frames) {
    std::string pointer;
    for (const ContainerFrame& frame : frames)
        pointer += "/" + (frame.is_object ? escapePointerToken(frame.current_key) : std::to_string(frame.index));
    return pointer;
}

void finishElement(std::vector<ContainerFrame>& frames) {
    if (!frames.empty() && !frames.back().is_object) ++frames.back().index;
}

std::string withoutExceptionPrefix(const std::string& message) {
    // nlohmann's messages start with "[json.exception.parse_error.101] "; the id means nothing to a user.
    if (!message.empty() && message.front() == '[') {
        const size_t end = message.find("] ");
        if (end != std::string::npos) return message.substr(end + 2);
    }
    return message;
}

}  // namespace

nlohmann::json parseDocument(const std::string& file, const std::string& text) {
    std::vector<ContainerFrame> frames;
    const nlohmann::json::parser_callback_t track = [&](int, nlohmann::json::parse_event_t event,
                                                        nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
        case Event::object_start: frames.push_back({true, {}, {}, 0}); break;
        case Event::array_start: frames.push_back({false, {}, {}, 0}); break;
        case Event::key: {
            ContainerFrame& object = frames.back();
            object.current_key = parsed.get<std::string>();
            if (!object.keys.insert(object.current_key).second)
                throw InputError(file, pointerOf(frames), "appears twice in the same object");
            break;
        }
        case Event::object_end:
        case Event::array_end:
            frames.pop_back();
            finishElement(frames);
            break;
        case Event::value: finishElement(frames); break;
        }
        return true;
    };
    try {
        // Comments (// and /* */) are allowed: `gusuku-bake init` writes a starter whose comments explain it.
        return nlohmann::json::parse(text, track, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::parse_error& error) {
        throw InputError(file, "byte " + std::to_string(error.byte),
                         "invalid JSON: " + withoutExceptionPrefix(error.what()));
    } catch (const nlohmann::json::out_of_range& error) {
        // A literal such as 1e999 overflows a double; the parser refuses it (error 406) without a position,
        // but the tracked frames still name the member being parsed.
        throw InputError(file, pointerOf(frames),
                         "is not a finite number (" + withoutExceptionPrefix(error.what()) + ")");
    }
}

double checkedNumber(const std::string& file, const std::string& pointer, const nlohmann::json& value,
                     const NumberRange& range) {
    if (!value.is_number())
        throw InputError(file, pointer, "expected a number, found " + describeJsonType(value));
    const double number = value.get<double>();
    // JSON has no NaN or infinity, but a literal such as 1e999 overflows to infinity when parsed.
    if (!std::isfinite(number))
        throw InputError(file, pointer, "is not a finite number (it overflows a double)");
    if (!range.contains(number))
        throw InputError(file, pointer, formatNumber(number) + " is outside " + range.describe());
    return number;
}

std::string checkedString(const std::string& file, const std::string& pointer, const nlohmann::json& value) {
    if (!value.is_string()) throw InputError(file, pointer, "expected a string, found " + describeJsonType(value));
    return value.get<std::string>();
}

ObjectReader::ObjectReader(std::string file, const nlohmann::json& object, std::string pointer,
                           std::initializer_list<const char*> known_fields)
    : file_(std::move(file)), object_(&object), pointer_(std::move(pointer)) {
    if (!object.is_object())
        throw InputError(file_, pointer_, "expected an object, found " + describeJsonType(object));
    for (const auto& member : object.items()) {
        bool known = false;
        for (const char* name : known_fields) known = known || member.key() == name;
        if (known) continue;
        std::string expected;
        for (const char* name : known_fields) expected += std::string(expected.empty() ? "" : ", ") + name;
        throw InputError(file_, fieldPointer(member.key()),
                         "unknown field (expected one of: " + expected + ")");
    }
}

std::string ObjectReader::fieldPointer(const std::string& name) const {
    return pointer_ + "/" + escapePointerToken(name);
}

bool ObjectReader::has(const std::string& name) const { return object_->contains(name); }

void ObjectReader::fail(const std::string& name, const std::string& problem) const {
    throw InputError(file_, fieldPointer(name), problem);
}

const nlohmann::json& ObjectReader::required(const std::string& name) const {
    const auto found = object_->find(name);
    if (found == object_->end()) fail(name, "required field is missing");
    return *found;
}

double ObjectReader::number(const std::string& name, const NumberRange& range) const {
    return checkedNumber(file_, fieldPointer(name), required(name), range);
}

double ObjectReader::number(const std::string& name, const NumberRange& range, double default_value) const {
    return optionalNumber(name, range).value_or(default_value);
}

std::optional<double> ObjectReader::optionalNumber(const std::string& name, const NumberRange& range) const {
    if (!has(name)) return std::nullopt;
    return checkedNumber(file_, fieldPointer(name), object_->at(name), range);
}

int64_t ObjectReader::integer(const std::string& name, int64_t min, int64_t max, int64_t default_value) const {
    if (!has(name)) return default_value;
    const NumberRange range{double(min), double(max)};
    const double number = checkedNumber(file_, fieldPointer(name), object_->at(name), range);
    if (number != std::floor(number)) fail(name, formatNumber(number) + " is not a whole number");
    return int64_t(number);
}

std::string ObjectReader::string(const std::string& name) const {
    return checkedString(file_, fieldPointer(name), required(name));
}

std::vector<double> ObjectReader::numberArray(const std::string& name, size_t count,
                                              const NumberRange& range) const {
    const nlohmann::json& values = array(name);
    if (values.size() != count)
        fail(name, "expected " + std::to_string(count) + " numbers, found " + std::to_string(values.size()));
    std::vector<double> numbers;
    for (size_t i = 0; i < count; ++i)
        numbers.push_back(checkedNumber(file_, fieldPointer(name) + "/" + std::to_string(i), values[i], range));
    return numbers;
}

const nlohmann::json& ObjectReader::array(const std::string& name) const {
    const nlohmann::json& value = required(name);
    if (!value.is_array()) fail(name, "expected an array, found " + describeJsonType(value));
    return value;
}

ObjectReader ObjectReader::object(const std::string& name, std::initializer_list<const char*> known_fields) const {
    return ObjectReader(file_, required(name), fieldPointer(name), known_fields);
}

std::optional<ObjectReader> ObjectReader::optionalObject(const std::string& name,
                                                         std::initializer_list<const char*> known_fields) const {
    if (!has(name)) return std::nullopt;
    return ObjectReader(file_, object_->at(name), fieldPointer(name), known_fields);
}

}  // namespace gusuku::json_reader

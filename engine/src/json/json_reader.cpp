// The standard-library JSON reader (json_reader.h).

#include "json_reader.h"

#include <charconv>
#include <cstdint>

#include "gusuku/formats/input_error.h"

namespace gusuku::json_detail {
namespace {

constexpr int kDeepestNesting = 64;

class Parser {
public:
    Parser(const std::string& text, const std::string& file) : text_(text), file_(file) {}

    JsonValue document() {
        JsonValue value = parseValue(0);
        skipSpace();
        if (at_ != text_.size()) fail("content after the JSON value");
        return value;
    }

private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(file_, "byte " + std::to_string(at_), problem);
    }
    void skipSpace() {
        while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' || text_[at_] == '\r'))
            ++at_;
    }
    bool consume(const char* word) {
        const std::string_view expected(word);
        if (text_.compare(at_, expected.size(), expected) != 0) return false;
        at_ += expected.size();
        return true;
    }
    void expect(char character, const char* what) {
        skipSpace();
        if (at_ >= text_.size() || text_[at_] != character) fail(std::string("expected ") + what);
        ++at_;
    }

    JsonValue parseValue(int depth) {
        if (depth > kDeepestNesting) fail("nested more than 64 deep");
        skipSpace();
        if (at_ >= text_.size()) fail("the text ends where a value should be (truncated?)");
        JsonValue value;
        const char first = text_[at_];
        if (first == '{') return parseObject(depth);
        if (first == '[') return parseArray(depth);
        if (first == '"') {
            value.type = JsonValue::Type::kString;
            value.text = parseString();
        } else if (consume("true") || consume("false")) {
            value.type = JsonValue::Type::kBool;
            value.boolean = text_[at_ - 1] == 'e' && text_[at_ - 2] == 'u';
        } else if (consume("null")) {
            value.type = JsonValue::Type::kNull;
        } else {
            value.type = JsonValue::Type::kNumber;
            value.number = parseNumber();
        }
        return value;
    }

    JsonValue parseObject(int depth) {
        JsonValue value;
        value.type = JsonValue::Type::kObject;
        ++at_;  // '{'
        skipSpace();
        if (at_ < text_.size() && text_[at_] == '}') {
            ++at_;
            return value;
        }
        while (true) {
            skipSpace();
            if (at_ >= text_.size() || text_[at_] != '"') fail("expected a member name in quotes");
            std::string key = parseString();
            if (value.find(key) != nullptr) fail("the key \"" + key + "\" appears twice");
            expect(':', "':' after a member name");
            JsonValue member = parseValue(depth + 1);
            value.keys.push_back(std::move(key));
            value.items.push_back(std::move(member));
            skipSpace();
            if (at_ < text_.size() && text_[at_] == ',') {
                ++at_;
                continue;
            }
            expect('}', "',' or '}' in an object");
            return value;
        }
    }

    JsonValue parseArray(int depth) {
        JsonValue value;
        value.type = JsonValue::Type::kArray;
        ++at_;  // '['
        skipSpace();
        if (at_ < text_.size() && text_[at_] == ']') {
            ++at_;
            return value;
        }
        while (true) {
            value.items.push_back(parseValue(depth + 1));
            skipSpace();
            if (at_ < text_.size() && text_[at_] == ',') {
                ++at_;
                continue;
            }
            expect(']', "',' or ']' in an array");
            return value;
        }
    }

    double parseNumber() {
        // RFC 8259's grammar: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?
        const size_t start = at_;
        auto digits = [&] {
            const size_t from = at_;
            while (at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9') ++at_;
            return at_ - from;
        };
        if (at_ < text_.size() && text_[at_] == '-') ++at_;
        if (at_ < text_.size() && text_[at_] == '0') ++at_;
        else if (digits() == 0) fail("not a JSON value");
        if (at_ < text_.size() && text_[at_] == '.') {
            ++at_;
            if (digits() == 0) fail("a number's fraction has no digits");
        }
        if (at_ < text_.size() && (text_[at_] == 'e' || text_[at_] == 'E')) {
            ++at_;
            if (at_ < text_.size() && (text_[at_] == '+' || text_[at_] == '-')) ++at_;
            if (digits() == 0) fail("a number's exponent has no digits");
        }
        double number = 0.0;
        const std::from_chars_result result = std::from_chars(text_.data() + start, text_.data() + at_, number);
        if (result.ec != std::errc() || result.ptr != text_.data() + at_) fail("a number out of range");
        return number;
    }

    void appendUtf8(std::string& out, uint32_t code) {
        if (code < 0x80) {
            out.push_back(char(code));
        } else if (code < 0x800) {
            out.push_back(char(0xC0 | code >> 6));
            out.push_back(char(0x80 | (code & 0x3F)));
        } else if (code < 0x10000) {
            out.push_back(char(0xE0 | code >> 12));
            out.push_back(char(0x80 | (code >> 6 & 0x3F)));
            out.push_back(char(0x80 | (code & 0x3F)));
        } else {
            out.push_back(char(0xF0 | code >> 18));
            out.push_back(char(0x80 | (code >> 12 & 0x3F)));
            out.push_back(char(0x80 | (code >> 6 & 0x3F)));
            out.push_back(char(0x80 | (code & 0x3F)));
        }
    }

    uint32_t hexQuad() {
        if (text_.size() - at_ < 4) fail("a \\u escape is cut short");
        uint32_t code = 0;
        const std::from_chars_result result = std::from_chars(text_.data() + at_, text_.data() + at_ + 4, code, 16);
        if (result.ptr != text_.data() + at_ + 4) fail("a \\u escape is not four hex digits");
        at_ += 4;
        return code;
    }

    std::string parseString() {
        ++at_;  // '"'
        std::string out;
        while (true) {
            if (at_ >= text_.size()) fail("a string is not closed (truncated?)");
            const unsigned char character = static_cast<unsigned char>(text_[at_++]);
            if (character == '"') return out;
            if (character < 0x20) fail("a control character inside a string");
            if (character != '\\') {
                out.push_back(char(character));
                continue;
            }
            if (at_ >= text_.size()) fail("a string is not closed (truncated?)");
            const char escape = text_[at_++];
            const char* simple = "\"\\/bfnrt";
            const char* meaning = "\"\\/\b\f\n\r\t";
            const char* found = std::char_traits<char>::find(simple, 8, escape);
            if (found != nullptr) {
                out.push_back(meaning[found - simple]);
            } else if (escape == 'u') {
                uint32_t code = hexQuad();
                if (code >= 0xD800 && code < 0xDC00) {  // a surrogate pair
                    if (!consume("\\u")) fail("a high surrogate without its low one");
                    const uint32_t low = hexQuad();
                    if (low < 0xDC00 || low >= 0xE000) fail("a high surrogate without its low one");
                    code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                } else if (code >= 0xDC00 && code < 0xE000) {
                    fail("a low surrogate without its high one");
                }
                appendUtf8(out, code);
            } else {
                fail(std::string("an unknown escape \\") + escape);
            }
        }
    }

    const std::string& text_;
    const std::string& file_;
    size_t at_ = 0;
};

}  // namespace

const JsonValue* JsonValue::find(const std::string& key) const {
    if (type != Type::kObject) return nullptr;
    for (size_t index = 0; index < keys.size(); ++index)
        if (keys[index] == key) return &items[index];
    return nullptr;
}

JsonValue parseJson(const std::string& text, const std::string& file) { return Parser(text, file).document(); }

}  // namespace gusuku::json_detail

// PLY (Greg Turk's polygon file format) as photogrammetry tools write it: ASCII or binary, any elements, of which
// "vertex" (x, y, z, optional red/green/blue) and "face" (a vertex_indices or vertex_index list) are used.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <string_view>

#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {

namespace {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
    std::string name;
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;  ///< lists only
    PlyType value_type = PlyType::Float32;
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
    size_t header_line = 0;  ///< the "element" line, for messages about its count
};

/// A header longer than this is no mesh's header (a real one is under 1 KB); it bounds the header's vectors.
constexpr size_t kMaxHeaderBytes = 64 * 1024;

size_t byteSize(PlyType type) {
    switch (type) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 1;
}

bool isInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

/// The largest value of an unsigned or signed integer type: a colour stored as one is value / this.
double integerMaximum(PlyType type) {
    switch (type) {
    case PlyType::Int8: return 127.0;
    case PlyType::UInt8: return 255.0;
    case PlyType::Int16: return 32767.0;
    case PlyType::UInt16: return 65535.0;
    case PlyType::Int32: return 2147483647.0;
    case PlyType::UInt32: return 4294967295.0;
    default: return 1.0;
    }
}

bool parseType(std::string_view name, PlyType& type) {
    static const std::pair<const char*, PlyType> kNames[] = {
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [text, value] : kNames)
        if (name == text) {
            type = value;
            return true;
        }
    return false;
}

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

/// A read value for a message: "57", "nan", "1e+300" (std::to_string would write "57.000000").
std::string formatValue(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

bool isUnsigned(PlyType type) {
    return type == PlyType::UInt8 || type == PlyType::UInt16 || type == PlyType::UInt32;
}

std::string shortened(std::string_view text) { return quotedForMessage(std::string(text)); }

/// Reads the elements' data, binary or ASCII, calling back per value; the header is already checked.
class PlyReader {
public:
    PlyReader(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}

    SurveyMeshData read() {
        readHeader();
        checkCountsAgainstFileSize();
        SurveyMeshData data;
        data.positions.reserve(size_t(vertex_count_));
        if (has_colours_) data.colours.reserve(size_t(vertex_count_));
        for (const PlyElement& element : elements_) {
            for (uint64_t item = 0; item < element.count; ++item) {
                item_ = item;
                element_ = &element;
                if (format_ == PlyFormat::Ascii) nextAsciiLine();
                if (element.name == "vertex") readVertex(element, data);
                else if (element.name == "face") readFace(element, data);
                else for (const PlyProperty& property : element.properties) skipProperty(property);
                if (format_ == PlyFormat::Ascii && word_ < words_.size())
                    fail("has " + std::to_string(words_.size()) + " values, more than the header's properties");
            }
        }
        return data;
    }

private:
    [[noreturn]] void failHeader(size_t line, const std::string& problem) const {
        throw InputError(path_, "header line " + std::to_string(line), problem);
    }
    [[noreturn]] void fail(const std::string& problem) const {
        const std::string item = element_->name + " " + std::to_string(item_);
        throw InputError(path_, format_ == PlyFormat::Ascii ? "line " + std::to_string(line_) + " (" + item + ")" : item,
                         problem);
    }

    void readHeader() {
        size_t line_number = 0;
        bool ended = false;
        while (!ended) {
            const size_t end = bytes_.find('\n', offset_);
            if (end == std::string::npos || end >= kMaxHeaderBytes)
                failHeader(line_number + 1, end == std::string::npos ? "the file ends inside the header (no end_header)"
                                                                     : "the header is over 64 KB (no end_header)");
            const std::string_view line(bytes_.data() + offset_, end - offset_);
            offset_ = end + 1;
            ++line_number;
            const std::vector<std::string_view> words = splitWords(line);
            if (line_number == 1) {
                if (words.size() != 1 || words[0] != "ply") failHeader(1, "not a PLY file (it does not start with \"ply\")");
                continue;
            }
            if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
            if (words[0] == "end_header") {
                ended = true;
            } else if (words[0] == "format") {
                if (words.size() != 3) failHeader(line_number, "expected \"format TYPE 1.0\"");
                if (words[1] == "ascii") format_ = PlyFormat::Ascii;
                else if (words[1] == "binary_little_endian") format_ = PlyFormat::BinaryLittleEndian;
                else if (words[1] == "binary_big_endian") format_ = PlyFormat::BinaryBigEndian;
                else failHeader(line_number, "unknown format " + shortened(words[1]) +
                                                 " (expected ascii, binary_little_endian or binary_big_endian)");
                if (words[2] != "1.0") failHeader(line_number, "unknown version " + shortened(words[2]) + " (expected 1.0)");
                has_format_ = true;
            } else if (words[0] == "element") {
                PlyElement element;
                if (words.size() != 3) failHeader(line_number, "expected \"element NAME COUNT\"");
                element.name = std::string(words[1]);
                element.header_line = line_number;
                const auto [end_of_count, error] =
                    std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
                if (error != std::errc() || end_of_count != words[2].data() + words[2].size())
                    failHeader(line_number, "element " + shortened(words[1]) + ": count " + shortened(words[2]) +
                                                " is not a whole number");
                for (const PlyElement& other : elements_)
                    if (other.name == element.name) failHeader(line_number, "element " + shortened(words[1]) + " appears twice");
                elements_.push_back(element);
            } else if (words[0] == "property") {
                if (elements_.empty()) failHeader(line_number, "a property before any element");
                PlyProperty property;
                const bool is_list = words.size() == 5 && words[1] == "list";
                if (!is_list && words.size() != 3)
                    failHeader(line_number, "expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
                property.is_list = is_list;
                if (is_list && !parseType(words[2], property.count_type))
                    failHeader(line_number, "unknown type " + shortened(words[2]));
                if (is_list && !isInteger(property.count_type))
                    failHeader(line_number, "a list's count type must be an integer type, not " + shortened(words[2]));
                const std::string_view value_type = words[is_list ? 3 : 1];
                if (!parseType(value_type, property.value_type)) failHeader(line_number, "unknown type " + shortened(value_type));
                property.name = std::string(words.back());
                elements_.back().properties.push_back(property);
            } else {
                failHeader(line_number, "unknown header keyword " + shortened(words[0]));
            }
        }
        if (!has_format_) failHeader(2, "no format line");
        header_lines_ = line_number;
        line_ = line_number;
        findVertexAndFaceProperties();
    }

    int propertyIndex(const PlyElement& element, std::initializer_list<const char*> names) const {
        for (size_t i = 0; i < element.properties.size(); ++i)
            for (const char* name : names)
                if (element.properties[i].name == name) return int(i);
        return -1;
    }

    void findVertexAndFaceProperties() {
        bool has_vertex = false, has_face = false;
        for (const PlyElement& element : elements_) {
            if (element.properties.empty() && element.count > 0)
                failHeader(element.header_line, "element " + shortened(element.name) + " has no properties");
            if (element.name == "vertex") {
                has_vertex = true;
                vertex_count_ = element.count;
                vertex_line_ = element.header_line;
                const char* axes[3] = {"x", "y", "z"};
                for (int axis = 0; axis < 3; ++axis) {
                    position_property_[axis] = propertyIndex(element, {axes[axis]});
                    if (position_property_[axis] < 0 || element.properties[position_property_[axis]].is_list)
                        failHeader(header_lines_, std::string("element vertex has no property ") + axes[axis]);
                }
                colour_property_[0] = propertyIndex(element, {"red", "diffuse_red", "r"});
                colour_property_[1] = propertyIndex(element, {"green", "diffuse_green", "g"});
                colour_property_[2] = propertyIndex(element, {"blue", "diffuse_blue", "b"});
                const int colours_found = (colour_property_[0] >= 0) + (colour_property_[1] >= 0) + (colour_property_[2] >= 0);
                if (colours_found != 0 && colours_found != 3)
                    failHeader(header_lines_, "element vertex has some of red, green and blue, not all three");
                has_colours_ = colours_found == 3;
                for (int channel = 0; has_colours_ && channel < 3; ++channel)
                    if (element.properties[colour_property_[channel]].is_list)
                        failHeader(header_lines_, "a vertex colour property is a list");
            } else if (element.name == "face") {
                has_face = true;
                face_property_ = propertyIndex(element, {"vertex_indices", "vertex_index"});
                if (face_property_ < 0 || !element.properties[face_property_].is_list)
                    failHeader(header_lines_, "element face has no vertex_indices (or vertex_index) list");
            }
        }
        if (!has_vertex) failHeader(header_lines_, "no element vertex");
        if (!has_face) failHeader(header_lines_, "no element face (a site mesh needs triangles, not a point cloud)");
        if (vertex_count_ > kMaxGltfInstancedVertices)
            failHeader(vertex_line_, "element vertex: " + std::to_string(vertex_count_) + " vertices, more than the " +
                                          std::to_string(kMaxGltfInstancedVertices) + " a site mesh may have");
    }

    /// A header that claims more items than the rest of the file can hold is refused before anything is reserved.
    void checkCountsAgainstFileSize() const {
        const uint64_t remaining = bytes_.size() - offset_;
        uint64_t needed = 0;  // bytes (binary) or values (ASCII), at least
        for (const PlyElement& element : elements_) {
            uint64_t per_item = 0;
            for (const PlyProperty& property : element.properties)
                per_item += format_ == PlyFormat::Ascii ? 1 : byteSize(property.is_list ? property.count_type : property.value_type);
            // Each ASCII value takes a character and a separator.
            if (format_ == PlyFormat::Ascii) per_item *= 2;
            if (per_item > 0 && element.count > (remaining + 1) / per_item + 1)
                failHeader(element.header_line, "element " + element.name + " claims " + std::to_string(element.count) +
                                              " items, more than the " + std::to_string(remaining) +
                                              " bytes after the header can hold (truncated file or wrong count)");
            needed += element.count * per_item;
        }
        if (needed > remaining + 1)
            failHeader(header_lines_, "the elements' counts need at least " + std::to_string(needed) + " bytes, the file has " +
                                          std::to_string(remaining) + " after the header (truncated file or wrong count)");
    }

    void nextAsciiLine() {
        while (true) {
            if (offset_ >= bytes_.size()) fail("the file ends before it (truncated, or the header's count is too large)");
            size_t end = bytes_.find('\n', offset_);
            if (end == std::string::npos) end = bytes_.size();
            const std::string_view line(bytes_.data() + offset_, end - offset_);
            offset_ = end + 1;
            ++line_;
            words_ = splitWords(line);
            word_ = 0;
            if (!words_.empty()) return;
        }
    }

    double readValue(PlyType type, const std::string& what) {
        if (format_ == PlyFormat::Ascii) {
            if (word_ >= words_.size())
                fail("has " + std::to_string(words_.size()) + " values, too few for the header's properties (" + what + ")");
            const std::string_view word = words_[word_++];
            double value = 0.0;
            const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
            if (error != std::errc() || end != word.data() + word.size())
                fail(what + ": " + shortened(word) + " is not a number");
            if (isInteger(type) && (value != std::floor(value) || value < (isUnsigned(type) ? 0.0 : -integerMaximum(type) - 1) ||
                                    value > integerMaximum(type)))
                fail(what + ": " + shortened(word) + " is not a value of its integer type");
            return value;
        }
        const size_t size = byteSize(type);
        if (bytes_.size() - offset_ < size) fail("the file ends inside it (truncated)");
        unsigned char raw[8];
        std::memcpy(raw, bytes_.data() + offset_, size);
        offset_ += size;
        // The file's byte order into this machine's (little endian on every target).
        if (format_ == PlyFormat::BinaryBigEndian)
            for (size_t i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
        switch (type) {
        case PlyType::Int8: { int8_t v; std::memcpy(&v, raw, 1); return v; }
        case PlyType::UInt8: return raw[0];
        case PlyType::Int16: { int16_t v; std::memcpy(&v, raw, 2); return v; }
        case PlyType::UInt16: { uint16_t v; std::memcpy(&v, raw, 2); return v; }
        case PlyType::Int32: { int32_t v; std::memcpy(&v, raw, 4); return v; }
        case PlyType::UInt32: { uint32_t v; std::memcpy(&v, raw, 4); return v; }
        case PlyType::Float32: { float v; std::memcpy(&v, raw, 4); return v; }
        case PlyType::Float64: { double v; std::memcpy(&v, raw, 8); return v; }
        }
        return 0.0;
    }

    uint64_t readListCount(const PlyProperty& property) {
        const double count = readValue(property.count_type, property.name + "'s count");
        if (count < 0) fail(property.name + ": negative list count " + std::to_string(int64_t(count)));
        // Each value needs its bytes (binary) or a character and a separator (ASCII): no count beyond the file.
        const uint64_t remaining = bytes_.size() - std::min(offset_, bytes_.size());
        const uint64_t per_value = format_ == PlyFormat::Ascii ? 2 : byteSize(property.value_type);
        if (format_ == PlyFormat::Ascii ? uint64_t(count) > words_.size() - word_
                                        : uint64_t(count) > remaining / per_value)
            fail(property.name + ": the list claims " + std::to_string(uint64_t(count)) + " values, more than " +
                 (format_ == PlyFormat::Ascii ? "the line holds" : "the file holds (truncated)"));
        return uint64_t(count);
    }

    void skipProperty(const PlyProperty& property) {
        const uint64_t count = property.is_list ? readListCount(property) : 1;
        for (uint64_t i = 0; i < count; ++i) readValue(property.value_type, property.name);
    }

    void readVertex(const PlyElement& element, SurveyMeshData& data) {
        double values[3] = {0, 0, 0}, colours[3] = {0, 0, 0};
        for (size_t i = 0; i < element.properties.size(); ++i) {
            const PlyProperty& property = element.properties[i];
            if (property.is_list) {
                skipProperty(property);
                continue;
            }
            const double value = readValue(property.value_type, property.name);
            for (int k = 0; k < 3; ++k) {
                if (int(i) == position_property_[k]) {
                    if (!std::isfinite(value)) fail(property.name + " is " + formatValue(value) + ", not a finite number");
                    values[k] = value;
                }
                if (has_colours_ && int(i) == colour_property_[k]) {
                    const double colour = isInteger(property.value_type) ? value / integerMaximum(property.value_type) : value;
                    if (!(colour >= 0.0 && colour <= 1.0))
                        fail(property.name + " is " + formatValue(value) + ", outside [0, " +
                             (isInteger(property.value_type) ? std::to_string(int64_t(integerMaximum(property.value_type)))
                                                             : std::string("1")) + "]");
                    colours[k] = colour;
                }
            }
        }
        data.positions.emplace_back(values[0], values[1], values[2]);
        if (has_colours_) data.colours.emplace_back(float(colours[0]), float(colours[1]), float(colours[2]));
    }

    void readFace(const PlyElement& element, SurveyMeshData& data) {
        for (size_t i = 0; i < element.properties.size(); ++i) {
            const PlyProperty& property = element.properties[i];
            if (int(i) != face_property_) {
                skipProperty(property);
                continue;
            }
            const uint64_t count = readListCount(property);
            if (count < 3) fail(property.name + ": " + std::to_string(count) + " vertices (a face needs 3 or more)");
            polygon_.clear();
            for (uint64_t k = 0; k < count; ++k) {
                const double index = readValue(property.value_type, property.name);
                if (!(index >= 0.0 && index < double(vertex_count_)) || index != std::floor(index))
                    fail(property.name + ": vertex index " + formatValue(index) + " is out of range (the file has " +
                         std::to_string(vertex_count_) + " vertices)");
                polygon_.push_back(uint32_t(index));
            }
            if (!appendPolygonFan(data.triangle_indices, polygon_))
                fail("more than " + std::to_string(kMaxSurveyTriangles) + " triangles, the most a site mesh may have");
        }
    }

    const std::string& path_;
    const std::string& bytes_;
    size_t offset_ = 0;
    PlyFormat format_ = PlyFormat::Ascii;
    bool has_format_ = false;
    std::vector<PlyElement> elements_;
    size_t header_lines_ = 0;
    uint64_t vertex_count_ = 0;
    size_t vertex_line_ = 0;
    int position_property_[3] = {-1, -1, -1};
    int colour_property_[3] = {-1, -1, -1};
    bool has_colours_ = false;
    int face_property_ = -1;
    // Where the reading is, for messages and ASCII tokens.
    const PlyElement* element_ = nullptr;
    uint64_t item_ = 0;
    size_t line_ = 0;
    std::vector<std::string_view> words_;
    size_t word_ = 0;
    std::vector<uint32_t> polygon_;
};

}  // namespace

SurveyMesh loadPlyMesh(const std::string& path, const glm::dmat4& enu_from_model) {
    const std::string bytes = readSurveyFile(path);
    PlyReader reader(path, bytes);
    return finishSurveyMesh(path, reader.read(), enu_from_model);
}

}  // namespace gusuku

// Wavefront OBJ as photogrammetry tools write it: v (with optional colours), f; the rest (texture coordinates,
// normals, materials, groups, smoothing) is ignored, since the site mesh is flat-shaded with one material.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {

namespace {

std::vector<std::string_view> splitObjWords(std::string_view line) {
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

class ObjReader {
public:
    ObjReader(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}

    SurveyMeshData read() {
        SurveyMeshData data;
        size_t offset = 0;
        while (offset < bytes_.size()) {
            size_t end = bytes_.find('\n', offset);
            if (end == std::string::npos) end = bytes_.size();
            std::string_view line(bytes_.data() + offset, end - offset);
            offset = end + 1;
            ++line_;
            if (const size_t comment = line.find('#'); comment != std::string_view::npos) line = line.substr(0, comment);
            const std::vector<std::string_view> words = splitObjWords(line);
            if (words.empty()) continue;
            const std::string_view keyword = words[0];
            if (keyword == "v") readVertex(words, data);
            else if (keyword == "f") readFace(words, data);
            else if (!isIgnored(keyword)) fail("unknown statement " + quotedForMessage(std::string(keyword)));
        }
        if (data.positions.empty()) throw InputError(path_, "", "has no vertices (no v lines): not a mesh");
        if (colour_state_ == ColourState::Some) data.colours.clear();
        return data;
    }

private:
    enum class ColourState { Unknown, All, None, Some };

    static bool isIgnored(std::string_view keyword) {
        for (const char* name : {"vt", "vn", "vp", "usemtl", "mtllib", "o", "g", "s", "l", "p"})
            if (keyword == name) return true;
        return false;
    }

    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(path_, "line " + std::to_string(line_), problem);
    }

    double number(std::string_view word, const char* what) const {
        double value = 0.0;
        const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (error != std::errc() || end != word.data() + word.size())
            fail(std::string(what) + ": " + quotedForMessage(std::string(word)) + " is not a number");
        if (!std::isfinite(value))
            fail(std::string(what) + " is " + quotedForMessage(std::string(word)) + ", not a finite number");
        return value;
    }

    void readVertex(const std::vector<std::string_view>& words, SurveyMeshData& data) {
        // v x y z, v x y z w, or v x y z r g b (MeshLab's and most SfM tools' vertex colours, 0 to 1).
        const size_t values = words.size() - 1;
        if (values != 3 && values != 4 && values != 6)
            fail("v has " + std::to_string(values) + " values (expected x y z, x y z w or x y z r g b)");
        glm::dvec3 position(number(words[1], "x"), number(words[2], "y"), number(words[3], "z"));
        if (values == 4) {
            const double w = number(words[4], "w");
            if (w == 0.0) fail("w is 0 (a point at infinity)");
            position /= w;
            if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
                fail("x y z / w is beyond double range");
        }
        if (data.positions.size() >= kMaxGltfInstancedVertices)
            fail("more than " + std::to_string(kMaxGltfInstancedVertices) + " vertices, the most a site mesh may have");
        data.positions.push_back(position);
        const bool has_colour = values == 6;
        if (has_colour) {
            const char* names[3] = {"r", "g", "b"};
            glm::vec3 colour;
            for (int k = 0; k < 3; ++k) {
                const double value = number(words[4 + k], names[k]);
                if (value < 0.0 || value > 1.0)
                    fail(std::string(names[k]) + " is " + std::string(words[4 + k]) + ", outside [0, 1]");
                colour[k] = float(value);
            }
            data.colours.push_back(colour);
        }
        // Colours are kept only when every vertex has one; a file that mixes them is read without (all or none is
        // what every writer produces, so a mix is rare and no colour is better than a made-up one).
        const ColourState this_vertex = has_colour ? ColourState::All : ColourState::None;
        if (colour_state_ == ColourState::Unknown) colour_state_ = this_vertex;
        else if (colour_state_ != this_vertex) colour_state_ = ColourState::Some;
        if (colour_state_ == ColourState::Some) data.colours.clear();
    }

    void readFace(const std::vector<std::string_view>& words, SurveyMeshData& data) {
        const size_t corners = words.size() - 1;
        if (corners < 3) fail("f has " + std::to_string(corners) + " vertices (a face needs 3 or more)");
        polygon_.clear();
        for (size_t k = 1; k < words.size(); ++k) {
            // v, v/vt, v//vn or v/vt/vn: the position index is before the first slash.
            std::string_view word = words[k];
            word = word.substr(0, word.find('/'));
            int64_t index = 0;
            const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), index);
            if (error != std::errc() || end != word.data() + word.size() || index == 0)
                fail("f: " + quotedForMessage(std::string(words[k])) + " is not a vertex index (1, 2, ... or -1, -2, ...)");
            // Negative indices count back from the latest vertex: -1 is the last one read so far.
            const int64_t vertex_count = int64_t(data.positions.size());
            const int64_t zero_based = index > 0 ? index - 1 : vertex_count + index;
            if (zero_based < 0 || zero_based >= vertex_count)
                fail("f: vertex index " + std::to_string(index) + " is out of range (" + std::to_string(vertex_count) +
                     " vertices so far)");
            polygon_.push_back(uint32_t(zero_based));
        }
        if (!appendPolygonFan(data.triangle_indices, polygon_))
            fail("more than " + std::to_string(kMaxSurveyTriangles) + " triangles, the most a site mesh may have");
    }

    const std::string& path_;
    const std::string& bytes_;
    size_t line_ = 0;
    ColourState colour_state_ = ColourState::Unknown;
    std::vector<uint32_t> polygon_;
};

}  // namespace

SurveyMesh loadObjMesh(const std::string& path, const glm::dmat4& enu_from_model) {
    const std::string bytes = readSurveyFile(path);
    ObjReader reader(path, bytes);
    return finishSurveyMesh(path, reader.read(), enu_from_model);
}

}  // namespace gusuku

// gusuku-bench's --views and --sample-results readers (see bench_views.h).
#include "bench_views.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "gusuku/formats/input_error.h"
#include "gusuku/tools/command_line.h"

namespace gusuku::bench {
namespace {

std::vector<std::string> splitOn(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.emplace_back();  // a trailing separator: an empty part
    return parts;
}

glm::dvec3 pointOf(const std::string& text, const std::string& where, const std::string& what) {
    const std::vector<std::string> parts = splitOn(text, ',');
    if (parts.size() != 3)
        throw std::invalid_argument(where + ": " + what + " " + quotedForMessage(text) +
                                    " needs three numbers E,N,U (site ENU metres)");
    glm::dvec3 point;
    for (int axis = 0; axis < 3; ++axis) {
        const std::optional<double> value = parseDecimal(parts[size_t(axis)]);
        if (!value || std::abs(*value) > 1e5)
            throw std::invalid_argument(where + ": " + what + " " + quotedForMessage(text) + ": " +
                                        quotedForMessage(parts[size_t(axis)]) +
                                        " is not a number within [-100000, 100000] m");
        point[axis] = *value;
    }
    return point;
}

bool isViewName(const std::string& name) {
    if (name.empty() || name.size() > 32) return false;
    for (char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

}  // namespace

std::vector<NamedView> parseBenchViews(const std::string& text) {
    std::vector<NamedView> views;
    std::set<std::string> names;
    const std::vector<std::string> poses = splitOn(text, ';');
    for (size_t index = 0; index < poses.size(); ++index) {
        const std::string where = "--views: pose " + std::to_string(index + 1);
        const std::vector<std::string> fields = splitOn(poses[index], ':');
        if (fields.size() != 3 && fields.size() != 4)
            throw std::invalid_argument(where + " " + quotedForMessage(poses[index]) +
                                        " is not NAME:E,N,U:E,N,U[:FOV]");
        NamedView named;
        named.name = fields[0];
        const std::string here = where + " (" + quotedForMessage(named.name) + ")";
        if (!isViewName(named.name))
            throw std::invalid_argument(here + ": the name must be 1-32 of a-z, 0-9, _");
        if (!names.insert(named.name).second) throw std::invalid_argument(here + ": the name is given twice");
        named.view.position_enu = pointOf(fields[1], here, "position");
        named.view.look_at_enu = pointOf(fields[2], here, "look-at");
        if (!(glm::length(named.view.look_at_enu - named.view.position_enu) > 1e-6))
            throw std::invalid_argument(here + ": the look-at point is the camera's position");
        if (fields.size() == 4) {
            const std::optional<double> fov = parseDecimal(fields[3]);
            if (!fov || !(*fov > 1.0 && *fov < 170.0))
                throw std::invalid_argument(here + ": field of view " + quotedForMessage(fields[3]) +
                                            " is not a number of degrees in (1, 170)");
            named.view.horizontal_fov_deg = *fov;
        }
        views.push_back(named);
    }
    if (views.empty()) throw std::invalid_argument("--views: names no pose");
    return views;
}

std::map<std::string, double> sampleFrameTimesFrom(const std::string& results_json) {
    std::ifstream stream(results_json, std::ios::binary);
    if (!stream) throw InputError(results_json, "", "file not found (a gusuku-bench results.json of the sample)");
    nlohmann::json results = nlohmann::json::parse(stream, nullptr, /*allow_exceptions=*/false);
    if (results.is_discarded()) throw InputError(results_json, "", "not valid JSON");
    const nlohmann::json* views = nullptr;
    if (results.is_object() && results.contains("site") && results["site"].is_object() &&
        results["site"].contains("views") && results["site"]["views"].is_array())
        views = &results["site"]["views"];
    if (!views) throw InputError(results_json, "/site/views", "missing: the run had no site section (--views)");
    std::map<std::string, double> frame_ms;
    for (size_t index = 0; index < views->size(); ++index) {
        const nlohmann::json& view = (*views)[index];
        const std::string field = "/site/views/" + std::to_string(index);
        if (!view.is_object() || !view.contains("name") || !view["name"].is_string())
            throw InputError(results_json, field + "/name", "missing or not a string");
        const nlohmann::json* proposed = view.contains("frame_1280x720") && view["frame_1280x720"].is_object() &&
                                                 view["frame_1280x720"].contains("proposed_ms")
                                             ? &view["frame_1280x720"]["proposed_ms"]
                                             : nullptr;
        if (!proposed || !proposed->is_number() || !(proposed->get<double>() > 0.0))
            throw InputError(results_json, field + "/frame_1280x720/proposed_ms", "missing or not a positive number");
        frame_ms[view["name"].get<std::string>()] = proposed->get<double>();
    }
    return frame_ms;
}

}  // namespace gusuku::bench

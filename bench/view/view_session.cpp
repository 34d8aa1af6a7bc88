// The session folder's reader and writer (see view_session.h and docs/session.md).

#include "view_session.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "camera_image.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"

namespace gusuku::view {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSessionJson = "session.json";
constexpr const char* kTrackCsv = "track.csv";
constexpr size_t kTrackColumns = 11;
/// How far a quaternion's norm may stray from 1 (text rounding, a float recording) before the row is refused:
/// a norm further off means the columns are not a rotation (swapped, or a position in their place).
constexpr double kQuaternionNormTolerance = 1e-3;
/// Positions within 100 km of the site's origin, as gusuku-render's --position.
constexpr double kMaxDistanceM = 1e5;

std::string joined(const std::string& folder, const std::string& name) { return (fs::path(folder) / name).string(); }

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream stream(line);
    while (std::getline(stream, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
}

double readNumberJson(const nlohmann::json& object, const std::string& file, const std::string& pointer,
                      const char* key) {
    const auto item = object.find(key);
    if (item == object.end()) throw InputError(file, pointer + "/" + key, "missing");
    if (!item->is_number()) throw InputError(file, pointer + "/" + key, "is not a number");
    const double value = item->get<double>();
    if (!std::isfinite(value)) throw InputError(file, pointer + "/" + key, "is not finite");
    return value;
}

CameraIntrinsics readIntrinsics(const nlohmann::json& root, const std::string& file) {
    const auto item = root.find("intrinsics");
    if (item == root.end() || !item->is_object()) throw InputError(file, "/intrinsics", "missing or not an object");
    CameraIntrinsics intrinsics;
    intrinsics.fx = readNumberJson(*item, file, "/intrinsics", "fx");
    intrinsics.fy = readNumberJson(*item, file, "/intrinsics", "fy");
    intrinsics.cx = readNumberJson(*item, file, "/intrinsics", "cx");
    intrinsics.cy = readNumberJson(*item, file, "/intrinsics", "cy");
    for (const char* key : {"width", "height"}) {
        const double side = readNumberJson(*item, file, "/intrinsics", key);
        if (side != std::floor(side) || side < render_cli::kMinCameraSide || side > render_cli::kMaxCameraSide)
            throw InputError(file, std::string("/intrinsics/") + key,
                             "must be a whole number of pixels in [" + std::to_string(render_cli::kMinCameraSide) +
                                 ", " + std::to_string(render_cli::kMaxCameraSide) + "]");
        (std::string(key) == "width" ? intrinsics.width : intrinsics.height) = uint32_t(side);
    }
    if (!(intrinsics.fx > 0.0) || !(intrinsics.fy > 0.0))
        throw InputError(file, "/intrinsics/fx", "focal lengths must be > 0 pixels");
    return intrinsics;
}

// One track row's cells, checked; `field(column)` names the place for a message.
struct RowReader {
    const std::string& file;
    size_t line_number;
    const std::vector<std::string>& cells;

    std::string field(size_t column) const {
        static const char* const kNames[kTrackColumns] = {"image", "time", "east_m", "north_m", "up_m", "qw",
                                                          "qx",    "qy",   "qz",     "cloud_cover", "exposure"};
        return "line " + std::to_string(line_number) + " " + kNames[column];
    }
    double number(size_t column) const {
        const std::optional<double> value = parseDecimal(cells[column]);
        if (!value || !std::isfinite(*value))
            throw InputError(file, field(column), quotedForMessage(cells[column]) + " is not a number");
        return *value;
    }
};

SessionFrame readRow(const std::string& folder, const std::string& file, size_t line_number,
                     const std::vector<std::string>& cells, const CameraIntrinsics& intrinsics) {
    const RowReader row{file, line_number, cells};
    if (cells.size() != kTrackColumns)
        throw InputError(file, "line " + std::to_string(line_number),
                         "has " + std::to_string(cells.size()) + " columns, expected " +
                             std::to_string(kTrackColumns) + " (" + kTrackHeader + ")");
    SessionFrame frame;
    frame.image = cells[0];
    const fs::path image_path(frame.image);
    if (frame.image.empty() || image_path.is_absolute() ||
        image_path.lexically_normal().string().rfind("..", 0) == 0)
        throw InputError(file, row.field(0), quotedForMessage(frame.image) +
                                                 " is not a path inside the session folder");
    try {
        const ImageSize size = readImageSize(joined(folder, frame.image));
        if (uint32_t(size.width) != intrinsics.width || uint32_t(size.height) != intrinsics.height)
            throw InputError(file, row.field(0),
                             frame.image + " is " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                                 ", the intrinsics say " + std::to_string(intrinsics.width) + " x " +
                                 std::to_string(intrinsics.height));
    } catch (const InputError& error) {
        if (error.file() == file) throw;
        throw InputError(file, row.field(0), frame.image + ": " + error.problem());
    }
    frame.time_iso = cells[1];
    try {
        frame.utc_seconds = parseIso8601Utc(frame.time_iso);
    } catch (const std::invalid_argument& error) {
        throw InputError(file, row.field(1), quotedForMessage(frame.time_iso) + ": " + error.what());
    }
    const glm::dvec3 position{row.number(2), row.number(3), row.number(4)};
    if (glm::length(position) > kMaxDistanceM)
        throw InputError(file, row.field(2), "the position is more than 100 km from the site's origin");
    const glm::dquat rotation(row.number(5), row.number(6), row.number(7), row.number(8));
    const double norm = glm::length(rotation);
    if (std::fabs(norm - 1.0) > kQuaternionNormTolerance)
        throw InputError(file, row.field(5), "qw, qx, qy, qz is not a unit quaternion (norm " +
                                                 defaultNumber(norm) + ")");
    frame.pose.position_enu = position;
    frame.pose.camera_to_enu = glm::mat3_cast(rotation / norm);
    const double cover = row.number(9);
    if (!(cover >= 0.0 && cover <= 1.0)) throw InputError(file, row.field(9), "must be in [0, 1]");
    frame.cloud_cover = float(cover);
    if (!cells[10].empty()) {
        const double exposure = row.number(10);
        if (!(exposure > 0.0 && exposure <= 1e9)) throw InputError(file, row.field(10), "must be in (0, 1e9]");
        frame.exposure = float(exposure);
    }
    return frame;
}

std::string numberText(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

}  // namespace

bool isSessionFolder(const std::string& folder) {
    std::error_code error;
    return fs::is_regular_file(joined(folder, kSessionJson), error);
}

Session readSession(const std::string& folder) {
    const std::string json_path = joined(folder, kSessionJson);
    const nlohmann::json root = nlohmann::json::parse(readWholeFile(json_path), nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded() || !root.is_object()) throw InputError(json_path, "", "is not a JSON object");
    const auto format = root.find("format");
    if (format == root.end() || !format->is_string() || format->get<std::string>() != kSessionFormat)
        throw InputError(json_path, "/format", std::string("must be \"") + kSessionFormat + "\"");
    Session session;
    session.folder = folder;
    session.intrinsics = readIntrinsics(root, json_path);
    if (const auto bake_set = root.find("bake_set"); bake_set != root.end()) {
        if (!bake_set->is_string()) throw InputError(json_path, "/bake_set", "is not a string");
        session.bake_set = bake_set->get<std::string>();
    }
    std::string track_name = kTrackCsv;
    if (const auto track = root.find("track"); track != root.end()) {
        if (!track->is_string()) throw InputError(json_path, "/track", "is not a string");
        track_name = track->get<std::string>();
    }
    const std::string track_path = joined(folder, track_name);
    std::istringstream track(readWholeFile(track_path));
    std::string line;
    if (!std::getline(track, line) || line != kTrackHeader)
        throw InputError(track_path, "line 1", std::string("must be the header ") + kTrackHeader);
    for (size_t line_number = 2; std::getline(track, line); ++line_number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();  // a track saved on Windows
        if (line.empty()) continue;
        if (session.frames.size() == kMaxSessionFrames)
            throw InputError(track_path, "line " + std::to_string(line_number),
                             "more than " + std::to_string(kMaxSessionFrames) + " frames");
        SessionFrame frame = readRow(folder, track_path, line_number, splitCsv(line), session.intrinsics);
        if (!session.frames.empty() && frame.utc_seconds < session.frames.back().utc_seconds)
            throw InputError(track_path, "line " + std::to_string(line_number) + " time",
                             "goes back in time (rows are in time order)");
        session.frames.push_back(std::move(frame));
    }
    if (session.frames.empty()) throw InputError(track_path, "", "holds no frame");
    return session;
}

std::optional<std::string> sessionBakeSet(const Session& session) {
    if (!session.bake_set) return std::nullopt;
    const fs::path path(*session.bake_set);
    return (path.is_absolute() ? path : fs::path(session.folder) / path).lexically_normal().string();
}

std::string trackRow(const SessionFrame& frame) {
    glm::dquat rotation = glm::quat_cast(frame.pose.camera_to_enu);
    if (rotation.w < 0.0) rotation = -rotation;  // the same rotation; qw >= 0 reads the same every time
    std::string row = frame.image + "," + (frame.time_iso.empty() ? formatIso8601(frame.utc_seconds, 0)
                                                                  : frame.time_iso);
    for (double value : {frame.pose.position_enu.x, frame.pose.position_enu.y, frame.pose.position_enu.z,
                         rotation.w, rotation.x, rotation.y, rotation.z, double(frame.cloud_cover)})
        row.append(1, ',').append(numberText(value));
    row.append(1, ',').append(frame.exposure ? numberText(double(*frame.exposure)) : std::string());
    return row;
}

void writeSession(const std::string& folder, const Session& session,
                  const std::optional<std::string>& bake_set_folder) {
    std::error_code error;
    if (fs::exists(folder, error) && !isSessionFolder(folder) &&
        !(fs::is_directory(folder, error) && fs::is_empty(folder, error)))
        throw InputError(folder, "", "exists and is not a session folder; not overwritten");
    const fs::path final_path = fs::absolute(folder).lexically_normal();
    const fs::path temporary = final_path.parent_path() /
                               ("." + final_path.filename().string() + ".tmp-" + std::to_string(getpid()));
    fs::remove_all(temporary, error);
    fs::create_directories(temporary / "frames", error);
    if (error) throw InputError(folder, "", "cannot create the folder: " + error.message());
    try {
        nlohmann::ordered_json root;
        root["format"] = kSessionFormat;
        const CameraIntrinsics& k = session.intrinsics;
        root["intrinsics"] = {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"width", k.width},
                              {"height", k.height}};
        root["track"] = kTrackCsv;
        if (bake_set_folder)
            root["bake_set"] = fs::relative(fs::absolute(*bake_set_folder), final_path).lexically_normal().string();
        std::string track = std::string(kTrackHeader) + "\n";
        for (size_t index = 0; index < session.frames.size(); ++index) {
            SessionFrame frame = session.frames[index];
            char name[32];
            std::snprintf(name, sizeof name, "frames/%06zu.png", index);
            frame.image = name;
            writePngRgba8((temporary / name).string(), int(k.width), int(k.height), frame.rgba8);
            track += trackRow(frame) + "\n";
        }
        const std::string json_text = root.dump(2) + "\n";
        writeBytesAtomically((temporary / kTrackCsv).string(), track.data(), track.size());
        writeBytesAtomically((temporary / kSessionJson).string(), json_text.data(), json_text.size());
        // The old session goes only once the new one is whole.
        const fs::path old = final_path.parent_path() /
                             ("." + final_path.filename().string() + ".old-" + std::to_string(getpid()));
        if (fs::exists(final_path)) fs::rename(final_path, old);
        fs::rename(temporary, final_path);
        fs::remove_all(old, error);
    } catch (...) {
        fs::remove_all(temporary, error);
        throw;
    }
}

}  // namespace gusuku::view

#pragma once
// A recorded session (docs/session.md): camera frames as an image sequence, a pose and time track, and the
// intrinsics, in one folder:
//   SESSION/session.json   {"format": "gusuku-session/1", "intrinsics": {...}, "track": "track.csv",
//                           "bake_set": "../bakeset"}   (bake_set optional, relative to SESSION)
//   SESSION/track.csv      one row a frame: image,time,east_m,north_m,up_m,qw,qx,qy,qz,cloud_cover,exposure
//   SESSION/frames/*.png   the camera frames (any image gusuku-render's --camera reads)
// Poses and intrinsics are the runtime's (gusuku/runtime/runtime.h): the site's ENU frame in metres, camera x
// right, y down, z forward, pixel (0, 0) the top-left corner. Times are ISO 8601 with their offset, as the bake
// set's slots state them.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gusuku/runtime/runtime.h"

namespace gusuku::view {

/// session.json's "format".
inline constexpr const char* kSessionFormat = "gusuku-session/1";
/// track.csv's header, the columns in this order.
inline constexpr const char* kTrackHeader = "image,time,east_m,north_m,up_m,qw,qx,qy,qz,cloud_cover,exposure";
/// The most frames a session holds (a 10-minute recording at 30 frames a second, twice over).
inline constexpr size_t kMaxSessionFrames = 36000;

struct SessionFrame {
    std::string image;        ///< as track.csv names it: a path relative to the session folder
    std::string time_iso;     ///< as written, with its offset ("2026-06-21T08:00:00+09:00")
    double utc_seconds = 0.0;
    CameraPose pose;          ///< camera-to-ENU rotation (from the unit quaternion qw, qx, qy, qz) and centre
    float cloud_cover = 0.0f; ///< [0, 1], the weather at this instant (0 when the recording does not know it)
    std::optional<float> exposure;  ///< display value per unit radiance; empty: unknown (leave it to the match)
    /// The frame's pixels when the session is held in memory (made, not read): width * height * 4, sRGB RGBA8,
    /// row 0 at the top. Empty for a session read from a folder (the image is read when it is drawn).
    std::vector<uint8_t> rgba8;
};

struct Session {
    std::string folder;                   ///< where it was read from (empty when made in memory)
    CameraIntrinsics intrinsics;          ///< every frame's
    std::optional<std::string> bake_set;  ///< as session.json names it, relative to the folder
    std::vector<SessionFrame> frames;     ///< in time order (times never decrease)
};

/// True when `folder` holds a session.json (what tells a session from a bake set on the command line).
bool isSessionFolder(const std::string& folder);

/// Reads and checks a session: session.json, every track row, and every frame image's header (it exists, is an
/// image, has the intrinsics' size); no pixel is decoded. InputError "FILE: FIELD: PROBLEM" naming the file and
/// the line and column, e.g. "S/track.csv: line 3 qw: 'x' is not a number".
Session readSession(const std::string& folder);

/// The bake set the session names, resolved against its folder; nullopt when it names none.
std::optional<std::string> sessionBakeSet(const Session& session);

/// Writes `session` (every frame's rgba8 filled) into `folder` as frames/000000.png, ... with the track and
/// session.json. Written into a temporary sibling folder and renamed into place, so an interrupted write leaves
/// nothing half-way; an existing session folder is replaced, any other existing non-empty folder is refused
/// (InputError). `bake_set_folder`, when given, is recorded relative to `folder`.
void writeSession(const std::string& folder, const Session& session,
                  const std::optional<std::string>& bake_set_folder = std::nullopt);

/// track.csv's row for a frame, no newline (what writeSession writes; the times as time_iso, or UTC when empty).
std::string trackRow(const SessionFrame& frame);

}  // namespace gusuku::view

#pragma once
// Every file a loader opens must be a regular file: opening a FIFO blocks until a writer appears, a character
// device (/dev/zero, /dev/urandom) never ends, a directory is no data. Checked by status (which follows links)
// before the first open. Private to gusuku_assets.

#include <filesystem>
#include <string>

namespace gusuku {

/// "a FIFO (named pipe)", "a character device", "a directory", ... for messages.
inline std::string describeFileType(std::filesystem::file_type type) {
    switch (type) {
    case std::filesystem::file_type::regular: return "a regular file";
    case std::filesystem::file_type::directory: return "a directory";
    case std::filesystem::file_type::fifo: return "a FIFO (named pipe)";
    case std::filesystem::file_type::character: return "a character device";
    case std::filesystem::file_type::block: return "a block device";
    case std::filesystem::file_type::socket: return "a socket";
    default: return "not a regular file";
    }
}

/// Empty when `path` is a regular file (after following links); otherwise the problem, e.g. "file not found" or
/// "is a FIFO (named pipe), not a regular file; not read".
inline std::string regularFileProblem(const std::string& path) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (status.type() == std::filesystem::file_type::regular) return "";
    if (error == std::errc::too_many_symbolic_link_levels) return "is a loop of symbolic links; not read";
    if (!std::filesystem::exists(status)) return "file not found";
    return "is " + describeFileType(status.type()) + ", not a regular file; not read";
}

}  // namespace gusuku

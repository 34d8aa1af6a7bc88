#pragma once
// Write-then-rename, so that an interrupted program never leaves a half-written output behind.

#include <cstdint>
#include <functional>
#include <string>

namespace gusuku {

/// Calls write(temporary_path) with a temporary path in the same directory as final_path, then renames it
/// onto final_path (atomic on POSIX file systems). If write throws, the temporary file is removed and the
/// exception propagates; final_path is then untouched. Creates missing parent directories. A write that fails
/// with errno ENOSPC is reported as "FINAL: cannot write: No space left on device (the disk holding FOLDER is
/// full, N KiB free; ...)" whatever the writer's own text said (OpenEXR names the temporary file).
void writeFileAtomically(const std::string& final_path,
                         const std::function<void(const std::string& temporary_path)>& write);

/// Like writeFileAtomically, but the temporary path keeps final_path's extension ("out.tmp-<pid>-<n>.exr"),
/// for writers such as OpenImageIO that choose the file format from the extension.
void writeFileAtomicallyKeepingExtension(const std::string& final_path,
                                         const std::function<void(const std::string& temporary_path)>& write);

/// Writes bytes to final_path through writeFileAtomically.
void writeBytesAtomically(const std::string& final_path, const void* bytes, size_t byte_count);

/// The largest file a tool reads whole (a glTF buffer, an image or a mesh being hashed): far above any asset a
/// bake takes (the glTF limits of gusuku/assets/gltf_loader.h fit in a few hundred megabytes), small enough
/// that a wrong path can never exhaust memory.
inline constexpr uint64_t kMaxInputFileBytes = uint64_t(1) << 30;

/// Reads a whole file. Before opening it, checks that it is a regular file after following links (a FIFO would
/// block, /dev/zero or /dev/urandom never end, a directory is no data) and at most max_bytes long; reads no more
/// than that even if the file grows meanwhile. Throws InputError(path, "", problem) naming what is wrong: "file
/// not found", "is a FIFO (named pipe), not a regular file; not read", "is N bytes, more than the M ...".
std::string readWholeFile(const std::string& path, uint64_t max_bytes = kMaxInputFileBytes);

}  // namespace gusuku

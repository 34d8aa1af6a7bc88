#pragma once
// Write-then-rename, so that an interrupted program never leaves a half-written output behind.

#include <functional>
#include <string>

namespace gusuku {

/// Calls write(temporary_path) with a temporary path in the same directory as final_path, then renames it
/// onto final_path (atomic on POSIX file systems). If write throws, the temporary file is removed and the
/// exception propagates; final_path is then untouched. Creates missing parent directories.
void writeFileAtomically(const std::string& final_path,
                         const std::function<void(const std::string& temporary_path)>& write);

/// Like writeFileAtomically, but the temporary path keeps final_path's extension ("out.tmp-<pid>-<n>.exr"),
/// for writers such as OpenImageIO that choose the file format from the extension.
void writeFileAtomicallyKeepingExtension(const std::string& final_path,
                                         const std::function<void(const std::string& temporary_path)>& write);

/// Writes bytes to final_path through writeFileAtomically.
void writeBytesAtomically(const std::string& final_path, const void* bytes, size_t byte_count);

/// Reads a whole file; throws InputError(path, "", "cannot open ...") when it cannot.
std::string readWholeFile(const std::string& path);

}  // namespace gusuku

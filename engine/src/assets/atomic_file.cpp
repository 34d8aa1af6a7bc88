#include "gusuku/assets/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include "gusuku/formats/input_error.h"
#include "regular_file.h"

namespace gusuku {

namespace fs = std::filesystem;

namespace {

// A per-process counter next to the pid keeps temporary names unique across processes and across threads
// writing the same final path at once.
std::atomic<unsigned> temporary_counter{0};

std::string temporaryPathFor(const std::string& final_path, bool keep_extension) {
    const std::string tag = ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(temporary_counter++);
    if (!keep_extension) return final_path + tag;
    const fs::path final_fs(final_path);
    const std::string extension = final_fs.extension().string();
    const std::string stem_path = final_path.substr(0, final_path.size() - extension.size());
    return stem_path + tag + extension;
}

// "OUT/x.exr: cannot write: No space left on device (the disk holding OUT is full, 12 KiB free)".
std::string diskFullMessage(const std::string& final_path, const fs::path& parent) {
    const fs::path folder = parent.empty() ? fs::path(".") : parent;
    std::error_code error;
    const fs::space_info space = fs::space(folder, error);
    std::string message = final_path + ": cannot write: " + std::strerror(ENOSPC) + " (the disk holding " +
                          folder.string() + " is full";
    if (!error) message += ", " + std::to_string(space.available / 1024) + " KiB free";
    return message + "; free some space and run the command again)";
}

void writeThroughTemporary(const std::string& final_path, const std::string& temporary_path,
                           const std::function<void(const std::string&)>& write) {
    // The rename would replace whatever the name holds: a device (/dev/full, /dev/null, as root), a FIFO or a
    // folder is refused before anything is written, so an output only ever replaces a regular file.
    std::error_code status_error;
    const fs::file_status status = fs::status(final_path, status_error);
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw std::runtime_error(final_path + ": is " + describeFileType(status.type()) +
                                 "; an output must be a regular file or a new name");
    const fs::path parent = fs::path(final_path).parent_path();
    if (!parent.empty()) {
        std::error_code error;
        fs::create_directories(parent, error);
        if (error) throw std::runtime_error(final_path + ": cannot create directory " + parent.string() + ": " +
                                            error.message());
    }
    try {
        write(temporary_path);
    } catch (...) {
        const int write_errno = errno;  // the failed write's, before the clean-up below
        std::error_code ignored;
        fs::remove(temporary_path, ignored);
        // A full disk is named as one, with the folder it fills: a writer's own text (OpenEXR's "File output
        // failed" about the temporary name) does not say why.
        if (write_errno == ENOSPC) throw std::runtime_error(diskFullMessage(final_path, parent));
        throw;
    }
    std::error_code error;
    fs::rename(temporary_path, final_path, error);
    if (error) {
        std::error_code ignored;
        fs::remove(temporary_path, ignored);
        throw std::runtime_error(final_path + ": cannot rename " + temporary_path + " onto it: " + error.message());
    }
}

}  // namespace

void writeFileAtomically(const std::string& final_path,
                         const std::function<void(const std::string& temporary_path)>& write) {
    writeThroughTemporary(final_path, temporaryPathFor(final_path, false), write);
}

void writeFileAtomicallyKeepingExtension(const std::string& final_path,
                                         const std::function<void(const std::string& temporary_path)>& write) {
    writeThroughTemporary(final_path, temporaryPathFor(final_path, true), write);
}

void writeBytesAtomically(const std::string& final_path, const void* bytes, size_t byte_count) {
    writeFileAtomically(final_path, [&](const std::string& temporary_path) {
        std::ofstream out(temporary_path, std::ios::binary | std::ios::trunc);
        // Messages name the output the user asked for; the temporary name is an implementation detail.
        if (!out) throw std::runtime_error(final_path + ": cannot open for writing: " + std::strerror(errno));
        out.write(static_cast<const char*>(bytes), std::streamsize(byte_count));
        out.flush();
        if (!out) throw std::runtime_error(final_path + ": write failed: " + std::strerror(errno));
    });
}

std::string readWholeFile(const std::string& path, uint64_t max_bytes) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) throw InputError(path, "", problem);
    std::error_code size_error;
    const uintmax_t size = fs::file_size(path, size_error);
    if (size_error) throw InputError(path, "", "cannot read its size: " + size_error.message());
    if (size > max_bytes)
        throw InputError(path, "", "is " + std::to_string(size) + " bytes, more than the " +
                                       std::to_string(max_bytes) + " a file read whole may have");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
    // One byte past the limit tells a file that grew after its size was read.
    std::string contents(size_t(std::min<uintmax_t>(size, max_bytes) + 1), '\0');
    in.read(contents.data(), std::streamsize(contents.size()));
    if (in.bad()) throw InputError(path, "", "read failed");
    contents.resize(size_t(in.gcount()));
    if (contents.size() > max_bytes)
        throw InputError(path, "", "grew past " + std::to_string(max_bytes) + " bytes while it was read");
    return contents;
}

}  // namespace gusuku

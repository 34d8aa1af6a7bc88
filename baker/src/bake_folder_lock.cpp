#include "gusuku_bake/bake_folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "gusuku/formats/input_error.h"

namespace gusuku::bake {

BakeFolderLock::BakeFolderLock(const std::string& output_dir) {
    // The folder is the first thing a bake or merge writes: a read-only or full file system is named here, as
    // one line for the user, not as the library's "filesystem error: cannot create directories".
    std::error_code create_error;
    std::filesystem::create_directories(output_dir, create_error);
    if (create_error)
        throw InputError(output_dir, "-o", "cannot create the folder: " + create_error.message());
    const std::string path = output_dir + "/.lock";
    descriptor_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (descriptor_ < 0) throw std::runtime_error(path + ": cannot create the bake lock: " + std::strerror(errno));
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        ::close(descriptor_);
        descriptor_ = -1;
        if (error == EWOULDBLOCK)
            throw InputError(output_dir, "-o",
                             "another gusuku-bake is baking into this folder (it holds " + path +
                                 "); wait for it to finish or stop it, or choose another folder");
        throw std::runtime_error(path + ": cannot lock: " + std::strerror(error));
    }
}

BakeFolderLock::~BakeFolderLock() {
    if (descriptor_ >= 0) ::close(descriptor_);  // closing the last descriptor releases the flock
}

}  // namespace gusuku::bake

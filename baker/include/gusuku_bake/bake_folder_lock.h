#pragma once
// One bake per bake set folder at a time: an exclusive flock(2) on BAKESET/.lock, held for the bake's
// lifetime. The kernel drops the lock when the process ends however it ends (Ctrl-C, kill -9, a crash), so a
// killed bake never leaves the folder locked; the empty .lock file itself stays and means nothing on its own.

#include <string>

namespace gusuku::bake {

class BakeFolderLock {
public:
    /// Creates output_dir if needed and takes the lock without waiting. Throws InputError(output_dir, "-o",
    /// "another gusuku-bake is baking into this folder ...") when another process (or another lock object)
    /// holds it, and std::runtime_error when the lock file cannot be created.
    explicit BakeFolderLock(const std::string& output_dir);
    ~BakeFolderLock();
    BakeFolderLock(const BakeFolderLock&) = delete;
    BakeFolderLock& operator=(const BakeFolderLock&) = delete;

private:
    int descriptor_ = -1;
};

}  // namespace gusuku::bake

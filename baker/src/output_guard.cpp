// The output guard (gusuku_bake/output_guard.h): every writing command asks it before its first write.
#include "gusuku_bake/output_guard.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/input_error.h"

namespace gusuku::bake {

namespace {

namespace fs = std::filesystem;

// Resolved with symbolic links followed where the path exists, without a trailing "/", so that two spellings of
// one file or folder compare equal.
fs::path resolved(const std::string& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(fs::absolute(path), error);
    if (error) result = fs::absolute(path).lexically_normal();
    if (result.has_relative_path() && result.filename().empty()) result = result.parent_path();
    return result;
}

bool isSameOrInside(const fs::path& path, const fs::path& folder) {
    auto path_part = path.begin();
    for (auto folder_part = folder.begin(); folder_part != folder.end(); ++folder_part, ++path_part)
        if (path_part == path.end() || *path_part != *folder_part) return false;
    return true;
}

std::string describeType(fs::file_type type) {
    switch (type) {
    case fs::file_type::regular: return "a regular file";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::socket: return "a socket";
    default: return "not a folder";
    }
}

// A manifest.json is a bake set's when its text names the format; one that cannot be read counts as one, so
// that the guard errs on the side of leaving it alone.
bool isBakeSetManifest(const fs::path& manifest) {
    std::ifstream in(manifest, std::ios::binary);
    if (!in) return true;
    constexpr size_t kLongestManifestRead = size_t(16) << 20;
    std::string text;
    text.resize(kLongestManifestRead);
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(size_t(in.gcount()));
    return text.find("\"gusuku-bakeset/") != std::string::npos;
}

const char* roleName(FolderRole role) { return role == FolderRole::kRuntimePack ? "runtime pack" : "bake set"; }

class OutputGuard {
public:
    explicit OutputGuard(const OutputRequest& request) : request_(request), output_(resolved(request.output)) {
        for (const std::string& set : request.read_sets) read_sets_.push_back(resolved(set));
        if (!request.packed_set.empty()) own_pack_ = resolved(request.packed_set) / "pack";
    }

    void check() const {
        const fs::file_status status = fs::status(output_, ignored_);
        checkInputs();
        if (request_.kind != OutputKind::kFile) checkIsFolder(status);
        checkAncestors();
        if (request_.kind != OutputKind::kFile && fs::is_directory(status)) {
            checkNothingInside();
            checkExistingFolder();
        }
    }

private:
    [[noreturn]] void refuse(const std::string& problem) const {
        throw InputError(request_.output, request_.field, problem);
    }

    // A read set as the user spelt it; any other folder as resolved.
    std::string shown(const fs::path& folder) const {
        for (size_t i = 0; i < read_sets_.size(); ++i)
            if (read_sets_[i] == folder) return request_.read_sets[i];
        return folder.string();
    }

    void checkIsFolder(const fs::file_status& status) const {
        if (fs::exists(status) && !fs::is_directory(status))
            refuse("is " + describeType(status.type()) + ", not a folder; the " + request_.command +
                   " writes a folder");
    }

    void checkInputs() const {
        for (const std::string& input : request_.inputs) {
            const fs::path file = resolved(input);
            if (file == output_)
                refuse("is an input of the " + request_.command + " (" + input + "); choose another " +
                       (request_.kind == OutputKind::kFile ? "file" : "folder"));
            if (request_.kind != OutputKind::kFile && isSameOrInside(file, output_))
                refuse("holds " + input + ", an input of the " + request_.command +
                       ", which it could overwrite; choose a folder that holds no input");
        }
    }

    // The output itself, when it is a folder already, may be only the command's own kind of output.
    void checkOwnFolder(FolderRole role) const {
        if (request_.kind == OutputKind::kRuntimePack) {
            if (role == FolderRole::kBakeSet && output_ != own_pack_)
                refuse("is the bake set " + shown(output_) +
                       "; a pack goes into a new folder or a previous pack, never over a bake set");
            return;
        }
        if (role == FolderRole::kRuntimePack)
            refuse("is the runtime pack " + shown(output_) + " (it holds pack.bin); the " + request_.command +
                   " writes a bake set into a folder of its own");
        for (size_t i = 0; i < read_sets_.size(); ++i)
            if (read_sets_[i] == output_)
                refuse("is the bake set " + request_.read_sets[i] + " that the " + request_.command +
                       " reads; write into another folder");
        const std::string other_site = siteOfBakeSet(output_);
        if (!other_site.empty() && resolved(other_site) != resolved(request_.site_json))
            refuse("is the bake set of " + other_site + ", not of " + request_.site_json +
                   "; write into another folder (or remove that bake set first)");
    }

    // The site.json a bake set's manifest names, or "" when it cannot be told (no manifest yet: an unfinished
    // bake, which the bake resumes or restarts; a manifest that does not read, which loads as nothing; an old
    // manifest's path relative to where its bake ran; a set copied away from its inputs, whose site.json is no
    // longer where it says).
    static std::string siteOfBakeSet(const fs::path& folder) {
        const std::string manifest_path = (folder / "manifest.json").string();
        std::error_code error;
        if (!fs::exists(manifest_path, error)) return "";
        try {
            const BakeSetManifest manifest = readBakeSetManifest(manifest_path);
            for (const BakeSetInput& input : manifest.inputs) {
                const bool placed = manifest.input_paths_relative_to_folder || fs::path(input.path).is_absolute();
                if (input.role != "site" || !placed) continue;
                const std::string site = resolveBakeSetInputPath(folder.string(), manifest, input.path);
                return fs::exists(site, error) ? site : "";
            }
        } catch (const std::exception&) {
        }
        return "";
    }

    void checkAncestors() const {
        if (request_.kind != OutputKind::kFile) {
            const FolderRole role = folderRole(output_.string());
            if (role != FolderRole::kNone) checkOwnFolder(role);
        }
        for (fs::path above = output_.parent_path(); !above.empty(); above = above.parent_path()) {
            const FolderRole role = folderRole(above.string());
            const bool own_pack_place = request_.kind == OutputKind::kRuntimePack && output_ == own_pack_ &&
                                        above == own_pack_.parent_path();
            if (role != FolderRole::kNone && !own_pack_place)
                refuse(std::string("lies inside the ") + roleName(role) + " " + shown(above) + "; write the " +
                       request_.command + "'s output elsewhere (its files stay as they were made)");
            if (above == above.parent_path()) return;
        }
    }

    // A pack replaces its whole folder: one that holds something else than a pack is not the pack's to replace.
    void checkExistingFolder() const {
        if (request_.kind != OutputKind::kRuntimePack || output_ == own_pack_) return;
        if (folderRole(output_.string()) == FolderRole::kRuntimePack) return;
        if (!fs::is_empty(output_, ignored_))
            refuse("holds files but is not a runtime pack (no pack.bin); a pack replaces its folder whole: choose "
                   "a new or empty folder, or a previous pack");
    }

    void checkNothingInside() const {
        size_t entries = 0;
        std::error_code error;
        fs::recursive_directory_iterator walk(output_, fs::directory_options::skip_permission_denied, error), end;
        for (; !error && walk != end; walk.increment(error)) {
            if (++entries > kMaxScannedEntries)
                refuse("holds more than " + std::to_string(kMaxScannedEntries) +
                       " entries, too many to check for bake sets it could overwrite; choose a new folder");
            if (!walk->is_directory(ignored_) || walk->is_symlink(ignored_)) continue;
            const fs::path folder = walk->path();
            const bool own_pack = request_.kind == OutputKind::kBakeSet && folder == output_ / "pack";
            if (own_pack || isPackTemporaryName(folder.filename().string())) {
                walk.disable_recursion_pending();
                continue;
            }
            const FolderRole role = folderRole(folder.string());
            if (role != FolderRole::kNone)
                refuse(std::string("holds the ") + roleName(role) + " " + shown(folder) + ", which the " +
                       request_.command + " could overwrite; choose a folder that holds none");
        }
    }

    const OutputRequest& request_;
    fs::path output_;
    fs::path own_pack_;
    std::vector<fs::path> read_sets_;
    mutable std::error_code ignored_;  // a path that cannot be looked at counts as absent
};

}  // namespace

FolderRole folderRole(const std::string& folder) {
    std::error_code error;
    const fs::path path(folder);
    if (!fs::is_directory(path, error)) return FolderRole::kNone;
    if (fs::is_regular_file(path / "pack.bin", error)) return FolderRole::kRuntimePack;
    if (fs::is_regular_file(path / "manifest.json", error) && isBakeSetManifest(path / "manifest.json"))
        return FolderRole::kBakeSet;
    if (fs::is_directory(path / ".checkpoint", error)) return FolderRole::kBakeSet;
    return FolderRole::kNone;
}

bool isPackTemporaryName(const std::string& file_name) {
    return file_name.size() > 1 && file_name[0] == '.' && file_name.find(".tmp-") != std::string::npos;
}

void refuseUnsafeOutput(const OutputRequest& request) { OutputGuard(request).check(); }

}  // namespace gusuku::bake

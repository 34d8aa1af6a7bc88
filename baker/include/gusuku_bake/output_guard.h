#pragma once
// The one rule every command that writes (bake, merge, pack, export, gusuku-render) applies to its output before
// it writes anything: an output never replaces, fills or nests inside what someone else made. A command may write
// over its own previous output (a re-bake or resume into the same bake set, a re-pack into the same pack, a new
// export over an old one), never over an input it or its bake set reads, and never into another bake set or pack.

#include <string>
#include <vector>

namespace gusuku::bake {

/// What a command writes, which decides what counts as its own previous output.
enum class OutputKind {
    kBakeSet,      ///< a bake set folder (bake, merge): may replace a bake set of the same site.json
    kRuntimePack,  ///< a runtime pack folder (pack): may replace a previous pack, or be its set's own BAKESET/pack
    kFile,         ///< one file (export's .glb, render's PNGs): may replace a file that nothing else owns
};

/// A folder's role for the guard: a folder holding pack.bin is a runtime pack; one holding a gusuku bake set
/// manifest.json (its text names "gusuku-bakeset/") or an unfinished bake's .checkpoint folder is a bake set.
enum class FolderRole { kNone, kBakeSet, kRuntimePack };
FolderRole folderRole(const std::string& folder);

struct OutputRequest {
    std::string output;          ///< the path as the user gave it (messages name it so)
    std::string field = "-o";    ///< the option that named it: the message's FIELD ("" for none)
    std::string command = "bake";  ///< the command's noun for messages: "bake", "merge", "pack", "export", "render"
    OutputKind kind = OutputKind::kBakeSet;
    /// The files the command (or the bake set it reads) reads: site.json, the building and site glTFs with
    /// their external files, the sky photos; for pack and export, the set manifest's `inputs`.
    std::vector<std::string> inputs;
    /// The bake set folders the command reads (pack's and export's set, merge's partial sets): named in
    /// messages as the user spelt them.
    std::vector<std::string> read_sets;
    /// kBakeSet: the site.json being baked. An existing bake set at the output whose manifest names this site is
    /// the command's own previous output; so is one whose site cannot be told (a manifest that does not read,
    /// an unfinished bake's folder, a set whose recorded site.json no longer exists).
    std::string site_json;
    /// kRuntimePack: the set being packed; its folder/pack is the pack's own place whatever it holds.
    std::string packed_set;
};

/// Throws InputError(output, field, problem) naming the path and what it would destroy, before anything is
/// created or written; touches nothing. Refused, with links and "..", "." resolved:
///   - a folder output that exists as something else than a folder (a file, a FIFO, a device); a folder that
///     cannot be made (below a file, on a read-only disk) is left to the command's "cannot create the folder",
///     and a file output that is a folder to the command's own check;
///   - an output that is one of `inputs`, or a folder holding one at any depth;
///   - an output that is, or lies inside, a bake set or a runtime pack, unless it is the command's own previous
///     output (OutputKind) or the packed set's own pack folder;
///   - a folder output that holds a bake set or a pack below it (other than its own BAKESET/pack), or more than
///     kMaxScannedEntries entries (too large to check: a bake, pack or merge goes into its own folder);
///   - kRuntimePack: an existing folder that holds files but is not a pack (the pack replaces its folder whole).
void refuseUnsafeOutput(const OutputRequest& request);

/// How many entries of an existing output folder are looked at for a bake set or pack inside it.
inline constexpr size_t kMaxScannedEntries = 100000;

/// The prefix of the temporary sibling a pack is written into before it is renamed into place
/// (".<name>.tmp-<pid>-<n>"); a scan skips such leftovers of a stopped pack.
bool isPackTemporaryName(const std::string& file_name);

}  // namespace gusuku::bake

// gusuku-bake merge PARTIAL... -o BAKESET/: joins one-slot partial bake sets (`bake --slot NAME`, one per machine)
// into the bake set one machine would have written (gusuku_bake/bake_merge.h).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku_bake/bake_merge.h"
#include "gusuku_bake/bake_progress.h"
#include "gusuku_bake/runtime_pack.h"

namespace gusuku::bake_cli {

namespace {

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake merge` must say.
CommandHelp mergeHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake merge PARTIAL_DIR... -o BAKESET_DIR";
    help.description =
        "Joins partial bake sets, each one slot of a site baked with `gusuku-bake bake SITE.json -o PARTIAL_DIR\n"
        "--slot NAME` (on one machine each), into the bake set a single `gusuku-bake bake` would have written: the\n"
        "same bytes in every file but the manifest's statistics (summed over the partial sets). Needs no GPU and\n"
        "no input files: only the partial sets.\n"
        "\n"
        "Refuses, before writing anything: a missing or repeated slot, partial sets of different inputs or\n"
        "settings, shared files (building.glb, ground_geometry.exr, occluder.glb) that differ between the sets or\n"
        "from what their manifest recorded, an output folder that is a partial set, is or holds an input, is,\n"
        "holds or lies inside another site's bake set or a pack, and a folder another bake or merge is using\n"
        "(BAKESET_DIR/.lock).";
    help.options = {{"--output", "-o", "DIR", "bake set folder (created)", ""}};
    help.notes = "Exit status: 0 merged, 1 bad input, 2 bad usage.";
    return help;
}

struct MergeRequest {
    std::vector<std::string> partial_folders;
    std::string output_dir;
};

MergeRequest parseArguments(CommandLine& line) {
    MergeRequest request;
    request.output_dir = line.text("--output", "-o").value_or("");
    request.partial_folders = line.positionals();
    line.finish();
    if (request.partial_folders.empty() || request.output_dir.empty())
        line.fail("needs PARTIAL_DIR... and -o BAKESET_DIR (see --help)");
    return request;
}

}  // namespace

int runMergeCommand(const std::vector<std::string>& args) {
    MergeRequest request;
    if (const std::optional<int> exit_code = readCommandLine(
            "gusuku-bake merge", args, mergeHelp(), false, [&](CommandLine& line) { request = parseArguments(line); }))
        return *exit_code;
    const bake::MergeReport report = bake::mergePartialBakeSets(request.partial_folders, request.output_dir);
    std::printf("bake set:        %s\n", report.manifest_path.c_str());
    std::printf("slots:           %zu, from %zu partial sets\n", report.slots, request.partial_folders.size());
    std::printf("rays:            %.3g traced in all, %.3f Mrays/s\n", double(report.statistics.rays_traced),
                report.statistics.rays_per_second / 1e6);
    std::printf("time:            tracing %s in all; the longest partial bake took %s\n",
                bake::formatDuration(report.statistics.trace_seconds).c_str(),
                bake::formatDuration(report.statistics.wall_seconds).c_str());
    // The runtime pack, as `gusuku-bake bake` writes it (gusuku_bake/runtime_pack.h): the same bytes.
    const bake::RuntimePackReport pack = bake::writeRuntimePack(request.output_dir);
    std::printf("runtime pack:    %s (%.2f MiB)\n", pack.folder.c_str(), double(pack.bytes) / 1048576.0);
    return 0;
}

}  // namespace gusuku::bake_cli

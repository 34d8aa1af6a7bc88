// `gusuku-bake sample DIR [--force]`: writes the bundled sample site (sample_site.h) into DIR, so a fresh
// clone can bake without external assets.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku_bake/sample_site.h"

namespace gusuku::bake_cli {

namespace {

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake sample` must say.
CommandHelp sampleHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake sample DIR [--force]";
    help.description =
        "Writes a sample site generated in code into DIR: site.glb (terrain, terrace, steps and a low\n"
        "wall, stored Y-up with its transform in site.json), building.glb (a thatched house with an open\n"
        "doorway), sky_sunny.hdr (CIE clear sky type 12 with the sun disc) and sky_overcast.hdr (CIE\n"
        "overcast sky), and site.json. Then `gusuku-bake bake DIR/site.json -o BAKESET_DIR` bakes it.";
    help.options = {
        {"--force", "", "", "write into DIR even if it is not empty (files of the same names are replaced)", ""},
    };
    return help;
}

}  // namespace

int runSampleCommand(const std::vector<std::string>& args) {
    std::string directory;
    bool force = false;
    const auto parse = [&](CommandLine& line) {
        force = line.flag("--force");
        const std::vector<std::string> directories = line.positionals();
        line.finish();
        if (directories.size() > 1)
            line.fail("more than one DIR given ('" + directories[0] + "', '" + directories[1] + "')");
        if (directories.empty()) line.fail("DIR is missing");
        directory = directories.front();
    };
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake sample", args, sampleHelp(), true, parse))
        return *exit_code;

    std::error_code error;
    const std::filesystem::path path(directory);
    if (std::filesystem::exists(path, error)) {
        if (!std::filesystem::is_directory(path, error)) {
            std::fprintf(stderr, "gusuku-bake sample: %s exists and is not a directory\n", directory.c_str());
            return 1;
        }
        // Refuse to mix the sample into someone's folder unless asked to.
        if (!force && !std::filesystem::is_empty(path, error)) {
            std::fprintf(stderr, "gusuku-bake sample: %s is not empty; use --force to write into it anyway\n",
                         directory.c_str());
            return 1;
        }
    }

    const std::vector<std::string> written = bake::sample_site::writeSampleSite(directory);
    for (const std::string& file : written) {
        const auto bytes = std::filesystem::file_size(file, error);
        std::printf("wrote %s (%llu bytes)\n", file.c_str(), error ? 0ULL : (unsigned long long)bytes);
    }
    std::printf("bake it with: gusuku-bake bake %s -o BAKESET_DIR\n",
                (std::filesystem::path(directory) / "site.json").string().c_str());
    return 0;
}

}  // namespace gusuku::bake_cli

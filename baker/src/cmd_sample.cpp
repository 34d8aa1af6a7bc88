// `gusuku-bake sample DIR [--force]`: writes the bundled sample site (sample_site.h) into DIR, so a fresh
// clone can bake without external assets.
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "gusuku_bake/sample_site.h"

namespace gusuku::bake_cli {

namespace {

void printSampleHelp(std::FILE* stream) {
    std::fprintf(stream,
                 "usage: gusuku-bake sample DIR [--force]\n"
                 "\n"
                 "Writes a sample site generated in code into DIR: site.glb (terrain, terrace, steps and a low\n"
                 "wall, stored Y-up with its transform in site.json), building.glb (a thatched house with an open\n"
                 "doorway), sky_sunny.hdr (CIE clear sky type 12 with the sun disc) and sky_overcast.hdr (CIE\n"
                 "overcast sky), and site.json. Then `gusuku-bake bake DIR/site.json -o BAKESET_DIR` bakes it.\n"
                 "\n"
                 "options:\n"
                 "  --force   write into DIR even if it is not empty (files of the same names are replaced)\n"
                 "  --help    show this help\n");
}

}  // namespace

int runSampleCommand(const std::vector<std::string>& args) {
    std::string directory;
    bool force = false;
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            printSampleHelp(stdout);
            return 0;
        }
        if (arg == "--force") {
            force = true;
        } else if (!arg.empty() && arg[0] == '-') {
            std::fprintf(stderr, "gusuku-bake sample: unknown option '%s'\n\n", arg.c_str());
            printSampleHelp(stderr);
            return 2;
        } else if (directory.empty()) {
            directory = arg;
        } else {
            std::fprintf(stderr, "gusuku-bake sample: more than one DIR given ('%s', '%s')\n\n", directory.c_str(),
                         arg.c_str());
            printSampleHelp(stderr);
            return 2;
        }
    }
    if (directory.empty()) {
        std::fprintf(stderr, "gusuku-bake sample: DIR is missing\n\n");
        printSampleHelp(stderr);
        return 2;
    }

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

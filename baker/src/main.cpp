// gusuku-bake: the offline baker's command line. Subcommands live in cmd_*.cpp; this file only dispatches and
// turns any escaped exception into a message and a non-zero exit (never a crash).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/formats/input_error.h"

namespace {

void printUsage() {
    std::fprintf(stderr,
                 "usage: gusuku-bake <command> [options]\n"
                 "\n"
                 "commands:\n"
                 "  sun       print the sun's position for a place and time (NREL SPA)\n"
                 "  init      write a starter site.json (with comments) and a checklist of what to measure on site\n"
                 "  sample    write the bundled sample site (terrain, house, skies, site.json) into a folder\n"
                 "  check     validate a site.json and load everything it names\n"
                 "  preview   pictures of the placement (top, a visitor's eye) and its checks, before a bake\n"
                 "  bake      bake a site's lightmaps and ground terms into a bake set\n"
                 "  merge     join partial bake sets (one slot each, `bake --slot`) into one bake set\n"
                 "  pack      write a bake set's runtime pack (KTX2 lightmaps, pack.bin; bake writes it too)\n"
                 "  converge  print RMS error against a converged bake as samples grow, and rays per second\n"
                 "  export    write the building with one slot's lightmap as a glTF other engines show\n"
                 "  georef    fit site.json's sfm_mesh transform from ground control points\n"
                 "\n"
                 "`gusuku-bake <command> --help` describes each.\n");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        printUsage();
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    try {
        using namespace gusuku::bake_cli;
        if (command == "sun") return runSunCommand(args);
        if (command == "init") return runInitCommand(args);
        if (command == "sample") return runSampleCommand(args);
        if (command == "check") return runCheckCommand(args);
        if (command == "preview") return runPreviewCommand(args);
        if (command == "bake") return runBakeCommand(args);
        if (command == "converge") return runConvergeCommand(args);
        if (command == "merge") return runMergeCommand(args);
        if (command == "pack") return runPackCommand(args);
        if (command == "export") return runExportCommand(args);
        if (command == "georef") return runGeorefCommand(args);
        std::fprintf(stderr, "gusuku-bake: unknown command '%s'\n\n", command.c_str());
        printUsage();
        return 2;
    } catch (const gusuku::InputError& error) {
        std::fprintf(stderr, "gusuku-bake: error: %s\n", error.what());
        return 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-bake: error: %s\n", error.what());
        return 1;
    }
}

// gusuku-bake pack BAKESET [-o DIR]: writes a finished bake set's runtime pack (gusuku_bake/runtime_pack.h), for
// bake sets made before `bake` wrote one, merged sets, or into another folder.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku_bake/runtime_pack.h"

namespace gusuku::bake_cli {

namespace {

// --textures' choices, in the order of their names; the default is the first.
constexpr bake::PackTextures kPackTextures[] = {bake::PackTextures::kBoth, bake::PackTextures::kAstc,
                                                bake::PackTextures::kRgba8};
constexpr const char* kPackTexturesNames[] = {"both", "astc", "rgba8"};
// The pack's folder when -o is not given, inside BAKESET_DIR (runtime_pack.h's default).
constexpr const char* kDefaultPackFolder = "BAKESET_DIR/pack";

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake pack` must say.
CommandHelp packHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake pack BAKESET_DIR [-o PACK_DIR] [--textures both|astc|rgba8]";
    help.description =
        "Writes the bake set's runtime pack (docs/bakeset.md, \"The runtime pack\"): the lightmaps as E5B9G9R9\n"
        "KTX2 and as ASTC 4x4 and 6x6 HDR blocks (for GPUs that sample them), their validity, the ground terms\n"
        "as float KTX2, the building and occluder as pack.bin, its textures as RGBA8 sRGB KTX2 and as ASTC\n"
        "6x6 sRGB mip chains, and the manifest (statistics zeroed), written last. `gusuku-bake bake` and\n"
        "`merge` write it into BAKESET_DIR/pack themselves; this command is for older bake sets and for a\n"
        "phone's or a desktop's copy (--textures). Needs no GPU.\n"
        "\n"
        "Refuses, before writing anything: a -o folder that is, holds or lies inside an input of the set's bake or\n"
        "any bake set or other pack (BAKESET_DIR's own pack and a previous pack are replaced), or that holds\n"
        "other files. The pack is written into a temporary folder beside it and renamed into place, so a failure\n"
        "(a full disk) leaves the old pack whole.";
    help.options = {
        {"--output", "-o", "DIR", "the pack's folder (created)", kDefaultPackFolder},
        {"--textures", "", "both|astc|rgba8",
         "both (every device), astc (a phone's pack: the ASTC 6x6 files alone, drawn only where the device samples "
         "ASTC LDR; needs -o, since the bake set's own pack feeds the tools, which draw RGBA8) or rgba8 (a desktop's "
         "pack, no encoding)",
         kPackTexturesNames[0]},
    };
    help.notes = "Exit status: 0 written, 1 bad input, 2 bad usage.";
    return help;
}

}  // namespace

int runPackCommand(const std::vector<std::string>& args) {
    std::string bake_set, output;
    bake::PackTextures textures = kPackTextures[0];
    if (const std::optional<int> exit_code =
            readCommandLine("gusuku-bake pack", args, packHelp(), false, [&](CommandLine& line) {
                output = line.text("--output", "-o").value_or("");
                // An unknown kind is bad usage (exit 2), as it always was, not a bad value.
                const std::string kind = line.text("--textures").value_or(kPackTexturesNames[0]);
                const auto known = std::find(std::begin(kPackTexturesNames), std::end(kPackTexturesNames), kind);
                if (known == std::end(kPackTexturesNames))
                    line.fail("--textures: '" + kind + "' is not both, astc or rgba8");
                textures = kPackTextures[known - std::begin(kPackTexturesNames)];
                if (textures == bake::PackTextures::kAstc && output.empty())
                    line.fail("--textures astc: needs -o DIR (the bake set's own pack feeds the tools, which draw "
                              "RGBA8; write a phone's pack elsewhere)");
                const std::vector<std::string> positionals = line.positionals();
                line.finish();
                if (positionals.size() != 1) line.fail("needs one BAKESET_DIR (see --help)");
                bake_set = positionals.front();
            }))
        return *exit_code;
    const bake::RuntimePackReport pack = bake::writeRuntimePack(bake_set, output, textures);
    std::printf("runtime pack:    %s (%.2f MiB; lightmaps E5B9G9R9 %.2f MiB, %s; textures RGBA8 "
                "%.2f MiB, ASTC 6x6 with mips %.2f MiB; ASTC encoded in %.1f s; scale %g)\n",
                pack.folder.c_str(), double(pack.bytes) / 1048576.0, double(pack.lightmap_bytes) / 1048576.0,
                bake::blockLightmapSummary(pack).c_str(), double(pack.texture_bytes) / 1048576.0,
                double(pack.astc_texture_bytes) / 1048576.0, pack.astc_encode_seconds, double(pack.lightmap_scale));
    return 0;
}

}  // namespace gusuku::bake_cli

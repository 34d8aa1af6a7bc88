// gusuku-bake pack BAKESET [-o DIR]: writes a finished bake set's runtime pack (gusuku_bake/runtime_pack.h), for
// bake sets made before `bake` wrote one, merged sets, or into another folder.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku_bake/runtime_pack.h"

namespace gusuku::bake_cli {

namespace {

constexpr const char* kPackUsage =
    "usage: gusuku-bake pack BAKESET_DIR [-o PACK_DIR] [--textures both|astc|rgba8]\n"
    "\n"
    "Writes the bake set's runtime pack (docs/bakeset.md, \"The runtime pack\"): the lightmaps as E5B9G9R9\n"
    "KTX2, their validity, the ground terms as float KTX2, the building and occluder as pack.bin, its\n"
    "textures as RGBA8 sRGB KTX2 and as ASTC 6x6 sRGB mip chains, and the manifest (statistics zeroed),\n"
    "written last. `gusuku-bake bake` and `merge` write it into BAKESET_DIR/pack themselves; this command is\n"
    "for older bake sets and for a phone's or a desktop's copy (--textures). Needs no GPU.\n"
    "\n"
    "Refuses, before writing anything: a -o folder that is, holds or lies inside an input of the set's bake or\n"
    "any bake set or other pack (BAKESET_DIR's own pack and a previous pack are replaced), or that holds\n"
    "other files. The pack is written into a temporary folder beside it and renamed into place, so a failure\n"
    "(a full disk) leaves the old pack whole.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR   the pack's folder (created; default BAKESET_DIR/pack)\n"
    "  --textures KIND    both (default: every device), astc (a phone's pack: the ASTC 6x6 files alone, drawn\n"
    "                     only where the device samples ASTC LDR; needs -o, since the bake set's own pack feeds\n"
    "                     the tools, which draw RGBA8) or rgba8 (a desktop's pack, no encoding)\n"
    "Exit status: 0 written, 1 bad input, 2 bad usage.\n";

}  // namespace

int runPackCommand(const std::vector<std::string>& args) {
    std::string bake_set, output;
    bake::PackTextures textures = bake::PackTextures::kBoth;
    if (const std::optional<int> exit_code =
            readCommandLine("gusuku-bake pack", args, kPackUsage, false, [&](CommandLine& line) {
                output = line.text("--output", "-o").value_or("");
                const std::string kind = line.text("--textures").value_or("both");
                if (kind == "astc") textures = bake::PackTextures::kAstc;
                else if (kind == "rgba8") textures = bake::PackTextures::kRgba8;
                else if (kind != "both") line.fail("--textures: '" + kind + "' is not both, astc or rgba8");
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

// gusuku-bake export BAKESET --slot NAME -o OUT.glb: the building with one slot's lightmap, as a glTF binary other
// engines and viewers show (gusuku_bake/lightmap_export.h, docs/export.md).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku_bake/lightmap_export.h"

namespace gusuku::bake_cli {

namespace {

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake export` must say.
CommandHelp exportHelp() {
    CommandHelp help;
    help.usage = "usage: gusuku-bake export BAKESET_DIR --slot NAME -o OUT.glb";
    help.description =
        "Writes the bake set's building as one glTF binary for other engines (docs/export.md): building.glb as\n"
        "baked, with the slot's lightmap (indirect irradiance, no direct sun) embedded as a linear 8-bit PNG on\n"
        "TEXCOORD_1 through the MOZ_lightmap extension (Mozilla Hubs, three.js's GLTFLightMapLoaderExtension:\n"
        "irradiance = byte / 255 * intensity, intensity the lightmap's brightest value, so every texel decodes\n"
        "within intensity / 510), and the slot's sun, when up, as a KHR_lights_punctual directional light in the\n"
        "same units. Needs no GPU and no input files: only the bake set.\n"
        "\n"
        "Refuses, before writing anything: a missing or bad bake set, a slot it does not hold, an output that is\n"
        "not a .glb, is an input of the set's bake (its building model, site.json, a sky), lies inside any bake\n"
        "set or pack, or cannot be written. The file is written to a temporary name and renamed, so it is never\n"
        "half-written.";
    help.options = {
        {"--slot", "", "NAME", "the slot whose lightmap to bind (see the manifest's slots)", ""},
        {"--output", "-o", "FILE", "the .glb to write", ""},
    };
    help.notes = "Exit status: 0 written, 1 bad input, 2 bad usage.";
    return help;
}

struct ExportRequest {
    std::string bakeset_folder;
    std::string slot;
    std::string output_path;
};

ExportRequest parseArguments(CommandLine& line) {
    ExportRequest request;
    request.output_path = line.text("--output", "-o").value_or("");
    request.slot = line.text("--slot").value_or("");
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() > 1) line.fail("one BAKESET_DIR only ('" + positionals[1] + "' is extra)");
    if (positionals.empty() || request.slot.empty() || request.output_path.empty())
        line.fail("needs BAKESET_DIR, --slot NAME and -o OUT.glb (see --help)");
    request.bakeset_folder = positionals[0];
    return request;
}

}  // namespace

int runExportCommand(const std::vector<std::string>& args) {
    ExportRequest request;
    if (const std::optional<int> exit_code = readCommandLine(
            "gusuku-bake export", args, exportHelp(), false, [&](CommandLine& line) { request = parseArguments(line); }))
        return *exit_code;
    const bake::LightmapExportReport report =
        bake::exportLightmappedGlb(request.bakeset_folder, request.slot, request.output_path);
    std::printf("export:          %s (%.1f KiB)\n", report.output_path.c_str(), double(report.bytes) / 1024.0);
    std::printf("slot:            %s, lightmap %dx%d on TEXCOORD_1 of %zu materials (%s)\n", report.slot.c_str(),
                report.lightmap_width, report.lightmap_height, report.materials, bake::kLightmapExtension);
    std::printf("encoding:        linear 8-bit PNG, intensity %.6g: every channel within %.3g of the bake\n",
                report.intensity, bake::linearLightmapMaxError(report.intensity));
    std::printf("dark texels:     %.1f %% of traced texels under 10 %% of the brightest (over 2 %% error there: the "
                "8-bit PNG holds shadows coarsely, fine for a web preview; the phone pack keeps them in HDR)\n",
                100.0 * report.coarse_valid_texel_fraction);
    std::printf("sun:             %s\n", report.sun_light ? "KHR_lights_punctual directional light, lightmap units"
                                                          : "none (overcast or below the horizon)");
    return 0;
}

}  // namespace gusuku::bake_cli

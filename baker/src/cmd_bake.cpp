// gusuku-bake bake site.json -o BAKESET/: the offline bake. Ctrl-C (SIGINT) or SIGTERM stops within about a second
// (bake_stop_signals.h): after the current dispatch with everything checkpointed; the same command resumes.
#include <cstdio>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bake_stop_signals.h"
#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku/assets/site.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/adaptive_sampling.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/bake_progress.h"
#include "gusuku_bake/runtime_pack.h"

namespace gusuku::bake_cli {

namespace {

// The ranges --samples and --texture-size accept.
constexpr int64_t kMaxBakeSamples = 1000000;
constexpr int64_t kMinTextureSide = 16, kMaxTextureSide = 8192;
// Below this many samples the summary calls the bake a quick look: the errors docs/measurements.md gives at 64
// samples are already several per cent, and adaptive sampling only starts at 32.
constexpr uint32_t kAdviceMinSamples = 64;

// The runtime pack beside the EXRs (gusuku_bake/runtime_pack.h), for a whole bake set; partial sets have none.
void writePackOf(const std::string& folder, bool show_progress = false) {
    // The ASTC encoding takes seconds (13 s on a large site) after the progress bar's 100 %: say what it is doing.
    if (show_progress) std::fprintf(stderr, "gusuku-bake: writing the runtime pack (encoding ASTC for the phone)...\n");
    const bake::RuntimePackReport pack = bake::writeRuntimePack(folder);
    std::printf("runtime pack:    %s (%.2f MiB; lightmaps E5B9G9R9 %.2f MiB, %s; textures RGBA8 "
                "%.2f MiB, ASTC 6x6 with mips %.2f MiB; ASTC encoded in %.1f s)\n",
                pack.folder.c_str(), double(pack.bytes) / 1048576.0, double(pack.lightmap_bytes) / 1048576.0,
                bake::blockLightmapSummary(pack).c_str(), double(pack.texture_bytes) / 1048576.0,
                double(pack.astc_texture_bytes) / 1048576.0, pack.astc_encode_seconds);
}

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake bake` must say.
CommandHelp bakeHelp() {
    const bake::BakeOptions defaults;
    CommandHelp help;
    help.usage = "usage: gusuku-bake bake SITE.json -o BAKESET_DIR [options]";
    help.description =
        "Path-traces the building's indirect irradiance and the ground's sky-and-bounce irradiance (with and\n"
        "without the building) for every slot of SITE.json, and writes a bake set (docs/bakeset.md).";
    help.options = {
        {"--output", "-o", "DIR", "bake set folder (created)", ""},
        {"--samples", "", "N", "samples per texel and ground cell, in [1, " + std::to_string(kMaxBakeSamples) + "]",
         "SITE.json's bake.samples_per_texel, itself " + std::to_string(BakeSettings{}.samples_per_texel) +
             " when absent"},
        {"--slot", "", "NAME",
         "bake only this slot of SITE.json into a partial set, to be joined with the other slots' partial sets by "
         "`gusuku-bake merge` (one slot per machine)",
         "every slot"},
        {"--texture-size", "", "N",
         "the building's textures in the bake set are held to N x N, in [" + std::to_string(kMinTextureSide) + ", " +
             std::to_string(kMaxTextureSide) + "]: the detail the runtime draws; tracing reads them at " +
             std::to_string(defaults.max_texture_size) + " whatever this is",
         std::to_string(defaults.building_texture_size)},
        {"--no-denoise", "", "", "skip the edge-keeping lightmap filter", ""},
        {"--uniform-sampling", "", "",
         "every texel the same samples (without it, from " + std::to_string(bake::kMinAdaptiveSamples) +
             " samples on: a quarter of them, at least " + std::to_string(bake::kMinAdaptivePilotSamples) +
             ", alike as a pilot, the rest where each texel's noise is)",
         ""},
        {"--force", "", "", "bake even if DIR/manifest.json already matches these inputs", ""},
        {"--quiet", "", "", "no progress bar", ""},
    };
    help.notes =
        "The progress bar shows the slot, the samples each texel has of its total (spp: samples per texel; more\n"
        "is less noise), Mrays/s (million ray segments a second: the device's speed) and the time left. The\n"
        "summary at the end explains the rays figure and the invalid texels, and says when the samples are too\n"
        "few for the phone.\n"
        "Ctrl-C or SIGTERM stops within about a second; everything traced so far is kept in DIR/.checkpoint,\n"
        "and running the same command again continues from there. The environment variable GUSUKU_DEVICE picks a\n"
        "Vulkan device by name (e.g. llvmpipe); GUSUKU_VALIDATION=1 turns on the Khronos validation layer.\n"
        "Exit status: 0 done or up to date, 1 bad input or a bad option value, 2 bad usage, 130 interrupted.";
    return help;
}

struct BakeRequest {
    std::string site_path;
    bake::BakeOptions options;
};

BakeRequest parseArguments(CommandLine& line) {
    BakeRequest request;
    bake::BakeOptions& options = request.options;
    options.output_dir = line.text("--output", "-o").value_or("");
    if (const std::optional<int64_t> samples = line.integer("--samples", 1, kMaxBakeSamples))
        options.samples_override = int(*samples);
    if (const std::optional<int64_t> side = line.integer("--texture-size", kMinTextureSide, kMaxTextureSide))
        options.building_texture_size = int(*side);
    options.denoise = !line.flag("--no-denoise");
    options.adaptive_sampling = !line.flag("--uniform-sampling");
    options.force = line.flag("--force");
    options.slot = line.text("--slot").value_or("");
    options.show_progress = !line.flag("--quiet");
    const std::vector<std::string> sites = line.positionals();
    line.finish();
    if (sites.size() > 1) line.fail("one site.json only ('" + sites[1] + "' is extra)");
    if (sites.empty() || options.output_dir.empty()) line.fail("needs SITE.json and -o BAKESET_DIR (see --help)");
    request.site_path = sites.front();
    return request;
}

}  // namespace

int runBakeCommand(const std::vector<std::string>& args) {
    BakeRequest request;
    if (const std::optional<int> exit_code = readCommandLine(
            "gusuku-bake bake", args, bakeHelp(), false, [&](CommandLine& line) { request = parseArguments(line); }))
        return *exit_code;
    bake::BakeOptions& options = request.options;

    // From the start: a Ctrl-C during setup (device, skies, BVH) ends the bake before its first sample.
    BakeStopSignals stop_signals(options.output_dir);
    options.should_stop = stop_signals.poll();
    const SiteConfig site = loadSiteConfig(request.site_path);
    if (!options.slot.empty()) bake::requireSiteSlot(site, options.slot);  // before the device is opened
    VulkanContext context(vulkanOptionsFromEnvironment());
    std::fprintf(stderr, "gusuku-bake: device %s\n", context.deviceDescription().c_str());

    const bake::BakeReport report = bake::runBake(context, site, options);
    // The set is written: a stop from here ends at once (the pack goes to a temporary folder first), and one
    // that came while the bake returned (its last files written, no poll left to see it) is honoured here.
    if ((report.completed || report.up_to_date) && stop_signals.beginPacking()) {
        std::fputs(stop_signals.packingMessage().c_str(), stderr);
        return 130;
    }

    if (report.up_to_date) {
        std::printf("bake set %s is up to date with its inputs (use --force to bake again)\n",
                    options.output_dir.c_str());
        if (options.slot.empty() && !bake::runtimePackIsUpToDate(options.output_dir)) writePackOf(options.output_dir);
        return 0;
    }
    if (!report.completed) {
        std::fprintf(stderr,
                     "gusuku-bake: interrupted; the work done is saved in %s/.checkpoint. Run the same command "
                     "again to resume.\n",
                     options.output_dir.c_str());
        return 130;
    }
    const double rays_per_second = report.trace_seconds > 0.0 ? double(report.rays_traced) / report.trace_seconds : 0.0;
    std::printf("bake set:        %s\n", report.manifest_path.c_str());
    if (options.slot.empty())
        std::printf("slots:           %zu\n", site.bake.slots.size());
    else
        std::printf("slots:           1 (%s, a partial set of %zu: join them with gusuku-bake merge)\n",
                    options.slot.c_str(), site.bake.slots.size());
    std::printf("samples:         %u per texel and per ground cell%s\n", report.samples_per_point,
                report.samples_per_point < kAdviceMinSamples
                    ? " (a quick look: noisy; bake with 256 or more for the phone, --samples or "
                      "bake.samples_per_texel, and measure the noise with gusuku-bake converge)"
                    : "");
    const double lightmap_texels = double(report.lightmap_resolution) * double(report.lightmap_resolution);
    std::printf("building:        %zu lightmap texels (%dx%d, charts fill %.1f %%)\n", report.building_texels,
                report.lightmap_resolution, report.lightmap_resolution,
                lightmap_texels > 0.0 ? 100.0 * double(report.building_texels) / lightmap_texels : 0.0);
    if (report.masked_triangles > 0)
        std::printf("alpha masks:     %zu of %zu masked triangles alpha-tested (the rest read no texel below the "
                    "cutoff)\n",
                    report.alpha_tested_triangles, report.masked_triangles);
    for (const bake::InvalidTexelCounts& invalid : report.invalid_texels)
        std::printf("invalid texels:  %s %zu (%.1f %%): %zu one-sided backs, %zu under the ground, %zu inside closed "
                    "double-sided parts, %zu unexplained\n",
                    invalid.slot.c_str(), invalid.total,
                    report.building_texels > 0 ? 100.0 * double(invalid.total) / double(report.building_texels) : 0.0,
                    invalid.one_sided_backs, invalid.under_ground, invalid.closed_double_sided, invalid.unexplained);
    if (!report.invalid_texels.empty() && report.invalid_texels.front().total > 0) {
        // What each kind means for the site team, named once for all slots (their counts differ little).
        const bake::InvalidTexelCounts& first = report.invalid_texels.front();
        std::printf("                 (invalid texels are filled from their neighbours; ");
        std::vector<std::string> advice;
        if (first.one_sided_backs > 0) advice.push_back("one-sided backs lie inside the model (under a wall, behind a floor): never seen, fine");
        if (first.under_ground > 0)
            advice.push_back("under the ground: a foot or a part sunk in the site mesh, fine for a footing, else run "
                             "gusuku-bake preview and raise the building");
        if (first.closed_double_sided > 0)
            advice.push_back("inside closed double-sided parts: beams or boxes passing through one another, fine "
                             "where no one can see in");
        if (first.unexplained > 0) advice.push_back("unexplained: at the limit of the check's noise, a few are normal");
        for (size_t i = 0; i < advice.size(); ++i)
            std::printf("%s%s", i ? "; " : "", advice[i].c_str());
        std::printf(")\n");
    }
    std::printf("ground:          %zu cells\n", report.ground_cells);
    if (report.resumed_fraction > 0.0)
        std::printf("resumed:         %.0f %% of the work came from checkpoints\n", report.resumed_fraction * 100.0);
    std::printf("rays:            %.3g traced, %.3f Mrays/s\n", double(report.rays_traced), rays_per_second / 1e6);
    // On a line of its own: scripts (bench/tracer_speed.sh, readme-figures.py) read the line above as it is.
    std::printf("                 (million ray segments a second, the device's speed: a bake's time is about samples "
                "x texels x bounces over it; a CPU device such as llvmpipe is 100x slower than a GPU)\n");
    std::printf("wall time:       %s (tracing %s)\n", bake::formatDuration(report.wall_seconds).c_str(),
                bake::formatDuration(report.trace_seconds).c_str());
    if (options.slot.empty()) writePackOf(options.output_dir, options.show_progress);
    return 0;
}

}  // namespace gusuku::bake_cli

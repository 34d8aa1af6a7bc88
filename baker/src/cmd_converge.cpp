// gusuku-bake converge site.json: the convergence curve and the tracer's speed on a real site.
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/adaptive_sampling.h"
#include "gusuku_bake/convergence.h"
#include "gusuku_bake/cycles_lighting_export.h"

namespace gusuku::bake_cli {

namespace {

// The sample counts --reference-samples and --max-samples accept: 1 up to, not including, 1e7.
constexpr int64_t kMaxSampleCount = 9999999;
// The relative RMS error whose trace time the study reports when --target-rms is not given.
constexpr double kDefaultTargetRms = 0.05;

// --sky-sampling's choices, in the order of their names.
constexpr bake::SkySampling kSkySamplings[] = {bake::SkySampling::Automatic, bake::SkySampling::CosineOnly,
                                               bake::SkySampling::CosineAndMap};
constexpr const char* kSkySamplingNames[] = {"auto", "cosine", "mis"};

std::string skySamplingOptionName(bake::SkySampling sampling) {
    for (size_t index = 0; index < std::size(kSkySamplings); ++index)
        if (kSkySamplings[index] == sampling) return kSkySamplingNames[index];
    return "?";
}

// The command's option table: its --help, and what docs/baker.md's table of `gusuku-bake converge` must say.
CommandHelp convergeHelp() {
    const bake::ConvergenceOptions defaults;
    CommandHelp help;
    help.usage =
        "usage: gusuku-bake converge SITE.json [--slot NAME] [--reference-samples N] [--max-samples N]\n"
        "                            [--target-rms R] [--sky-sampling auto|cosine|mis] [--sampling adaptive|uniform]\n"
        "                            [--error-mask IMAGE]\n"
        "       gusuku-bake converge SITE.json --slot NAME --export-lighting DIR";
    help.description =
        "Bakes the building lightmap of one slot at 1, 2, 4, ... --max-samples samples per texel and prints the\n"
        "relative RMS error of each against a reference of --reference-samples (an independent seed), with and\n"
        "without the edge-keeping filter, the log-log slope (-0.5 for 1/sqrt(samples)), rays per second, and the\n"
        "trace time needed to reach --target-rms.";
    help.options = {
        {"--slot", "", "NAME", "the slot to study", "the site's first slot"},
        {"--reference-samples", "", "N",
         "samples per texel of the reference bake, at most " + std::to_string(kMaxSampleCount),
         std::to_string(defaults.reference_samples)},
        {"--max-samples", "", "N", "the study doubles from 1 up to this, at most --reference-samples",
         std::to_string(defaults.max_samples)},
        {"--target-rms", "", "R", "the relative RMS error, in (0, 1), whose trace time is reported",
         defaultNumber(kDefaultTargetRms)},
        {"--sky-sampling", "", "auto|cosine|mis",
         "how paths gather the sky: as a bake does (auto), the cosine lobe alone, or with the map by MIS; to "
         "compare the two on a site's own sky",
         skySamplingOptionName(defaults.sky_sampling)},
        {"--sampling", "", "adaptive|uniform",
         "adaptive (what a bake does: from " + std::to_string(bake::kMinAdaptiveSamples) +
             " samples on, a pilot of a quarter of the samples, at least " +
             std::to_string(bake::kMinAdaptivePilotSamples) +
             ", and the rest where each texel's noise is) or uniform (every texel alike)",
         defaults.adaptive ? "adaptive" : "uniform"},
        {"--error-mask", "", "IMAGE",
         "an image of the lightmap's size (row 0 at the top); its texels with a first channel above 0.5 get their "
         "own error columns (common_*), e.g. the texels another baker bakes too",
         ""},
        {"--export-lighting", "", "DIR",
         "write the slot's sky without its sun (DIR/sky_NAME.hdr, laid out for Blender's world) and its sun "
         "(DIR/sun_NAME.json) as the bake traces them, for bench/cycles, and run no study",
         ""},
    };
    help.notes = "Exit status: 0 ok, 1 bad input or a bad option value, 2 bad usage.";
    return help;
}

struct ConvergeRequest {
    std::string site_path;
    bake::ConvergenceOptions options;
    double target_rms = kDefaultTargetRms;
    std::string export_lighting_folder;  ///< non-empty: write the slot's lighting for bench/cycles, no study
    std::string error_mask_path;         ///< non-empty: an image of texels with their own error columns
};

ConvergeRequest parseArguments(CommandLine& line) {
    ConvergeRequest request;
    bake::ConvergenceOptions& options = request.options;
    options.slot_name = line.text("--slot").value_or("");
    request.export_lighting_folder = line.text("--export-lighting").value_or("");
    request.error_mask_path = line.text("--error-mask").value_or("");
    if (const std::optional<int64_t> samples = line.integer("--reference-samples", 1, kMaxSampleCount))
        options.reference_samples = uint32_t(*samples);
    if (const std::optional<int64_t> samples = line.integer("--max-samples", 1, kMaxSampleCount))
        options.max_samples = uint32_t(*samples);
    if (const std::optional<double> target_rms = line.number("--target-rms", 0.0, 1.0)) {
        // An error of 0 is never reached and one of 1 is no target: the open interval (0, 1).
        if (*target_rms <= 0.0 || *target_rms >= 1.0) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", *target_rms);
            line.failValue("--target-rms", std::string(value) + " is outside (0, 1)");
        }
        request.target_rms = *target_rms;
    }
    if (const std::optional<size_t> method =
            line.choice("--sky-sampling", {kSkySamplingNames[0], kSkySamplingNames[1], kSkySamplingNames[2]}))
        options.sky_sampling = kSkySamplings[*method];
    if (const std::optional<size_t> sampling = line.choice("--sampling", {"adaptive", "uniform"}))
        options.adaptive = *sampling == 0;
    const std::vector<std::string> sites = line.positionals();
    line.finish();
    if (sites.size() > 1) line.fail("one site.json only ('" + sites[1] + "' is extra)");
    if (sites.empty()) line.fail("needs SITE.json (see --help)");
    if (!request.export_lighting_folder.empty() && options.slot_name.empty())
        line.fail("--export-lighting needs --slot NAME");
    // The error is measured against the reference: an estimate with more samples than the reference would
    // measure the reference's own noise.
    if (options.max_samples > options.reference_samples)
        line.fail("--max-samples " + std::to_string(options.max_samples) + " is above --reference-samples " +
                  std::to_string(options.reference_samples) +
                  "; the reference must have at least as many samples as the largest estimate");
    request.site_path = sites.front();
    return request;
}

}  // namespace

int runConvergeCommand(const std::vector<std::string>& args) {
    ConvergeRequest request;
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake converge", args, convergeHelp(), false,
                                                             [&](CommandLine& line) { request = parseArguments(line); }))
        return *exit_code;
    const SiteConfig site = loadSiteConfig(request.site_path);
    if (!request.export_lighting_folder.empty()) {
        bake::exportSlotLightingForCycles(site, request.options.slot_name, request.export_lighting_folder);
        return 0;
    }
    if (!request.error_mask_path.empty()) {
        // Read before the device starts, so that a bad mask fails at once. The lightmap's size is known only
        // after the charts are made: the study checks it.
        const ImageRGBA mask = readImage(request.error_mask_path, ImageEncoding::Linear);
        if (mask.width != mask.height)
            throw InputError(request.error_mask_path, "size",
                             std::to_string(mask.width) + " x " + std::to_string(mask.height) +
                                 " is not square, as a lightmap is");
        request.options.error_mask.resize(size_t(mask.width) * size_t(mask.height));
        for (size_t i = 0; i < request.options.error_mask.size(); ++i)
            request.options.error_mask[i] = mask.texels[i * 4] > 0.5f ? 1 : 0;
        request.options.error_mask_name = request.error_mask_path;
    }
    VulkanContext context(vulkanOptionsFromEnvironment());
    std::fprintf(stderr, "gusuku-bake: device %s\n", context.deviceDescription().c_str());
    const bake::ConvergenceStudy study = bake::runConvergenceStudy(context, site, request.options);
    std::fputs(bake::formatConvergenceStudy(study, request.target_rms).c_str(), stdout);
    return 0;
}

}  // namespace gusuku::bake_cli

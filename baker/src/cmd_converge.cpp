// gusuku-bake converge site.json: the convergence curve and the tracer's speed on a real site.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "commands.h"
#include "gusuku/site.h"
#include "gusuku/vulkan_context.h"
#include "gusuku_bake/convergence.h"

namespace gusuku::bake_cli {

namespace {

bool parsePositive(const std::string& text, double& value) {
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return end != text.c_str() && *end == '\0' && value > 0.0 && value < 1e7;
}

}  // namespace

int runConvergeCommand(const std::vector<std::string>& args) {
    std::string site_path;
    bake::ConvergenceOptions options;
    double target_rms = 0.05;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        double value = 0.0;
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: gusuku-bake converge SITE.json [--slot NAME] [--reference-samples N] [--max-samples N]\n"
                "                            [--target-rms R] [--sky-sampling auto|cosine|mis]\n"
                "\n"
                "Bakes the building lightmap of one slot at 1, 2, 4, ... --max-samples (default 128) samples per\n"
                "texel and prints the relative RMS error of each against a reference of --reference-samples (default\n"
                "1024, an independent seed), with and without the edge-keeping filter, the log-log slope (-0.5 for\n"
                "1/sqrt(samples)), rays per second, and the trace time needed to reach --target-rms (default 0.05).\n"
                "--sky-sampling forces how paths gather the sky (cosine lobe alone, or with the map by MIS; auto, the\n"
                "default, is what a bake does), to compare the two on a site's own sky.\n");
            return 0;
        }
        if ((arg == "--slot" || arg == "--reference-samples" || arg == "--max-samples" || arg == "--target-rms" ||
             arg == "--sky-sampling") &&
            i + 1 >= args.size()) {
            std::fprintf(stderr, "gusuku-bake converge: %s needs a value\n", arg.c_str());
            return 2;
        }
        if (arg == "--slot") {
            options.slot_name = args[++i];
        } else if (arg == "--reference-samples" || arg == "--max-samples") {
            if (!parsePositive(args[++i], value) || value != double(uint32_t(value))) {
                std::fprintf(stderr, "gusuku-bake converge: %s: '%s' is not a positive integer\n", arg.c_str(),
                             args[i].c_str());
                return 2;
            }
            (arg == "--max-samples" ? options.max_samples : options.reference_samples) = uint32_t(value);
        } else if (arg == "--target-rms") {
            if (!parsePositive(args[++i], target_rms) || target_rms >= 1.0) {
                std::fprintf(stderr, "gusuku-bake converge: --target-rms: '%s' is not in (0, 1)\n", args[i].c_str());
                return 2;
            }
        } else if (arg == "--sky-sampling") {
            const std::string& method = args[++i];
            if (method == "auto") {
                options.sky_sampling = bake::SkySampling::Automatic;
            } else if (method == "cosine") {
                options.sky_sampling = bake::SkySampling::CosineOnly;
            } else if (method == "mis") {
                options.sky_sampling = bake::SkySampling::CosineAndMap;
            } else {
                std::fprintf(stderr, "gusuku-bake converge: --sky-sampling: '%s' is not auto, cosine or mis\n",
                             method.c_str());
                return 2;
            }
        } else if (!arg.empty() && arg[0] == '-') {
            std::fprintf(stderr, "gusuku-bake converge: unknown option '%s' (see --help)\n", arg.c_str());
            return 2;
        } else {
            site_path = arg;
        }
    }
    if (site_path.empty()) {
        std::fprintf(stderr, "gusuku-bake converge: needs SITE.json (see --help)\n");
        return 2;
    }
    // The error is measured against the reference: an estimate with more samples than the reference would
    // measure the reference's own noise.
    if (options.max_samples > options.reference_samples) {
        std::fprintf(stderr,
                     "gusuku-bake converge: --max-samples %u is above --reference-samples %u; the reference must "
                     "have at least as many samples as the largest estimate\n",
                     options.max_samples, options.reference_samples);
        return 2;
    }
    const SiteConfig site = loadSiteConfig(site_path);
    VulkanContext context(vulkanOptionsFromEnvironment());
    std::fprintf(stderr, "gusuku-bake: device %s\n", context.deviceDescription().c_str());
    const bake::ConvergenceStudy study = bake::runConvergenceStudy(context, site, options);
    std::fputs(bake::formatConvergenceStudy(study, target_rms).c_str(), stdout);
    return 0;
}

}  // namespace gusuku::bake_cli

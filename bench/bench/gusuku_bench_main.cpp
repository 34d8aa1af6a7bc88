// gusuku-bench: the runtime's frame time on this machine's Vulkan against its accuracy to a path-traced truth,
// one mode against another, from one run (docs/measurements.md, "The benchmark").
//
// Sections, in order (each writes its part of results.json; the summary is printed and written as summary.md):
//   truth     the site WITH the building, path-traced (the truth), its noise between two seeds; the site
//             WITHOUT it (the camera frame), through a camera response (camera_response.h);
//   accuracy  every mode's composite (or path-traced frame) against the truth: mean and p95 CIEDE2000, PSNR,
//             over the pixels the building changes and over the whole frame, at the accuracy size;
//   timing    fenced whole frames at 1280x720 and 640x360, modes interleaved; a per-pass profile; the path
//             tracer's frame at 640x360;
//   chart     error against frame time, log x, with the goals (chart.svg + chart.json);
//   day       the day in steps: nearest slot, blend of two, direct-only (day.svg);
//   weather   overcast and partial cloud under three camera responses, colour match on and off, both modes;
//   cost      frame time against building triangles and against screen coverage;
//   clouds    the cloud-cover estimate from camera frames of known weather;
//   site      (with --views) the goals from each visitor pose, at a baked instant and 1.5 hours from it
//             (site_section.cpp; scripts/bench-sites.sh runs it on the sample and on real models).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bakeset_site.h"
#include "bench_run.h"
#include "camera_response.h"
#include "camera_view.h"
#include "gusuku/maths/weather_estimate.h"
#include "gusuku_bake/content_hash.h"
#include "frame_spread.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/camera_frame.h"
#include "host_info.h"
#include "image_metrics.h"
#include "runtime_modes.h"
#include "svg_chart.h"
#include "truth_renderer.h"

namespace gusuku::bench {
namespace {

// Where path-traced frames are kept when --cache is not given: this folder beside the output folder.
constexpr const char* kCacheFolderName = "bench-cache";

// --quick: the short run (small frames, few samples, fewer steps), a minute or two.
void applyQuickRun(Settings& settings) {
    settings.accuracy_width = 160, settings.accuracy_height = 90, settings.truth_samples = 128;
    settings.sweep_width = 96, settings.sweep_height = 54, settings.sweep_samples = 64;
    settings.day_step_minutes = 120;
    settings.timed_frames = 15, settings.warm_up_frames = 3;
    settings.tracer_timed_max_samples = 4;
}

// The command's option table: its --help, and what docs/measurements.md's table of gusuku-bench must say.
CommandHelp benchHelp() {
    const Settings defaults;
    Settings quick;
    applyQuickRun(quick);
    CommandHelp help;
    help.usage = "usage: gusuku-bench BAKESET -o DIR [--quick] [options]";
    help.description =
        "Frame time of gusuku's runtime on this machine's Vulkan against its accuracy to a path-traced truth, for\n"
        "direct-only, the proposed method with each part on and off, and the path tracer itself; the day, the weather,\n"
        "camera responses and the cost against triangles and coverage. Writes DIR/results.json, DIR/chart.svg,\n"
        "DIR/chart.json, DIR/day.svg, DIR/summary.md and the frames it compares; prints the summary.";
    help.options = {
        {"--output", "-o", "DIR", "the results' folder", ""},
        {"--quick", "", "", "the short run (small frames, few samples, fewer steps): a minute or two", ""},
        {"--cache", "", "DIR", "path-traced frames are kept here by key", std::string("DIR/../") + kCacheFolderName},
        {"--site", "", "SITE.json", "the site", "the one the bake set was baked from"},
        {"--only", "", "LIST",
         "comma-separated sections to run: truth,timing,day,weather,cost,clouds,field,site (truth, the accuracy of every "
         "mode and the chart always run, unless LIST names only site or field)",
         "every section"},
        {"--photographed-skies", "", "BAKESET2",
         "the same site baked under photographed skies (scripts/bench.sh bakes one under ../shared/data/env when it "
         "is there): the weather, clouds and field sections run under them too, with their own path-traced truths",
         ""},
        {"--truth-samples", "", "N", "samples a pixel of every path-traced truth",
         std::to_string(defaults.truth_samples) + ", --quick " + std::to_string(quick.truth_samples)},
        {"--accuracy-size", "", "WxH", "the accuracy frames' size",
         std::to_string(defaults.accuracy_width) + "x" + std::to_string(defaults.accuracy_height) + ", --quick " +
             std::to_string(quick.accuracy_width) + "x" + std::to_string(quick.accuracy_height)},
        {"--msaa", "", "N", "the runtime's samples a pixel (RuntimeOptions::msaa_samples)",
         std::to_string(defaults.msaa_samples)},
        {"--anisotropy", "", "N",
         "the runtime's texture anisotropy (RuntimeOptions::max_anisotropy), clamped to what the bench's own device "
         "has",
         defaultNumber(defaults.max_anisotropy)},
        {"--views", "", "LIST", "the site section's visitor poses, NAME:E,N,U:E,N,U (eye, look-at) separated by ';'",
         ""},
        {"--sample-bakeset", "", "DIR",
         "the sample's bake set: the site section times its frame from each pose in the same run, interleaved with "
         "the site's (preferred over --sample-results)",
         ""},
        {"--sample-results", "", "FILE",
         "the sample's results.json: the site section reads the frame against the sample's", ""},
        {"--cycles-truth", "", "DIR",
         "Cycles' renders of the --views poses at the site section's size, lit by the slot of its baked instant "
         "(bench/cycles/compare_views_with_cycles.sh writes them): each pose reports the path tracer's difference "
         "from Cycles beside its own seed-to-seed noise",
         ""},
    };
    help.notes = "Exit status: 0 ok, 1 bad input, 2 bad usage.";
    return help;
}

Settings parseSettings(const std::vector<std::string>& args, bool& help) {
    Settings settings;
    CommandLine line("gusuku-bench", args);
    line.useOptionTable(benchHelp().options);
    help = line.helpRequested();
    if (help) return settings;
    const std::optional<std::string> output = line.text("--output", "-o");
    settings.quick = line.flag("--quick");
    settings.site_json = line.text("--site");
    settings.photographed_bake_set = line.text("--photographed-skies");
    const std::optional<std::string> cache = line.text("--cache");
    settings.sample_results = line.text("--sample-results");
    settings.sample_bake_set = line.text("--sample-bakeset");
    settings.cycles_truth = line.text("--cycles-truth");
    if (const auto views = line.text("--views")) {
        try {
            settings.views = parseBenchViews(*views);
        } catch (const std::invalid_argument& error) {
            throw OptionValueError("gusuku-bench: " + std::string(error.what()));
        }
    }
    const std::optional<int64_t> truth_samples = line.integer("--truth-samples", 1, 1 << 20);
    const std::optional<std::string> accuracy_size = line.text("--accuracy-size");
    if (const auto msaa = line.integer("--msaa", 1, 64)) settings.msaa_samples = uint32_t(*msaa);
    if (const auto anisotropy = line.integer("--anisotropy", 1, 16)) settings.max_anisotropy = float(*anisotropy);
    if (const auto only = line.text("--only")) {
        std::stringstream stream(*only);
        for (std::string section; std::getline(stream, section, ',');) {
            static const std::vector<std::string> known{"truth", "timing", "day", "weather", "cost", "clouds", "field",
                                                        "site"};
            if (std::find(known.begin(), known.end(), section) == known.end())
                line.failValue("--only", "'" + section + "' is not one of truth,timing,day,weather,cost,clouds,field,site");
            settings.only.push_back(section);
        }
    }
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() != 1) line.fail("needs exactly one BAKESET folder (see --help)");
    if (!output) line.fail("needs -o DIR (see --help)");
    settings.bake_set = positionals[0];
    settings.output = *output;
    settings.cache = cache.value_or((std::filesystem::path(*output).parent_path() / kCacheFolderName).string());
    if (settings.cache.empty()) settings.cache = kCacheFolderName;
    if (settings.quick) applyQuickRun(settings);
    if (truth_samples) settings.truth_samples = uint32_t(*truth_samples);
    if (accuracy_size) {
        unsigned width = 0, height = 0;
        char end = 0;
        if (std::sscanf(accuracy_size->c_str(), "%ux%u%c", &width, &height, &end) != 2 || width < 16 ||
            height < 16 || width > 4096 || height > 4096)
            line.failValue("--accuracy-size", "'" + *accuracy_size + "' is not WxH with each in [16, 4096]");
        settings.accuracy_width = width, settings.accuracy_height = height;
    }
    if (settings.sample_results && settings.views.empty()) line.fail("--sample-results needs --views (see --help)");
    if (settings.sample_bake_set && settings.views.empty()) line.fail("--sample-bakeset needs --views (see --help)");
    if (settings.cycles_truth && settings.views.empty()) line.fail("--cycles-truth needs --views (see --help)");
    if (!settings.views.empty() && !settings.only.empty() && !settings.wants("site"))
        line.fail("--views is for the site section, which --only leaves out (see --help)");
    if (settings.views.empty() && std::find(settings.only.begin(), settings.only.end(), "site") != settings.only.end())
        line.fail("--only site needs --views (see --help)");
    return settings;
}

// The weather section for one pair of skies: the sample's analytic ones (the bake set's) or the photographed ones
// (--photographed-skies: the same site baked under ../shared/data/env). Returns its JSON.
Json runWeatherUnder(Bench& bench, const SkySet& skies) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.sweep_width, height = settings.sweep_height;
    const double utc = bench.bake_midnight_utc + 10.5 * 3600.0;
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    Runtime& runtime = *skies.runtime;
    bench.say("");
    bench.say("**Weather and camera responses, " + skies.label + " (" + std::to_string(width) + "x" +
              std::to_string(height) + ", " + bench.localTime(utc) + ", mean dE00 over the building and shadow)**");
    // "proposed, match" is the ground match (n/a for a bake set without ground albedo); the preserve match beside.
    bench.say("| cloud cover | camera response | proposed, match | proposed, preserve match | proposed, no match | "
              "direct-only |");
    bench.say("| --- | --- | --- | --- | --- | --- |");
    Json rows = Json::array();
    for (float cover : {0.0f, 0.5f, 1.0f}) {
        const ConditionFrames frames = traceCondition(*skies.renderer, bench.view, width, height, {utc, cover},
                                                      settings.sweep_samples);
        for (const CameraResponse& response : benchCameraResponses()) {
            const auto [truth, camera, mask] = respondedFrames(frames, response);
            auto errorOf = [&](const std::string& mode_name) {
                const FrameInput input = frameInputFor(runtimeModeNamed(mode_name), camera, intrinsics, pose, utc,
                                                       cover, frames.exposure * response.exposure_scale);
                return summariseError(steadyComposite(runtime, input), truth, mask);
            };
            std::optional<ErrorSummary> ground;
            if (skies.has_ground_albedo) ground = errorOf("proposed_ground_match");
            const ErrorSummary matched = errorOf("proposed_preserve_match"), unmatched = errorOf("proposed"),
                               direct = errorOf("direct_only");
            rows.push_back({{"cloud_cover", cover}, {"camera_response", response.name},
                            {"proposed_ground_match", ground ? errorJson(*ground) : Json()},
                            {"proposed_preserve_match", errorJson(matched)}, {"proposed", errorJson(unmatched)},
                            {"direct_only", errorJson(direct)}});
            bench.say("| " + fixed(cover, 1) + " | " + response.name + " | " +
                      (ground ? fixed(ground->mean_de00) : std::string("n/a")) + " | " + fixed(matched.mean_de00) +
                      " | " + fixed(unmatched.mean_de00) + " | " + fixed(direct.mean_de00) + " |");
        }
    }
    return {{"skies", skies.label}, {"size", std::to_string(width) + "x" + std::to_string(height)},
            {"local_time", bench.localTime(utc)}, {"rows", rows}};
}

// A section under the analytic skies (results[key]), then under the photographed ones
// (results[key + "_photographed_skies"], or why they were not run).
void runUnderEachSkySet(Bench& bench, const std::string& key, Json (*section)(Bench&, const SkySet&)) {
    bench.results[key] = section(bench, bench.analyticSkies());
    if (bench.photographed) {
        bench.results[key + "_photographed_skies"] = section(bench, bench.photographedSkies());
    } else {
        bench.results[key + "_photographed_skies"] = bench.photographed_skipped;
        bench.say("photographed skies: " + bench.photographed_skipped);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Cost: triangles and coverage
// ---------------------------------------------------------------------------------------------------------------

// Each triangle of the building split into four at its edges' midpoints (attributes interpolated).
BakeSetMesh subdivide(const BakeSetMesh& mesh) {
    BakeSetMesh finer = mesh;
    finer.indices.clear();
    finer.triangle_material.clear();
    auto midpoint = [&](uint32_t a, uint32_t b) {
        finer.positions.push_back(0.5f * (mesh.positions[a] + mesh.positions[b]));
        finer.normals.push_back(glm::normalize(mesh.normals[a] + mesh.normals[b] + glm::vec3(1e-12f)));
        finer.uv0.push_back(0.5f * (mesh.uv0[a] + mesh.uv0[b]));
        finer.uv1.push_back(0.5f * (mesh.uv1[a] + mesh.uv1[b]));
        return uint32_t(finer.positions.size() - 1);
    };
    for (size_t triangle = 0; triangle < mesh.indices.size() / 3; ++triangle) {
        const uint32_t a = mesh.indices[3 * triangle], b = mesh.indices[3 * triangle + 1],
                       c = mesh.indices[3 * triangle + 2];
        const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        for (const std::array<uint32_t, 3>& corner : {std::array<uint32_t, 3>{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}) {
            finer.indices.insert(finer.indices.end(), corner.begin(), corner.end());
            finer.triangle_material.push_back(mesh.triangle_material[triangle]);
        }
    }
    return finer;
}

double medianFrameMs(Runtime& runtime, const FrameInput& input, uint32_t warm_up, uint32_t frames,
                     std::vector<uint8_t>& out) {
    for (uint32_t index = 0; index < warm_up; ++index) runtime.renderFrame(input, out.data());
    std::vector<double> times;
    for (uint32_t index = 0; index < frames; ++index) {
        const Clock::time_point start = Clock::now();
        runtime.renderFrame(input, out.data());
        times.push_back(millisecondsSince(start));
    }
    return spreadOf(times).median;
}

void runCost(Bench& bench) {
    const Settings& settings = bench.settings;
    const uint32_t width = 640, height = 360;
    const double utc = bench.bake_midnight_utc + 10.5 * 3600.0;
    // The camera frame: a flat grey with alpha 0, so the building's pixels (alpha 255) count the coverage.
    std::vector<uint8_t> camera(size_t(width) * height * 4, 128);
    for (size_t pixel = 0; pixel < size_t(width) * height; ++pixel) camera[4 * pixel + 3] = 0;
    std::vector<uint8_t> out(camera.size());
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    bench.say("");
    bench.say("**Cost (640x360, median of " + std::to_string(settings.timed_frames) + " fenced frames)**");
    Json triangles = Json::array();
    BakeSetData data = bench.bake_set;
    const uint32_t levels = settings.quick ? 2 : 3;
    for (uint32_t level = 0; level <= levels; ++level) {
        if (level > 0) data.building = subdivide(data.building);
        std::unique_ptr<Runtime> runtime = Runtime::open(*bench.context, data, bench.runtimeOptions(width, height));
        const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
        Json row{{"triangles", data.building.indices.size() / 3}};
        for (const char* name : {"direct_only", "proposed"}) {
            const FrameInput input = frameInputFor(runtimeModeNamed(name), camera, intrinsics, pose, utc, 0.0f, 1.0f);
            row[std::string(name) + "_ms"] = medianFrameMs(*runtime, input, settings.warm_up_frames,
                                                           settings.timed_frames, out);
        }
        bench.say("cost: " + std::to_string(data.building.indices.size() / 3) + " building triangles: direct-only " +
                  fixed(row["direct_only_ms"]) + " ms, proposed " + fixed(row["proposed_ms"]) + " ms");
        triangles.push_back(row);
    }
    Json coverage = Json::array();
    Runtime& runtime = bench.runtimeFor(width, height);
    const glm::dvec3 target = bench.view.look_at_enu;
    for (double distance : {80.0, 40.0, 25.0, 15.0, 9.0}) {
        const glm::dvec3 direction = glm::normalize(bench.view.position_enu - target);
        const CameraPose pose = lookAtPose(target + direction * distance, target);
        Json row{{"camera_distance_m", distance}};
        for (const char* name : {"direct_only", "proposed"}) {
            const FrameInput input = frameInputFor(runtimeModeNamed(name), camera, intrinsics, pose, utc, 0.0f, 1.0f);
            row[std::string(name) + "_ms"] = medianFrameMs(runtime, input, settings.warm_up_frames,
                                                           settings.timed_frames, out);
        }
        size_t covered = 0;
        for (size_t pixel = 0; pixel < size_t(width) * height; ++pixel) covered += out[4 * pixel + 3] == 255;
        row["building_coverage"] = double(covered) / double(width * height);
        bench.say("cost: building covers " + fixed(100.0 * double(row["building_coverage"]), 1) +
                  " % of the frame: direct-only " + fixed(row["direct_only_ms"]) + " ms, proposed " +
                  fixed(row["proposed_ms"]) + " ms");
        coverage.push_back(row);
    }
    bench.results["cost"] = {{"size", "640x360"}, {"triangles", triangles}, {"coverage", coverage}};
}

// ---------------------------------------------------------------------------------------------------------------
// Weather from the camera frame
// ---------------------------------------------------------------------------------------------------------------

// The cloud estimate on camera frames of known weather under one pair of skies. The estimate's constants were set on
// the analytic skies (weather_estimate.h), so the photographed skies are its test on skies it never saw.
Json runCloudsUnder(Bench& bench, const SkySet& skies) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.sweep_width, height = settings.sweep_height;
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    Runtime& runtime = *skies.runtime;
    const std::vector<float> candidates{0.0f, 0.5f, 1.0f};
    bench.say("");
    bench.say("**Weather from the camera frame, " + skies.label + " (" + std::to_string(width) + "x" +
              std::to_string(height) + ")**");
    bench.say("| site clock | true cover | camera response | estimate | picked | closest composite |");
    bench.say("| --- | --- | --- | --- | --- | --- |");
    Json rows = Json::array();
    size_t hits = 0, total = 0;
    double cover_error_sum = 0.0;  // |estimate - true cover|
    // The sky cue's constants were set on the 10:30 frames (weather_estimate.h): the full run measures the
    // estimate at other hours only, so none of its figures comes from the frames it was set on.
    const std::vector<double> hours = settings.quick ? std::vector<double>{10.5} : std::vector<double>{9.0, 13.5, 16.0};
    for (double hour : hours) {
        const double utc = bench.bake_midnight_utc + hour * 3600.0;
        for (float cover : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
            const ConditionFrames frames = traceCondition(*skies.renderer, bench.view, width, height, {utc, cover},
                                                          settings.sweep_samples);
            for (const CameraResponse& response : benchCameraResponses()) {
                const auto [truth, camera, mask] = respondedFrames(frames, response);
                const CloudEstimate estimate = estimateCloudCover(camera, width, height);
                // The candidate weather whose composite is closest to the truth, and the one the estimate picks.
                float best = candidates[0], picked = candidates[0];
                double best_error = 1e300;
                for (float candidate : candidates) {
                    const FrameInput input = frameInputFor(runtimeModeNamed("proposed"), camera, intrinsics, pose,
                                                           utc, candidate, frames.exposure * response.exposure_scale);
                    const double error = summariseError(steadyComposite(runtime, input), truth, mask).mean_de00;
                    if (error < best_error) best_error = error, best = candidate;
                    if (std::abs(candidate - estimate.cloud_cover) < std::abs(picked - estimate.cloud_cover))
                        picked = candidate;
                }
                hits += picked == best;
                ++total;
                cover_error_sum += std::abs(estimate.cloud_cover - cover);
                rows.push_back({{"local_time", bench.localTime(utc)}, {"true_cover", cover},
                                {"camera_response", response.name}, {"estimate", estimate.cloud_cover},
                                {"shadow_contrast", estimate.shadow_contrast},
                                {"sky_blueness", estimate.sky_blueness}, {"picked", picked},
                                {"closest_composite", best}});
                bench.say("| " + bench.localTime(utc) + " | " + fixed(cover) + " | " + response.name + " | " +
                          fixed(estimate.cloud_cover) + " | " + fixed(picked, 1) + " | " + fixed(best, 1) + " |");
            }
        }
    }
    const double cover_error = total ? cover_error_sum / double(total) : 0.0;
    bench.say("clouds, " + skies.label + ": the estimate picks the weather whose composite is closest to the truth in " +
              std::to_string(hits) + " of " + std::to_string(total) + " frames; its mean error against the true cover " +
              fixed(cover_error));
    return {{"skies", skies.label}, {"candidates", candidates}, {"rows", rows}, {"picked_closest", hits},
            {"cases", total}, {"mean_abs_cover_error", cover_error}};
}

// The site a bake set was baked from (or explicit_site) and the path tracer of it, whose cache keys cover the bake
// set's manifest and the site.json (a rebake or an edited site traces afresh).
struct SiteTruth {
    std::string site_json;
    SiteConfig site;
    std::unique_ptr<TruthRenderer> renderer;
};
SiteTruth siteTruthFor(const VulkanContext& context, const std::string& bake_set_folder,
                       const BakeSetManifest& manifest, const std::optional<std::string>& explicit_site,
                       const std::string& cache) {
    SiteTruth truth;
    truth.site_json = bench_common::siteJsonOf(bake_set_folder, manifest, explicit_site);
    truth.site = loadSiteConfig(truth.site_json);
    const std::string context_hash =
        bake::ContentHash().addFile(bake_set_folder + "/manifest.json").addFile(truth.site_json).hex();
    truth.renderer = std::make_unique<TruthRenderer>(context, truth.site, cache, context_hash);
    return truth;
}

int run(const Settings& settings) {
    const Clock::time_point start = Clock::now();
    Bench bench;
    bench.settings = settings;
    bench.bake_set = loadBakeSet(settings.bake_set);
    bench.ground_match_available = !bench.bake_set.manifest.ground_grid.albedo.empty();
    bench.bake_midnight_utc = bench_common::bakeDateMidnightUtc(settings.bake_set, bench.bake_set.manifest, "--time");
    bench.utc_offset_minutes = bench.bake_set.manifest.site.utc_offset_minutes;
    bench.context = std::make_unique<VulkanContext>(vulkanOptionsFromEnvironment());
    const HostInfo host = describeHost(bench.context->deviceDescription());
    SiteTruth truth = siteTruthFor(*bench.context, settings.bake_set, bench.bake_set.manifest, settings.site_json,
                                   settings.cache);
    const std::string& site_json = truth.site_json;
    std::filesystem::create_directories(settings.output + "/frames");
    bench.renderer = std::move(truth.renderer);

    std::time_t now = std::time(nullptr);
    char started[32];
    std::strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    bench.results["run"] = {{"mode", settings.quick ? "quick" : "full"}, {"started_utc", started},
                            {"bake_set", settings.bake_set}, {"bake_samples", bench.bake_set.manifest.settings.samples_per_texel},
                            {"site", site_json}, {"cpu", host.cpu_model}, {"logical_cpus", host.logical_cpus},
                            {"lavapipe_threads", host.lavapipe_threads}, {"device", host.device},
                            {"accuracy_size", {settings.accuracy_width, settings.accuracy_height}},
                            {"truth_samples", settings.truth_samples},
                            {"runtime", {{"msaa_samples", settings.msaa_samples},
                                         {"max_anisotropy", settings.max_anisotropy}}},
                            {"view", {{"position_enu", {bench.view.position_enu.x, bench.view.position_enu.y, bench.view.position_enu.z}},
                                      {"look_at_enu", {bench.view.look_at_enu.x, bench.view.look_at_enu.y, bench.view.look_at_enu.z}},
                                      {"horizontal_fov_deg", bench.view.horizontal_fov_deg}}}};
    bench.say("**gusuku-bench, " + std::string(settings.quick ? "quick" : "full") + " run of " + started + "**");
    bench.say("machine: " + host.cpu_model + ", " + std::to_string(host.logical_cpus) + " logical CPUs, lavapipe threads " +
              std::to_string(host.lavapipe_threads) + "; device " + host.device);
    bench.say("runtime: msaa " + std::to_string(settings.msaa_samples) + ", anisotropy " +
              fixed(settings.max_anisotropy, 0) + "; accuracy frames " + std::to_string(settings.accuracy_width) + "x" +
              std::to_string(settings.accuracy_height) + ", truth " + std::to_string(settings.truth_samples) + " spp");
    bench.say("bake set: " + settings.bake_set + " (" + std::to_string(bench.bake_set.manifest.settings.samples_per_texel) +
              " samples), building " + std::to_string(bench.bake_set.building.indices.size() / 3) + " triangles");

    if (settings.photographed_bake_set) {
        auto photographed = std::make_unique<PhotographedSkies>();
        photographed->bake_set_folder = *settings.photographed_bake_set;
        photographed->bake_set = loadBakeSet(photographed->bake_set_folder);
        SiteTruth photographed_truth = siteTruthFor(*bench.context, photographed->bake_set_folder,
                                                    photographed->bake_set.manifest, std::nullopt, settings.cache);
        const SiteConfig& photographed_site = photographed_truth.site;
        photographed->renderer = std::move(photographed_truth.renderer);
        photographed->runtime = Runtime::open(*bench.context, photographed->bake_set,
                                              bench.runtimeOptions(settings.sweep_width, settings.sweep_height));
        const auto fileName = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
        photographed->label = "photographed skies (sunny " + fileName(photographed_site.sunny_sky.path) +
                              ", overcast " +
                              (photographed_site.overcast_sky ? fileName(photographed_site.overcast_sky->path)
                                                              : std::string("none")) +
                              ")";
        bench.say("photographed skies: " + photographed->bake_set_folder + ", " + photographed->label);
        bench.photographed = std::move(photographed);
    } else {
        bench.photographed_skipped =
            "not run: no --photographed-skies bake set (scripts/bench.sh bakes one under ../shared/data/env when it "
            "is there, in its full run)";
    }

    if (settings.wantsMain()) runMain(bench);
    if (settings.wants("site")) runSiteGoals(bench);
    if (settings.wants("day")) runDay(bench);
    if (settings.wants("weather")) runUnderEachSkySet(bench, "weather", runWeatherUnder);
    if (settings.wants("cost")) runCost(bench);
    if (settings.wants("clouds")) runUnderEachSkySet(bench, "clouds", runCloudsUnder);
    if (settings.wants("field")) runUnderEachSkySet(bench, "field_light", runFieldLightUnder);

    const double seconds = millisecondsSince(start) / 1000.0;
    bench.results["run"]["seconds"] = seconds;
    bench.say("");
    bench.say("run time: " + fixed(seconds, 0) + " s");
    const std::string json = bench.results.dump(2) + "\n";
    writeBytesAtomically(settings.output + "/results.json", json.data(), json.size());
    std::string markdown;
    // Markdown joins adjacent lines into one paragraph: each line but a table row is a paragraph of its own.
    for (size_t index = 0; index < bench.summary.size(); ++index) {
        const std::string& line = bench.summary[index];
        const bool table_row = !line.empty() && line[0] == '|';
        const bool next_is_table_row = index + 1 < bench.summary.size() && !bench.summary[index + 1].empty() &&
                                       bench.summary[index + 1][0] == '|';
        markdown += line + "\n";
        if (!line.empty() && !(table_row && next_is_table_row) && !(!table_row && next_is_table_row)) markdown += "\n";
    }
    writeBytesAtomically(settings.output + "/summary.md", markdown.data(), markdown.size());
    return 0;
}

}  // namespace
}  // namespace gusuku::bench

int main(int argc, char** argv) {
    using namespace gusuku::bench;
    return gusuku::runToolMain("gusuku-bench", [&] {
        bool help = false;
        const Settings settings = parseSettings(std::vector<std::string>(argv + 1, argv + argc), help);
        if (help) {
            std::printf("%s", formatHelp(benchHelp()).c_str());
            return 0;
        }
        return run(settings);
    });
}

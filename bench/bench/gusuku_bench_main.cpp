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
//   clouds    the cloud-cover estimate from camera frames of known weather.

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
#include "camera_response.h"
#include "camera_view.h"
#include "gusuku/maths/weather_estimate.h"
#include "gusuku_bake/content_hash.h"
#include "frame_spread.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/assets/image.h"
#include "gusuku/maths/input_error.h"
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

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
using bench_common::lookAtPose;
using bench_common::Spread;
using bench_common::spreadOf;

const char* const kUsage =
    "usage: gusuku-bench BAKESET -o DIR [--quick] [options]\n"
    "\n"
    "Frame time of gusuku's runtime on this machine's Vulkan against its accuracy to a path-traced truth, for\n"
    "direct-only, the proposed method with each part on and off, and the path tracer itself; the day, the weather,\n"
    "camera responses and the cost against triangles and coverage. Writes DIR/results.json, DIR/chart.svg,\n"
    "DIR/chart.json, DIR/day.svg, DIR/summary.md and the frames it compares; prints the summary.\n"
    "\n"
    "  --quick           the short run (small frames, few samples, fewer steps): a minute or two\n"
    "  --cache DIR       path-traced frames are kept here by key (default DIR/../bench-cache)\n"
    "  --site SITE.json  the site (default: the one the bake set was baked from)\n"
    "  --only LIST       comma-separated sections to run: truth,timing,day,weather,cost,clouds (truth, the\n"
    "                    accuracy of every mode and the chart always run)\n"
    "  --photographed-skies BAKESET2\n"
    "                    the same site baked under photographed skies (scripts/bench.sh bakes one under\n"
    "                    ../shared/data/env when it is there): the weather and clouds sections run under\n"
    "                    them too, with their own path-traced truths\n"
    "\n"
    "Exit status: 0 ok, 1 bad input, 2 bad usage.\n";

struct Settings {
    std::string bake_set, output, cache;
    std::optional<std::string> site_json;
    std::optional<std::string> photographed_bake_set;
    bool quick = false;
    std::vector<std::string> only;
    // Derived from quick.
    uint32_t accuracy_width = 320, accuracy_height = 180, truth_samples = 512;
    uint32_t sweep_width = 160, sweep_height = 90, sweep_samples = 256;
    uint32_t day_step_minutes = 15;
    uint32_t timed_frames = 40, warm_up_frames = 5;
    std::vector<uint32_t> tracer_samples{1, 4, 16, 64};
    uint32_t tracer_timed_max_samples = 64;  ///< above this, the tracer's 640x360 time is scaled from it
    bool wants(const std::string& section) const {
        return only.empty() || std::find(only.begin(), only.end(), section) != only.end();
    }
};

Settings parseSettings(const std::vector<std::string>& args, bool& help) {
    Settings settings;
    CommandLine line("gusuku-bench", args);
    help = line.helpRequested();
    if (help) return settings;
    const std::optional<std::string> output = line.text("--output", "-o");
    settings.quick = line.flag("--quick");
    settings.site_json = line.text("--site");
    settings.photographed_bake_set = line.text("--photographed-skies");
    const std::optional<std::string> cache = line.text("--cache");
    if (const auto only = line.text("--only")) {
        std::stringstream stream(*only);
        for (std::string section; std::getline(stream, section, ',');) {
            static const std::vector<std::string> known{"truth", "timing", "day", "weather", "cost", "clouds"};
            if (std::find(known.begin(), known.end(), section) == known.end())
                line.failValue("--only", "'" + section + "' is not one of truth,timing,day,weather,cost,clouds");
            settings.only.push_back(section);
        }
    }
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() != 1) line.fail("needs exactly one BAKESET folder (see --help)");
    if (!output) line.fail("needs -o DIR (see --help)");
    settings.bake_set = positionals[0];
    settings.output = *output;
    settings.cache = cache.value_or((std::filesystem::path(*output).parent_path() / "bench-cache").string());
    if (settings.cache.empty() || settings.cache == "bench-cache") settings.cache = "bench-cache";
    if (settings.quick) {
        settings.accuracy_width = 160, settings.accuracy_height = 90, settings.truth_samples = 128;
        settings.sweep_width = 96, settings.sweep_height = 54, settings.sweep_samples = 64;
        settings.day_step_minutes = 120;
        settings.timed_frames = 15, settings.warm_up_frames = 3;
        settings.tracer_timed_max_samples = 4;
    }
    return settings;
}

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// JSON has no infinity: PSNR of equal frames is written as null.
Json finiteOrNull(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json errorJson(const ErrorSummary& summary) {
    return Json{{"mean_de00", summary.mean_de00}, {"p95_de00", summary.p95_de00},
                {"psnr_db", finiteOrNull(summary.psnr_db)}, {"pixels", summary.pixel_count}};
}

std::string fixed(double value, int digits = 2) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// Error of a frame against the truth over the changed pixels and the whole frame.
struct RegionErrors {
    ErrorSummary changed, whole;
};
RegionErrors regionErrors(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                          const std::vector<uint8_t>& mask) {
    return {summariseError(frame, truth, mask), summariseError(frame, truth)};
}
Json regionJson(const RegionErrors& errors) {
    return Json{{"building_and_shadow", errorJson(errors.changed)}, {"whole_frame", errorJson(errors.whole)}};
}

// Everything one condition (view, instant, weather) needs for accuracy: the linear truth and camera frames.
struct ConditionFrames {
    ImageRGBA truth, camera;  // with and without the building, same seed
    float exposure = 1.0f;    // the camera's auto exposure (middle grey of the camera frame)
    double trace_seconds = 0.0;
};

ConditionFrames traceCondition(TruthRenderer& renderer, const BenchView& view, uint32_t width, uint32_t height,
                               const BenchCondition& condition, uint32_t samples) {
    TracedFrameRequest request;
    request.view = view;
    request.width = width;
    request.height = height;
    request.condition = condition;
    request.samples_per_pixel = samples;
    request.seed = 1;
    request.include_building = true;
    ConditionFrames frames;
    TracedFrame truth = renderer.render(request);
    request.include_building = false;
    TracedFrame camera = renderer.render(request);
    frames.trace_seconds = truth.trace_seconds + camera.trace_seconds;
    frames.truth = std::move(truth.linear);
    frames.camera = std::move(camera.linear);
    frames.exposure = bake::middleGreyExposure(frames.camera);
    return frames;
}

// One pair of skies the weather sections run under: the path tracer of the site under them and the runtime with
// the bake set baked under them, at the sweep size.
struct SkySet {
    std::string label;
    TruthRenderer* renderer = nullptr;
    Runtime* runtime = nullptr;
    bool has_ground_albedo = false;  ///< its bake set can run the ground match
};

// The same site baked under the photographed skies of ../shared/data/env (--photographed-skies).
struct PhotographedSkies {
    std::string bake_set_folder;
    BakeSetData bake_set;
    std::unique_ptr<TruthRenderer> renderer;
    std::unique_ptr<Runtime> runtime;
    std::string label;
};

struct Bench {
    Settings settings;
    BakeSetData bake_set;
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<TruthRenderer> renderer;
    BenchView view;
    double bake_midnight_utc = 0.0;
    int utc_offset_minutes = 0;
    Json results;
    std::vector<std::string> summary;  // markdown lines
    std::map<std::string, std::unique_ptr<Runtime>> runtimes;  // by "WxH"
    bool ground_match_available = false;  // the bake set has ground albedo (manifest ground_grid.albedo)
    std::unique_ptr<PhotographedSkies> photographed;           // null: not given (photographed_skipped says why)
    std::string photographed_skipped;

    SkySet analyticSkies() {
        return {"the sample's analytic skies", renderer.get(), &runtimeFor(settings.sweep_width, settings.sweep_height),
                ground_match_available};
    }
    SkySet photographedSkies() {
        return {photographed->label, photographed->renderer.get(), photographed->runtime.get(),
                !photographed->bake_set.manifest.ground_grid.albedo.empty()};
    }

    void say(const std::string& line) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
        summary.push_back(line);
    }
    void note(const std::string& line) {
        std::fprintf(stderr, "gusuku-bench: %s\n", line.c_str());
    }
    Runtime& runtimeFor(uint32_t width, uint32_t height) {
        const std::string key = std::to_string(width) + "x" + std::to_string(height);
        auto& runtime = runtimes[key];
        if (!runtime) {
            RuntimeOptions options;
            options.frame_width = width;
            options.frame_height = height;
            runtime = Runtime::open(*context, bake_set, options);
        }
        return *runtime;
    }
    std::string localTime(double utc) const { return formatIso8601(utc, utc_offset_minutes).substr(11, 5); }
    void writePng(const std::string& name, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
        writePngRgba8(settings.output + "/frames/" + name, int(width), int(height), rgba8);
    }
};

// ---------------------------------------------------------------------------------------------------------------
// Truth, accuracy, timing, chart
// ---------------------------------------------------------------------------------------------------------------

struct ModePoint {
    std::string name;
    std::string kind;  // "runtime", "tracer_raw", "tracer_denoised"
    RegionErrors errors;
    double frame_ms_640 = 0.0;  // the chart's x
    std::string time_source;
};

void runMain(Bench& bench) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.accuracy_width, height = settings.accuracy_height;
    const BenchCondition condition{bench.bake_midnight_utc + 10.5 * 3600.0, 0.0f};
    const CameraResponse response = benchCameraResponses()[0];
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    bench.say("**Truth**");
    const Clock::time_point start = Clock::now();
    const ConditionFrames frames = traceCondition(*bench.renderer, bench.view, width, height, condition,
                                                  settings.truth_samples);
    // A second seed: the noise left in the truth.
    TracedFrameRequest second;
    second.view = bench.view;
    second.width = width;
    second.height = height;
    second.condition = condition;
    second.samples_per_pixel = settings.truth_samples;
    second.seed = 2;
    second.include_building = true;
    const ImageRGBA truth_seed2 = bench.renderer->render(second).linear;
    const std::vector<uint8_t> truth = applyCameraResponse(frames.truth, frames.exposure, response);
    const std::vector<uint8_t> camera = applyCameraResponse(frames.camera, frames.exposure, response);
    const std::vector<uint8_t> truth2 = applyCameraResponse(truth_seed2, frames.exposure, response);
    const std::vector<uint8_t> mask = changedPixelMask(truth, camera);
    const RegionErrors noise = regionErrors(truth2, truth, mask);
    bench.writePng("truth.png", width, height, truth);
    bench.writePng("camera.png", width, height, camera);
    size_t changed = 0;
    for (uint8_t in : mask) changed += in;
    std::vector<uint8_t> mask_image(mask.size() * 4, 255);
    for (size_t i = 0; i < mask.size(); ++i) mask_image[4 * i] = mask_image[4 * i + 1] = mask_image[4 * i + 2] = mask[i] ? 255 : 0;
    bench.writePng("mask.png", width, height, mask_image);
    bench.results["truth"] = {
        {"size", std::to_string(width) + "x" + std::to_string(height)},
        {"samples_per_pixel", settings.truth_samples},
        {"local_time", bench.localTime(condition.utc_seconds)},
        {"cloud_cover", condition.cloud_cover},
        {"camera_response", response.name},
        {"exposure", frames.exposure},
        {"changed_pixels", changed},
        {"noise_between_seeds", regionJson(noise)},
        {"seconds", millisecondsSince(start) / 1000.0}};
    bench.say("truth: " + std::to_string(width) + "x" + std::to_string(height) + ", " +
              std::to_string(settings.truth_samples) + " spp, sunny " + bench.localTime(condition.utc_seconds) +
              " site clock; building and shadow " + std::to_string(changed) + " px (" +
              fixed(100.0 * double(changed) / double(mask.size()), 1) + " %)");
    bench.say("truth noise (seed 1 vs seed 2): building+shadow mean " + fixed(noise.changed.mean_de00) + " p95 " +
              fixed(noise.changed.p95_de00) + " dE00, whole frame mean " + fixed(noise.whole.mean_de00) +
              " p95 " + fixed(noise.whole.p95_de00));

    // Accuracy of the runtime's modes.
    std::vector<ModePoint> points;
    Runtime& runtime = bench.runtimeFor(width, height);
    for (const RuntimeMode& mode : benchRuntimeModes(bench.ground_match_available)) {
        const FrameInput input = frameInputFor(mode, camera, intrinsics, pose, condition.utc_seconds,
                                               condition.cloud_cover, frames.exposure * response.exposure_scale);
        const std::vector<uint8_t> composite = steadyComposite(runtime, input);
        bench.writePng(mode.name + ".png", width, height, composite);
        points.push_back({mode.name, "runtime", regionErrors(composite, truth, mask), 0.0, "measured"});
    }
    // Accuracy of the path tracer (another seed than the truth's).
    std::map<uint32_t, double> tracer_seconds_small;  // raw, at the accuracy size
    std::map<uint32_t, double> denoise_seconds_small;
    for (uint32_t samples : settings.tracer_samples) {
        TracedFrameRequest request = second;
        request.samples_per_pixel = samples;
        request.seed = 3;
        request.denoise = true;
        const TracedFrame traced = bench.renderer->render(request, /*use_cache=*/false);
        tracer_seconds_small[samples] = traced.trace_seconds;
        denoise_seconds_small[samples] = traced.denoise_seconds;
        const std::vector<uint8_t> raw = applyCameraResponse(traced.linear, frames.exposure, response);
        const std::vector<uint8_t> denoised = applyCameraResponse(traced.denoised, frames.exposure, response);
        bench.writePng("tracer_" + std::to_string(samples) + "spp_raw.png", width, height, raw);
        bench.writePng("tracer_" + std::to_string(samples) + "spp_denoised.png", width, height, denoised);
        points.push_back({"tracer_" + std::to_string(samples) + "spp_raw", "tracer_raw",
                          regionErrors(raw, truth, mask), 0.0, ""});
        points.push_back({"tracer_" + std::to_string(samples) + "spp_denoised", "tracer_denoised",
                          regionErrors(denoised, truth, mask), 0.0, ""});
    }

    // Frame time of the runtime's modes: 1280x720 and 640x360, modes interleaved frame by frame.
    Json timing;
    std::map<std::string, double> median_640;
    for (const auto& [timing_width, timing_height] : std::vector<std::pair<uint32_t, uint32_t>>{{1280, 720}, {640, 360}}) {
        const std::string size = std::to_string(timing_width) + "x" + std::to_string(timing_height);
        const std::vector<uint8_t> big_camera = resizeNearest(camera, width, height, timing_width, timing_height);
        const CameraIntrinsics big = CameraIntrinsics::fromFieldOfView(timing_width, timing_height, bench.view.horizontal_fov_deg);
        Runtime& timed = bench.runtimeFor(timing_width, timing_height);
        std::vector<FrameInput> inputs;
        std::vector<RuntimeMode> modes = benchRuntimeModes(bench.ground_match_available);
        for (const RuntimeMode& mode : modes)
            inputs.push_back(frameInputFor(mode, big_camera, big, pose, condition.utc_seconds, condition.cloud_cover,
                                           frames.exposure * response.exposure_scale));
        std::vector<uint8_t> out(size_t(timing_width) * timing_height * 4);
        for (uint32_t frame = 0; frame < settings.warm_up_frames; ++frame)
            for (const FrameInput& input : inputs) timed.renderFrame(input, out.data());
        std::vector<std::vector<double>> times(modes.size());
        for (uint32_t frame = 0; frame < settings.timed_frames; ++frame)
            for (size_t index = 0; index < modes.size(); ++index) {
                const Clock::time_point frame_start = Clock::now();
                timed.renderFrame(inputs[index], out.data());
                times[index].push_back(millisecondsSince(frame_start));
            }
        Json per_mode;
        const double direct_ms = spreadOf(times[0]).median;
        std::string line = "frame " + size + " (median [p10, p90] of " + std::to_string(settings.timed_frames) +
                           " fenced frames):";
        for (size_t index = 0; index < modes.size(); ++index) {
            const Spread spread = spreadOf(times[index]);
            per_mode[modes[index].name] = {{"median_ms", spread.median}, {"p10_ms", spread.low},
                                           {"p90_ms", spread.high}, {"over_direct_only", spread.median / direct_ms}};
            if (timing_width == 640) median_640[modes[index].name] = spread.median;
            line += " " + modes[index].name + " " + fixed(spread.median) + " [" + fixed(spread.low) + ", " +
                    fixed(spread.high) + "]";
        }
        bench.say(line);
        // The per-pass profile (each pass submitted alone; shadow maps redrawn every profiled frame, as when
        // the sun moves a step).
        Json profile;
        for (size_t index : {size_t(0), size_t(1)}) {
            std::vector<PassTimings> passes(std::max(5u, settings.timed_frames / 2));
            for (PassTimings& pass : passes) {
                timed.invalidateShadowMaps();
                timed.renderFrameProfiled(inputs[index], out.data(), pass);
            }
            auto median = [&](double PassTimings::*field) {
                std::vector<double> values;
                for (const PassTimings& pass : passes) values.push_back(pass.*field);
                return spreadOf(values).median;
            };
            profile[modes[index].name] = {{"upload_ms", median(&PassTimings::upload_ms)},
                                          {"shadow_ms", median(&PassTimings::shadow_ms)},
                                          {"occluder_ms", median(&PassTimings::occluder_ms)},
                                          {"building_ms", median(&PassTimings::building_ms)},
                                          {"ground_ms", median(&PassTimings::ground_ms)},
                                          {"statistics_ms", median(&PassTimings::statistics_ms)},
                                          {"readback_ms", median(&PassTimings::readback_ms)},
                                          {"total_ms", median(&PassTimings::total_ms)}};
        }
        bench.say("passes " + size + " proposed (profiling mode, ms): upload " +
                  fixed(profile["proposed"]["upload_ms"]) + ", shadow " + fixed(profile["proposed"]["shadow_ms"]) +
                  ", occluder " + fixed(profile["proposed"]["occluder_ms"]) + ", building " +
                  fixed(profile["proposed"]["building_ms"]) + ", ground " + fixed(profile["proposed"]["ground_ms"]) +
                  ", statistics " + fixed(profile["proposed"]["statistics_ms"]) + ", readback " +
                  fixed(profile["proposed"]["readback_ms"]));
        timing[size] = {{"modes", per_mode}, {"passes", profile}};
    }
    // The path tracer's frame at 640x360: traced and timed up to tracer_timed_max_samples; above, the
    // per-sample time of the largest timed count scaled (the tracer's cost is linear in samples).
    Json tracer_timing;
    {
        TracedFrameRequest request = second;
        request.width = 640;
        request.height = 360;
        request.seed = 4;
        request.denoise = true;
        double per_sample_ms = 0.0, fixed_ms = 0.0, denoise_ms = 0.0;
        for (uint32_t samples : settings.tracer_samples) {
            double trace_ms = 0.0;
            std::string source = "measured";
            if (samples <= settings.tracer_timed_max_samples) {
                request.samples_per_pixel = samples;
                const TracedFrame traced = bench.renderer->render(request, /*use_cache=*/false);
                trace_ms = traced.trace_seconds * 1000.0;
                denoise_ms = traced.denoise_seconds * 1000.0;
                if (samples == 1) fixed_ms = trace_ms;
                per_sample_ms = samples > 1 ? (trace_ms - fixed_ms) / double(samples - 1) : trace_ms;
            } else {
                trace_ms = fixed_ms + per_sample_ms * double(samples - 1);
                source = "scaled from the timed sample counts (linear in samples)";
            }
            for (ModePoint& point : points) {
                if (point.name == "tracer_" + std::to_string(samples) + "spp_raw") {
                    point.frame_ms_640 = trace_ms;
                    point.time_source = source;
                }
                if (point.name == "tracer_" + std::to_string(samples) + "spp_denoised") {
                    point.frame_ms_640 = trace_ms + denoise_ms;
                    point.time_source = source;
                }
            }
            tracer_timing[std::to_string(samples) + "spp"] = {{"raw_ms", trace_ms}, {"denoised_ms", trace_ms + denoise_ms},
                                                             {"source", source}};
        }
    }
    timing["640x360"]["tracer"] = tracer_timing;
    for (ModePoint& point : points)
        if (point.kind == "runtime") point.frame_ms_640 = median_640[point.name];
    bench.results["timing"] = timing;

    // Accuracy table.
    Json accuracy;
    bench.say("");
    bench.say("| mode | frame 640x360 ms | building+shadow mean / p95 dE00 | PSNR dB | whole frame mean / p95 dE00 | PSNR dB |");
    bench.say("| --- | --- | --- | --- | --- | --- |");
    for (const ModePoint& point : points) {
        accuracy[point.name] = regionJson(point.errors);
        accuracy[point.name]["frame_ms_640x360"] = point.frame_ms_640;
        accuracy[point.name]["frame_time_source"] = point.time_source;
        bench.say("| " + point.name + " | " + fixed(point.frame_ms_640, 1) + " | " + fixed(point.errors.changed.mean_de00) +
                  " / " + fixed(point.errors.changed.p95_de00) + " | " + fixed(point.errors.changed.psnr_db, 1) +
                  " | " + fixed(point.errors.whole.mean_de00) + " / " + fixed(point.errors.whole.p95_de00) + " | " +
                  fixed(point.errors.whole.psnr_db, 1) + " |");
    }
    bench.results["accuracy"] = accuracy;

    // Goals.
    auto find = [&](const std::string& name) -> const ModePoint& {
        for (const ModePoint& point : points)
            if (point.name == name) return point;
        throw std::logic_error(name);
    };
    const ModePoint& direct = find("direct_only");
    const ModePoint& proposed = find("proposed");
    const double time_ratio_720 = double(timing["1280x720"]["modes"]["proposed"]["over_direct_only"]);
    const double time_ratio_360 = double(timing["640x360"]["modes"]["proposed"]["over_direct_only"]);
    const double error_ratio = proposed.errors.changed.mean_de00 / direct.errors.changed.mean_de00;
    // The tracer's cheapest mode that reaches the proposed method's error (over the building and shadow).
    std::optional<const ModePoint*> reaching;
    double slowest_tracer_ms = 0.0;
    for (const ModePoint& point : points)
        if (point.kind != "runtime") {
            slowest_tracer_ms = std::max(slowest_tracer_ms, point.frame_ms_640);
            if (point.errors.changed.mean_de00 <= proposed.errors.changed.mean_de00 &&
                (!reaching || point.frame_ms_640 < (*reaching)->frame_ms_640))
                reaching = &point;
        }
    const double tracer_ratio = (reaching ? (*reaching)->frame_ms_640 : slowest_tracer_ms) / proposed.frame_ms_640;
    Json goals;
    goals["frame_time_over_direct_only"] = {{"1280x720", time_ratio_720}, {"640x360", time_ratio_360},
                                            {"goal", 1.05}, {"limit", 1.10},
                                            {"held_1280x720", time_ratio_720 <= 1.10},
                                            {"held_640x360", time_ratio_360 <= 1.10}};
    goals["error_over_direct_only"] = {{"ratio", error_ratio}, {"goal_below", 1.0 / 3.0},
                                       {"held", error_ratio < 1.0 / 3.0}};
    goals["tracer_time_to_reach_proposed_error"] = {
        {"reached_by", reaching ? Json((*reaching)->name) : Json(nullptr)},
        {"ratio_over_proposed", tracer_ratio},
        {"is_lower_bound", !reaching},
        {"goal_at_least", 100.0},
        {"held", tracer_ratio >= 100.0}};
    bench.results["goals"] = goals;
    bench.say("");
    bench.say("goal: proposed frame time over direct-only " + fixed(time_ratio_720, 3) + " at 1280x720, " +
              fixed(time_ratio_360, 3) + " at 640x360 (limit 1.10, goal 1.05): " +
              (time_ratio_720 <= 1.10 && time_ratio_360 <= 1.10 ? "held" : "NOT held"));
    bench.say("goal: proposed error over direct-only (building+shadow mean dE00) " + fixed(error_ratio, 3) +
              " (below 0.333): " + (error_ratio < 1.0 / 3.0 ? "held" : "NOT held"));
    bench.say("goal: path tracer time to reach the proposed error over the proposed time " +
              (reaching ? fixed(tracer_ratio, 0) + "x (" + (*reaching)->name + ")"
                        : "> " + fixed(tracer_ratio, 0) + "x (no tracer mode reached it)") +
              " (at least 100x): " + (tracer_ratio >= 100.0 ? "held" : "NOT held"));

    // The chart.
    Chart chart;
    chart.title = "gusuku: error against frame time (" + std::to_string(width) + "x" + std::to_string(height) +
                  " accuracy, 640x360 time, sunny " + bench.localTime(condition.utc_seconds) + ")";
    chart.x_label = "frame time at 640x360, ms (log scale; lavapipe)";
    chart.y_label = "mean CIEDE2000 over the building and its shadow";
    chart.log_x = true;
    ChartSeries runtime_series{"runtime modes", "#1f77b4", {}, false};
    ChartSeries direct_series{"direct-only", "#d62728", {}, false};
    ChartSeries raw_series{"path tracer, raw", "#7f7f7f", {}, true};
    ChartSeries denoised_series{"path tracer, denoised", "#2ca02c", {}, true};
    Json chart_json = Json::array();
    for (const ModePoint& point : points) {
        const ChartPoint chart_point{point.frame_ms_640, point.errors.changed.mean_de00,
                                     point.kind == "runtime" ? point.name : point.name.substr(7, point.name.find('_', 7) - 7)};
        if (point.name == "direct_only") direct_series.points.push_back(chart_point);
        else if (point.kind == "runtime") runtime_series.points.push_back(chart_point);
        else if (point.kind == "tracer_raw") raw_series.points.push_back(chart_point);
        else denoised_series.points.push_back(chart_point);
        chart_json.push_back({{"mode", point.name}, {"frame_ms_640x360", point.frame_ms_640},
                              {"mean_de00_building_and_shadow", point.errors.changed.mean_de00},
                              {"p95_de00_building_and_shadow", point.errors.changed.p95_de00},
                              {"mean_de00_whole_frame", point.errors.whole.mean_de00}});
    }
    chart.series = {direct_series, runtime_series, raw_series, denoised_series};
    chart.references.push_back({direct.errors.changed.mean_de00 / 3.0, "goal: a third of direct-only's error", false, "#d62728"});
    chart.references.push_back({direct.frame_ms_640 * 1.10, "1.10x direct-only's time", true, "#d62728"});
    chart.references.push_back({proposed.frame_ms_640 * 100.0, "100x the proposed time", true, "#1f77b4"});
    chart.references.push_back({noise.changed.mean_de00, "truth noise (two seeds)", false, "#999999"});
    writeBytesAtomically(settings.output + "/chart.svg", renderSvgChart(chart).data(), renderSvgChart(chart).size());
    const std::string chart_text = Json{{"points", chart_json}, {"goals", goals}}.dump(2) + "\n";
    writeBytesAtomically(settings.output + "/chart.json", chart_text.data(), chart_text.size());
}

// ---------------------------------------------------------------------------------------------------------------
// Where it fails: the day, the weather and camera responses
// ---------------------------------------------------------------------------------------------------------------

double sunElevationAt(const Bench& bench, double utc) {
    SunObserver observer;
    observer.latitude_deg = bench.bake_set.manifest.site.latitude_deg;
    observer.longitude_deg = bench.bake_set.manifest.site.longitude_deg;
    observer.height_m = bench.bake_set.manifest.site.height_m;
    return computeSunPosition(observer, utc).apparent_elevation_deg;
}

// The instant the sun's apparent elevation crosses 0 between two instants (bisection, to a second).
double horizonCrossing(const Bench& bench, double below_or_above, double other) {
    const bool rising = sunElevationAt(bench, below_or_above) < 0.0;
    double a = below_or_above, b = other;
    while (std::abs(b - a) > 1.0) {
        const double middle = 0.5 * (a + b);
        if ((sunElevationAt(bench, middle) < 0.0) == rising) a = middle;
        else b = middle;
    }
    return 0.5 * (a + b);
}

void runDay(Bench& bench) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.sweep_width, height = settings.sweep_height;
    const double noon = bench.bake_midnight_utc + 12 * 3600.0;
    const double sunrise = horizonCrossing(bench, bench.bake_midnight_utc, noon);
    const double sunset = horizonCrossing(bench, bench.bake_midnight_utc + 24 * 3600.0, noon);
    const CameraResponse response = benchCameraResponses()[0];
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    Runtime& runtime = bench.runtimeFor(width, height);
    bench.say("");
    bench.say("**The day (" + std::to_string(width) + "x" + std::to_string(height) + ", truth " +
              std::to_string(settings.sweep_samples) + " spp, sunrise " + bench.localTime(sunrise) + ", sunset " +
              bench.localTime(sunset) + ", every " + std::to_string(settings.day_step_minutes) + " min)**");
    bench.say("mean dE00 over the building and shadow; the proposed method without its colour match unless named");
    // The match column: the ground match where the bake set has ground albedo, else the seed paper's Lab match.
    const std::string match_mode = bench.ground_match_available ? "proposed_ground_match" : "proposed_preserve_match";
    bench.say("| site clock | sun elevation | blend of two | nearest slot | blend, " +
              std::string(bench.ground_match_available ? "ground match" : "preserve match") + " | direct-only |");
    bench.say("| --- | --- | --- | --- | --- | --- |");
    Json steps = Json::array();
    ChartSeries blend{"blend of two slots (match off)", "#1f77b4", {}, true};
    ChartSeries nearest{"nearest slot (match off)", "#ff7f0e", {}, true};
    ChartSeries direct{"direct-only", "#d62728", {}, true};
    std::vector<std::pair<double, double>> blend_errors;  // (hour, error)
    for (double utc = sunrise + 3600.0; utc <= sunset - 3600.0 + 1.0; utc += settings.day_step_minutes * 60.0) {
        const ConditionFrames frames = traceCondition(*bench.renderer, bench.view, width, height, {utc, 0.0f},
                                                      settings.sweep_samples);
        const std::vector<uint8_t> truth = applyCameraResponse(frames.truth, frames.exposure, response);
        const std::vector<uint8_t> camera = applyCameraResponse(frames.camera, frames.exposure, response);
        const std::vector<uint8_t> mask = changedPixelMask(truth, camera);
        // The slot choice is measured with the colour match off (a neutral camera leaves it nothing to undo, and
        // on the sample it is the larger error: see the accuracy table); the match-on blend is shown beside it.
        auto errorOf = [&](RuntimeMode mode) {
            const FrameInput input = frameInputFor(mode, camera, intrinsics, pose, utc, 0.0f, frames.exposure);
            return summariseError(steadyComposite(runtime, input), truth, mask);
        };
        RuntimeMode nearest_mode = runtimeModeNamed("proposed");
        nearest_mode.blend_slots = false;
        const ErrorSummary with_blend = errorOf(runtimeModeNamed("proposed")),
                           without_blend = errorOf(nearest_mode),
                           matched = errorOf(runtimeModeNamed(match_mode)),
                           direct_only = errorOf(runtimeModeNamed("direct_only"));
        const double hour = (utc - bench.bake_midnight_utc) / 3600.0;
        const double elevation = sunElevationAt(bench, utc);
        steps.push_back({{"local_time", bench.localTime(utc)}, {"sun_elevation_deg", elevation},
                         {"blend", errorJson(with_blend)}, {"nearest_slot", errorJson(without_blend)},
                         {"blend_colour_match", errorJson(matched)}, {"colour_match_mode", match_mode},
                         {"direct_only", errorJson(direct_only)}});
        blend.points.push_back({hour, with_blend.mean_de00, ""});
        nearest.points.push_back({hour, without_blend.mean_de00, ""});
        direct.points.push_back({hour, direct_only.mean_de00, ""});
        blend_errors.push_back({hour, with_blend.mean_de00});
        bench.say("| " + bench.localTime(utc) + " | " + fixed(elevation, 1) + " | " + fixed(with_blend.mean_de00) +
                  " | " + fixed(without_blend.mean_de00) + " | " + fixed(matched.mean_de00) + " | " +
                  fixed(direct_only.mean_de00) + " |");
    }
    // Where the blend's error passes 2 and 5: the steps above, as runs of consecutive steps in site clock time.
    Json findings;
    for (double threshold : {2.0, 5.0}) {
        std::vector<std::string> hours;
        std::string runs;
        size_t above = 0;
        for (size_t step = 0; step < blend_errors.size(); ++step) {
            if (blend_errors[step].second <= threshold) continue;
            hours.push_back(fixed(blend_errors[step].first, 2));
            ++above;
            const bool starts_run = step == 0 || blend_errors[step - 1].second <= threshold;
            const bool ends_run = step + 1 == blend_errors.size() || blend_errors[step + 1].second <= threshold;
            const std::string clock = bench.localTime(bench.bake_midnight_utc + blend_errors[step].first * 3600.0);
            if (starts_run) runs += (runs.empty() ? "" : ", ") + clock;
            if (ends_run && !starts_run) runs += " to " + clock;
        }
        findings["blend_above_" + fixed(threshold, 0) + "_de00_hours"] = hours;
        bench.say("day: blend error above " + fixed(threshold, 0) + " dE00 at " +
                  (above == 0 ? std::string("no step")
                              : std::to_string(above) + " of " + std::to_string(blend_errors.size()) + " steps: " + runs));
    }
    // Why: the error at the slots' own times (where neither the blend nor the nearest slot interpolates anything,
    // so what is left is the method's error at a baked instant), against the steps between slots; and the truth's
    // own noise at these settings (a second seed at the step nearest noon), below which no error is measurable.
    // The step nearest each sunny slot's time stands for that slot.
    std::vector<bool> at_slot(blend_errors.size(), false);
    for (const BakeSetSlot& slot : bench.bake_set.manifest.slots) {
        if (slot.utc.empty() || blend_errors.empty()) continue;
        const double slot_hour = (parseIso8601Utc(slot.utc) - bench.bake_midnight_utc) / 3600.0;
        size_t nearest_step = 0;
        for (size_t step = 1; step < blend_errors.size(); ++step)
            if (std::abs(blend_errors[step].first - slot_hour) < std::abs(blend_errors[nearest_step].first - slot_hour))
                nearest_step = step;
        at_slot[nearest_step] = true;
    }
    double at_slots_sum = 0.0, between_max = 0.0;
    size_t at_slots_count = 0;
    for (size_t step = 0; step < blend_errors.size(); ++step) {
        if (at_slot[step]) at_slots_sum += blend_errors[step].second, ++at_slots_count;
        else between_max = std::max(between_max, blend_errors[step].second);
    }
    double noise = 0.0;
    if (!blend_errors.empty()) {
        double noon_hour = blend_errors.front().first;
        for (const auto& step : blend_errors)
            if (std::abs(step.first - 12.0) < std::abs(noon_hour - 12.0)) noon_hour = step.first;
        TracedFrameRequest request;
        request.view = bench.view;
        request.width = width;
        request.height = height;
        request.condition = {bench.bake_midnight_utc + noon_hour * 3600.0, 0.0f};
        request.samples_per_pixel = settings.sweep_samples;
        request.include_building = true;
        request.seed = 1;
        const ImageRGBA first = bench.renderer->render(request).linear;
        request.seed = 2;
        const ImageRGBA second = bench.renderer->render(request).linear;
        request.include_building = false;
        request.seed = 1;
        const ImageRGBA camera_frame = bench.renderer->render(request).linear;
        const float exposure = bake::middleGreyExposure(camera_frame);
        const std::vector<uint8_t> truth1 = applyCameraResponse(first, exposure, response);
        noise = summariseError(applyCameraResponse(second, exposure, response), truth1,
                               changedPixelMask(truth1, applyCameraResponse(camera_frame, exposure, response)))
                    .mean_de00;
    }
    const double at_slots = at_slots_count ? at_slots_sum / double(at_slots_count) : 0.0;
    findings["blend_at_slot_times_mean_de00"] = at_slots;
    findings["blend_between_slots_max_de00"] = between_max;
    findings["truth_noise_de00"] = noise;
    bench.say("day, why: at the slots' own times (" + std::to_string(at_slots_count) +
              " steps, the nearest to each; nothing interpolated there) the blend's error is " + fixed(at_slots) +
              " dE00 on average, between them at most " + fixed(between_max) +
              "; the truth's own noise at these settings is " + fixed(noise) +
              " (seed 1 against seed 2 at the step nearest noon). An error at the slot times above the noise is the "
              "method's at a baked instant (the lightmap's texels, the shadow map against the sun's disc, the ground "
              "ratio's cells), not the slot choice; the part above it between slots is the interpolation's.");
    bench.results["day"] = {{"size", std::to_string(width) + "x" + std::to_string(height)},
                            {"truth_samples", settings.sweep_samples}, {"sunrise", bench.localTime(sunrise)},
                            {"sunset", bench.localTime(sunset)}, {"steps", steps}, {"findings", findings}};
    Chart chart;
    chart.title = "gusuku: error through the day (mean CIEDE2000 over the building and shadow)";
    chart.x_label = "hour, site clock";
    chart.y_label = "mean CIEDE2000";
    chart.series = {blend, nearest, direct};
    chart.references.push_back({2.0, "2 dE00", false, "#999999"});
    chart.references.push_back({5.0, "5 dE00", false, "#999999"});
    for (const BakeSetSlot& slot : bench.bake_set.manifest.slots)
        if (!slot.utc.empty())
            chart.references.push_back({(parseIso8601Utc(slot.utc) - bench.bake_midnight_utc) / 3600.0,
                                        "slot " + slot.name, true, "#2ca02c"});
    const std::string svg = renderSvgChart(chart);
    writeBytesAtomically(bench.settings.output + "/day.svg", svg.data(), svg.size());
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
            const std::vector<uint8_t> truth = applyCameraResponse(frames.truth, frames.exposure, response);
            const std::vector<uint8_t> camera = applyCameraResponse(frames.camera, frames.exposure, response);
            const std::vector<uint8_t> mask = changedPixelMask(truth, camera);
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
        RuntimeOptions options;
        options.frame_width = width;
        options.frame_height = height;
        std::unique_ptr<Runtime> runtime = Runtime::open(*bench.context, data, options);
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
                const std::vector<uint8_t> truth = applyCameraResponse(frames.truth, frames.exposure, response);
                const std::vector<uint8_t> camera = applyCameraResponse(frames.camera, frames.exposure, response);
                const std::vector<uint8_t> mask = changedPixelMask(truth, camera);
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
                            {"view", {{"position_enu", {bench.view.position_enu.x, bench.view.position_enu.y, bench.view.position_enu.z}},
                                      {"look_at_enu", {bench.view.look_at_enu.x, bench.view.look_at_enu.y, bench.view.look_at_enu.z}},
                                      {"horizontal_fov_deg", bench.view.horizontal_fov_deg}}}};
    bench.say("**gusuku-bench, " + std::string(settings.quick ? "quick" : "full") + " run of " + started + "**");
    bench.say("machine: " + host.cpu_model + ", " + std::to_string(host.logical_cpus) + " logical CPUs, lavapipe threads " +
              std::to_string(host.lavapipe_threads) + "; device " + host.device);
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
        RuntimeOptions options;
        options.frame_width = settings.sweep_width;
        options.frame_height = settings.sweep_height;
        photographed->runtime = Runtime::open(*bench.context, photographed->bake_set, options);
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

    runMain(bench);
    if (settings.wants("day")) runDay(bench);
    if (settings.wants("weather")) runUnderEachSkySet(bench, "weather", runWeatherUnder);
    if (settings.wants("cost")) runCost(bench);
    if (settings.wants("clouds")) runUnderEachSkySet(bench, "clouds", runCloudsUnder);

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
            std::printf("%s", kUsage);
            return 0;
        }
        return run(settings);
    });
}

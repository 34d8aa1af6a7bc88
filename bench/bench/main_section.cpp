// The bench's main section (runMain), always run: the truth at the accuracy size and its noise between two seeds,
// every runtime mode's and the path tracer's error against it, the frame times of both, the goals, and the chart
// of error against frame time.
#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_run.h"
#include "camera_response.h"
#include "gusuku/assets/atomic_file.h"
#include "runtime_modes.h"
#include "svg_chart.h"

namespace gusuku::bench {
namespace {

struct ModePoint {
    std::string name;
    std::string kind;  // "runtime", "tracer_raw", "tracer_denoised"
    RegionErrors errors;
    double frame_ms_640 = 0.0;  // the chart's x
    std::string time_source;
    // The runtime modes' error with both images 3 x 3 low-passed in linear light (image_metrics.h): the light's
    // error without the per-pixel part; the goal is read on it too, with the truth's noise taken out.
    std::optional<RegionErrors> light;
};

// What the main section measures against: the truth, the camera frame and the pixels the building changes,
// through the camera response; the truth's noise (seed 2 against seed 1).
struct MainTruth {
    ConditionFrames frames;
    TracedFrameRequest seed2_request;  // the truth's request with seed 2: the path tracer's modes start from it
    std::vector<uint8_t> truth, camera, mask;
    RegionErrors noise;
    std::vector<uint8_t> truth_low_passed;  // the truth 3 x 3 low-passed in linear light
    RegionErrors noise_low_passed;           // seed 2 against seed 1, both low-passed
};

// The truth, its camera frame and its second seed, written as frames and as results["truth"].
MainTruth traceMainTruth(Bench& bench, const BenchCondition& condition, const CameraResponse& response) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.accuracy_width, height = settings.accuracy_height;
    bench.say("**Truth**");
    const Clock::time_point start = Clock::now();
    MainTruth main;
    main.frames = traceCondition(*bench.renderer, bench.view, width, height, condition, settings.truth_samples);
    // A second seed: the noise left in the truth.
    main.seed2_request = truthRequest(bench.view, width, height, condition, settings.truth_samples, 2);
    const ImageRGBA truth_seed2 = bench.renderer->render(main.seed2_request).linear;
    const ConditionFrames& frames = main.frames;
    main.truth = applyCameraResponse(frames.truth, frames.exposure, response);
    main.camera = applyCameraResponse(frames.camera, frames.exposure, response);
    const std::vector<uint8_t> truth2 = applyCameraResponse(truth_seed2, frames.exposure, response);
    main.mask = changedPixelMask(main.truth, main.camera);
    main.noise = regionErrors(truth2, main.truth, main.mask);
    main.truth_low_passed = lowPass3x3Linear(main.truth, width, height);
    main.noise_low_passed = regionErrors(lowPass3x3Linear(truth2, width, height), main.truth_low_passed, main.mask);
    const std::vector<uint8_t>& mask = main.mask;
    bench.writePng("truth.png", width, height, main.truth);
    bench.writePng("camera.png", width, height, main.camera);
    size_t changed = 0;
    for (uint8_t in : mask) changed += in;
    std::vector<uint8_t> mask_image(mask.size() * 4, 255);
    for (size_t i = 0; i < mask.size(); ++i) mask_image[4 * i] = mask_image[4 * i + 1] = mask_image[4 * i + 2] = mask[i] ? 255 : 0;
    bench.writePng("mask.png", width, height, mask_image);
    const RegionErrors& noise = main.noise;
    bench.results["truth"] = {
        {"size", std::to_string(width) + "x" + std::to_string(height)},
        {"samples_per_pixel", settings.truth_samples},
        {"local_time", bench.localTime(condition.utc_seconds)},
        {"cloud_cover", condition.cloud_cover},
        {"camera_response", response.name},
        {"exposure", frames.exposure},
        {"changed_pixels", changed},
        {"noise_between_seeds", regionJson(noise)},
        {"noise_between_seeds_low_passed", regionJson(main.noise_low_passed)},
        {"seconds", millisecondsSince(start) / 1000.0}};
    bench.say("truth: " + std::to_string(width) + "x" + std::to_string(height) + ", " +
              std::to_string(settings.truth_samples) + " spp, sunny " + bench.localTime(condition.utc_seconds) +
              " site clock; building and shadow " + std::to_string(changed) + " px (" +
              fixed(100.0 * double(changed) / double(mask.size()), 1) + " %)");
    bench.say("truth noise (seed 1 vs seed 2): building+shadow mean " + fixed(noise.changed.mean_de00) + " p95 " +
              fixed(noise.changed.p95_de00) + " dE00, whole frame mean " + fixed(noise.whole.mean_de00) +
              " p95 " + fixed(noise.whole.p95_de00));
    return main;
}

// Accuracy of the runtime's modes: each one's steady composite against the truth (frame times come later).
std::vector<ModePoint> runtimeModeAccuracy(Bench& bench, const MainTruth& main, const BenchCondition& condition,
                                           const CameraResponse& response, const CameraPose& pose) {
    const uint32_t width = bench.settings.accuracy_width, height = bench.settings.accuracy_height;
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    std::vector<ModePoint> points;
    Runtime& runtime = bench.runtimeFor(width, height);
    for (const RuntimeMode& mode : benchRuntimeModes(bench.ground_match_available)) {
        const FrameInput input = frameInputFor(mode, main.camera, intrinsics, pose, condition.utc_seconds,
                                               condition.cloud_cover, main.frames.exposure * response.exposure_scale);
        const std::vector<uint8_t> composite = steadyComposite(runtime, input);
        bench.writePng(mode.name + ".png", width, height, composite);
        ModePoint point{mode.name, "runtime", regionErrors(composite, main.truth, main.mask), 0.0, "measured"};
        point.light = regionErrors(lowPass3x3Linear(composite, width, height), main.truth_low_passed, main.mask);
        points.push_back(point);
    }
    return points;
}

// Accuracy of the path tracer at each sample count, raw and denoised (another seed than the truth's).
void addTracerAccuracy(Bench& bench, const MainTruth& main, const CameraResponse& response,
                       std::vector<ModePoint>& points) {
    const uint32_t width = bench.settings.accuracy_width, height = bench.settings.accuracy_height;
    for (uint32_t samples : bench.settings.tracer_samples) {
        TracedFrameRequest request = main.seed2_request;
        request.samples_per_pixel = samples;
        request.seed = 3;
        request.denoise = true;
        const TracedFrame traced = bench.renderer->render(request, /*use_cache=*/false);
        const std::vector<uint8_t> raw = applyCameraResponse(traced.linear, main.frames.exposure, response);
        const std::vector<uint8_t> denoised = applyCameraResponse(traced.denoised, main.frames.exposure, response);
        bench.writePng("tracer_" + std::to_string(samples) + "spp_raw.png", width, height, raw);
        bench.writePng("tracer_" + std::to_string(samples) + "spp_denoised.png", width, height, denoised);
        points.push_back({"tracer_" + std::to_string(samples) + "spp_raw", "tracer_raw",
                          regionErrors(raw, main.truth, main.mask), 0.0, ""});
        points.push_back({"tracer_" + std::to_string(samples) + "spp_denoised", "tracer_denoised",
                          regionErrors(denoised, main.truth, main.mask), 0.0, ""});
    }
}

// The per-pass profile of direct-only and the proposed method (each pass submitted alone; shadow maps redrawn
// every profiled frame, as when the sun moves a step).
Json profilePasses(Bench& bench, Runtime& timed, const std::vector<RuntimeMode>& modes,
                   const std::vector<FrameInput>& inputs, std::vector<uint8_t>& out) {
    Json profile;
    for (size_t index : {size_t(0), size_t(1)}) {
        std::vector<PassTimings> passes(std::max(5u, bench.settings.timed_frames / 2));
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
    return profile;
}

// Frame time of the runtime's modes at one size, modes interleaved frame by frame, and their pass profile;
// the medians at 640x360 go to median_640 (the chart's x).
Json timeRuntimeModesAt(Bench& bench, uint32_t timing_width, uint32_t timing_height, const MainTruth& main,
                        const BenchCondition& condition, const CameraResponse& response, const CameraPose& pose,
                        std::map<std::string, double>& median_640) {
    const Settings& settings = bench.settings;
    const std::string size = std::to_string(timing_width) + "x" + std::to_string(timing_height);
    const std::vector<uint8_t> big_camera = resizeNearest(main.camera, settings.accuracy_width,
                                                          settings.accuracy_height, timing_width, timing_height);
    const CameraIntrinsics big = CameraIntrinsics::fromFieldOfView(timing_width, timing_height, bench.view.horizontal_fov_deg);
    Runtime& timed = bench.runtimeFor(timing_width, timing_height);
    std::vector<FrameInput> inputs;
    std::vector<RuntimeMode> modes = benchRuntimeModes(bench.ground_match_available);
    for (const RuntimeMode& mode : modes)
        inputs.push_back(frameInputFor(mode, big_camera, big, pose, condition.utc_seconds, condition.cloud_cover,
                                       main.frames.exposure * response.exposure_scale));
    std::vector<uint8_t> out(size_t(timing_width) * timing_height * 4);
    // Each mode timed on a runtime of its own, as an app has: one runtime switching modes would choose the ground
    // quads again at every switch (ground_pass.h), 4-7 ms of host time in each proposed frame that no app pays.
    std::vector<std::unique_ptr<Runtime>> mode_runtimes;
    for (size_t index = 0; index < modes.size(); ++index)
        mode_runtimes.push_back(
            Runtime::open(*bench.context, bench.bake_set, bench.runtimeOptions(timing_width, timing_height)));
    for (uint32_t frame = 0; frame < settings.warm_up_frames; ++frame)
        for (size_t index = 0; index < modes.size(); ++index) mode_runtimes[index]->renderFrame(inputs[index], out.data());
    std::vector<std::vector<double>> times(modes.size());
    for (uint32_t frame = 0; frame < settings.timed_frames; ++frame)
        for (size_t index = 0; index < modes.size(); ++index) {
            const Clock::time_point frame_start = Clock::now();
            mode_runtimes[index]->renderFrame(inputs[index], out.data());
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
    Json profile = profilePasses(bench, timed, modes, inputs, out);
    bench.say("passes " + size + " proposed (profiling mode, ms): upload " +
              fixed(profile["proposed"]["upload_ms"]) + ", shadow " + fixed(profile["proposed"]["shadow_ms"]) +
              ", occluder " + fixed(profile["proposed"]["occluder_ms"]) + ", building " +
              fixed(profile["proposed"]["building_ms"]) + ", ground " + fixed(profile["proposed"]["ground_ms"]) +
              ", statistics " + fixed(profile["proposed"]["statistics_ms"]) + ", readback " +
              fixed(profile["proposed"]["readback_ms"]));
    return {{"modes", per_mode}, {"passes", profile}};
}

// The path tracer's frame at 640x360: traced and timed up to tracer_timed_max_samples; above, the per-sample
// time of the largest timed count scaled (the tracer's cost is linear in samples). Sets the tracer points'
// frame times.
Json timeTracer(Bench& bench, const MainTruth& main, std::vector<ModePoint>& points) {
    const Settings& settings = bench.settings;
    Json tracer_timing;
    TracedFrameRequest request = main.seed2_request;
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
    return tracer_timing;
}

// Every mode's frame time: the runtime's at 1280x720 and 640x360, the path tracer's at 640x360; results["timing"].
Json timeModes(Bench& bench, const MainTruth& main, const BenchCondition& condition, const CameraResponse& response,
               const CameraPose& pose, std::vector<ModePoint>& points) {
    Json timing;
    std::map<std::string, double> median_640;
    for (const auto& [timing_width, timing_height] : std::vector<std::pair<uint32_t, uint32_t>>{{1280, 720}, {640, 360}}) {
        const std::string size = std::to_string(timing_width) + "x" + std::to_string(timing_height);
        timing[size] = timeRuntimeModesAt(bench, timing_width, timing_height, main, condition, response, pose, median_640);
    }
    timing["640x360"]["tracer"] = timeTracer(bench, main, points);
    for (ModePoint& point : points)
        if (point.kind == "runtime") point.frame_ms_640 = median_640[point.name];
    bench.results["timing"] = timing;
    return timing;
}

// The accuracy table, printed and as results["accuracy"].
void reportAccuracy(Bench& bench, const std::vector<ModePoint>& points) {
    Json accuracy;
    bench.say("");
    bench.say("| mode | frame 640x360 ms | building+shadow mean / p95 dE00 | PSNR dB | whole frame mean / p95 dE00 | PSNR dB |");
    bench.say("| --- | --- | --- | --- | --- | --- |");
    for (const ModePoint& point : points) {
        accuracy[point.name] = regionJson(point.errors);
        if (point.light) accuracy[point.name]["low_passed"] = regionJson(*point.light);
        accuracy[point.name]["frame_ms_640x360"] = point.frame_ms_640;
        accuracy[point.name]["frame_time_source"] = point.time_source;
        bench.say("| " + point.name + " | " + fixed(point.frame_ms_640, 1) + " | " + fixed(point.errors.changed.mean_de00) +
                  " / " + fixed(point.errors.changed.p95_de00) + " | " + fixed(point.errors.changed.psnr_db, 1) +
                  " | " + fixed(point.errors.whole.mean_de00) + " / " + fixed(point.errors.whole.p95_de00) + " | " +
                  fixed(point.errors.whole.psnr_db, 1) + " |");
    }
    bench.results["accuracy"] = accuracy;
}

const ModePoint& modePointNamed(const std::vector<ModePoint>& points, const std::string& name) {
    for (const ModePoint& point : points)
        if (point.name == name) return point;
    throw std::logic_error(name);
}

// The goals: the proposed method's frame time within 1.10x of direct-only's, its error below a third of
// direct-only's, and the path tracer at least 100x slower to reach that error. Printed, results["goals"], and
// returned for the chart.
Json reportGoals(Bench& bench, const std::vector<ModePoint>& points, const Json& timing,
                 const RegionErrors& noise_low_passed) {
    const ModePoint& direct = modePointNamed(points, "direct_only");
    const ModePoint& proposed = modePointNamed(points, "proposed");
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
    // The same goal read on the light (issue 44 item 6): both images low-passed, the truth's noise taken out.
    const double noise_light = noise_low_passed.changed.mean_de00;
    const double proposed_light = withoutTruthNoise(proposed.light->changed.mean_de00, noise_light);
    const double direct_light = withoutTruthNoise(direct.light->changed.mean_de00, noise_light);
    const double light_ratio = proposed_light / direct_light;
    goals["error_over_direct_only_low_passed"] = {
        {"ratio", light_ratio}, {"proposed_mean_de00", proposed_light}, {"direct_only_mean_de00", direct_light},
        {"noise_between_seeds_mean_de00", noise_light}, {"goal_below", 1.0 / 3.0}, {"held", light_ratio < 1.0 / 3.0}};
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
    bench.say("goal, read on the light (3 x 3 low-passed in linear light, the truth's noise of " + fixed(noise_light) +
              " dE00 between seeds taken out): proposed " + fixed(proposed_light) + " over direct-only " +
              fixed(direct_light) + " = " + fixed(light_ratio, 3) + " (below 0.333): " +
              (light_ratio < 1.0 / 3.0 ? "held" : "NOT held"));
    bench.say("goal: path tracer time to reach the proposed error over the proposed time " +
              (reaching ? fixed(tracer_ratio, 0) + "x (" + (*reaching)->name + ")"
                        : "> " + fixed(tracer_ratio, 0) + "x (no tracer mode reached it)") +
              " (at least 100x): " + (tracer_ratio >= 100.0 ? "held" : "NOT held"));
    return goals;
}

// chart.svg (error against frame time, log x, with the goals' lines) and chart.json (its points and the goals).
void writeErrorChart(Bench& bench, const std::vector<ModePoint>& points, const Json& goals, const RegionErrors& noise,
                     const BenchCondition& condition) {
    const Settings& settings = bench.settings;
    const ModePoint& direct = modePointNamed(points, "direct_only");
    const ModePoint& proposed = modePointNamed(points, "proposed");
    Chart chart;
    chart.title = "gusuku: error against frame time (" + std::to_string(settings.accuracy_width) + "x" +
                  std::to_string(settings.accuracy_height) + " accuracy, 640x360 time, sunny " +
                  bench.localTime(condition.utc_seconds) + ")";
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

}  // namespace

void runMain(Bench& bench) {
    const BenchCondition condition{bench.bake_midnight_utc + 10.5 * 3600.0, 0.0f};
    const CameraResponse response = benchCameraResponses()[0];
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    const MainTruth main = traceMainTruth(bench, condition, response);
    std::vector<ModePoint> points = runtimeModeAccuracy(bench, main, condition, response, pose);
    addTracerAccuracy(bench, main, response, points);
    const Json timing = timeModes(bench, main, condition, response, pose, points);
    reportAccuracy(bench, points);
    const Json goals = reportGoals(bench, points, timing, main.noise_low_passed);
    writeErrorChart(bench, points, goals, main.noise, condition);
}

}  // namespace gusuku::bench

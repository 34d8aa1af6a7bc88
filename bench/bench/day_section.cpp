// The bench's day section (runDay): from an hour after sunrise to an hour before sunset in steps, the error of
// the slot blend, the nearest slot, the blend with a colour match and direct-only; where the blend's error
// passes 2 and 5 dE00, why (the error at the slots' own times against the truth's noise), and day.svg.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bench_run.h"
#include "camera_response.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/maths/sun.h"
#include "gusuku_bake/camera_frame.h"
#include "runtime_modes.h"
#include "svg_chart.h"

namespace gusuku::bench {
namespace {

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

// The day's steps as measured: their JSON, the chart's series, and the blend's error per step.
struct DaySteps {
    Json steps = Json::array();
    ChartSeries blend{"blend of two slots (match off)", "#1f77b4", {}, true};
    ChartSeries nearest{"nearest slot (match off)", "#ff7f0e", {}, true};
    ChartSeries direct{"direct-only", "#d62728", {}, true};
    std::vector<std::pair<double, double>> blend_errors;  // (hour, error)
};

// Traces and measures every step from an hour after sunrise to an hour before sunset, printing a table row
// for each. match_mode: the match column's mode.
DaySteps measureDaySteps(Bench& bench, double sunrise, double sunset, const std::string& match_mode,
                         const CameraResponse& response) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.sweep_width, height = settings.sweep_height;
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    const CameraPose pose = lookAtPose(bench.view.position_enu, bench.view.look_at_enu);
    Runtime& runtime = bench.runtimeFor(width, height);
    DaySteps day;
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
        // The blend's composite and the truth go to frames/ (day_HHMM_*.png), so a part of the building (a roof,
        // a wall) can be read against the truth after the run.
        const std::vector<uint8_t> blend_frame = steadyComposite(
            runtime, frameInputFor(runtimeModeNamed("proposed"), camera, intrinsics, pose, utc, 0.0f, frames.exposure));
        std::string clock = bench.localTime(utc);
        clock.erase(2, 1);
        bench.writePng("day_" + clock + "_blend.png", width, height, blend_frame);
        bench.writePng("day_" + clock + "_truth.png", width, height, truth);
        const ErrorSummary with_blend = summariseError(blend_frame, truth, mask),
                           without_blend = errorOf(nearest_mode),
                           matched = errorOf(runtimeModeNamed(match_mode)),
                           direct_only = errorOf(runtimeModeNamed("direct_only"));
        const double hour = (utc - bench.bake_midnight_utc) / 3600.0;
        const double elevation = sunElevationAt(bench, utc);
        day.steps.push_back({{"local_time", bench.localTime(utc)}, {"sun_elevation_deg", elevation},
                             {"blend", errorJson(with_blend)}, {"nearest_slot", errorJson(without_blend)},
                             {"blend_colour_match", errorJson(matched)}, {"colour_match_mode", match_mode},
                             {"direct_only", errorJson(direct_only)}});
        day.blend.points.push_back({hour, with_blend.mean_de00, ""});
        day.nearest.points.push_back({hour, without_blend.mean_de00, ""});
        day.direct.points.push_back({hour, direct_only.mean_de00, ""});
        day.blend_errors.push_back({hour, with_blend.mean_de00});
        bench.say("| " + bench.localTime(utc) + " | " + fixed(elevation, 1) + " | " + fixed(with_blend.mean_de00) +
                  " | " + fixed(without_blend.mean_de00) + " | " + fixed(matched.mean_de00) + " | " +
                  fixed(direct_only.mean_de00) + " |");
    }
    return day;
}

// Where the blend's error passes 2 and 5: the steps above, as runs of consecutive steps in site clock time.
void reportBlendAboveThresholds(Bench& bench, const std::vector<std::pair<double, double>>& blend_errors,
                                Json& findings) {
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
}

// Which steps stand for a sunny slot: the step nearest each slot's time.
std::vector<bool> stepsAtSlotTimes(const Bench& bench, const std::vector<std::pair<double, double>>& blend_errors) {
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
    return at_slot;
}

// The truth's own noise at the day's settings: seed 2 against seed 1 at the step nearest noon, over the pixels
// the building changes (0 without steps). Below it no error is measurable.
double truthNoiseNearNoon(Bench& bench, const std::vector<std::pair<double, double>>& blend_errors,
                          const CameraResponse& response) {
    if (blend_errors.empty()) return 0.0;
    double noon_hour = blend_errors.front().first;
    for (const auto& step : blend_errors)
        if (std::abs(step.first - 12.0) < std::abs(noon_hour - 12.0)) noon_hour = step.first;
    TracedFrameRequest request = truthRequest(bench.view, bench.settings.sweep_width, bench.settings.sweep_height,
                                              {bench.bake_midnight_utc + noon_hour * 3600.0, 0.0f},
                                              bench.settings.sweep_samples, 1);
    const ImageRGBA first = bench.renderer->render(request).linear;
    request.seed = 2;
    const ImageRGBA second = bench.renderer->render(request).linear;
    request.include_building = false;
    request.seed = 1;
    const ImageRGBA camera_frame = bench.renderer->render(request).linear;
    const float exposure = bake::middleGreyExposure(camera_frame);
    const std::vector<uint8_t> truth1 = applyCameraResponse(first, exposure, response);
    return summariseError(applyCameraResponse(second, exposure, response), truth1,
                          changedPixelMask(truth1, applyCameraResponse(camera_frame, exposure, response)))
        .mean_de00;
}

// Why: the error at the slots' own times (where neither the blend nor the nearest slot interpolates anything,
// so what is left is the method's error at a baked instant), against the steps between slots; and the truth's
// own noise at these settings, below which no error is measurable.
void reportWhy(Bench& bench, const std::vector<std::pair<double, double>>& blend_errors,
               const CameraResponse& response, Json& findings) {
    const std::vector<bool> at_slot = stepsAtSlotTimes(bench, blend_errors);
    double at_slots_sum = 0.0, between_max = 0.0;
    size_t at_slots_count = 0;
    for (size_t step = 0; step < blend_errors.size(); ++step) {
        if (at_slot[step]) at_slots_sum += blend_errors[step].second, ++at_slots_count;
        else between_max = std::max(between_max, blend_errors[step].second);
    }
    const double noise = truthNoiseNearNoon(bench, blend_errors, response);
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
}

// day.svg: the three series through the day, the 2 and 5 dE00 lines and the slots' times.
void writeDayChart(const Bench& bench, const DaySteps& day) {
    Chart chart;
    chart.title = "gusuku: error through the day (mean CIEDE2000 over the building and shadow)";
    chart.x_label = "hour, site clock";
    chart.y_label = "mean CIEDE2000";
    chart.series = {day.blend, day.nearest, day.direct};
    chart.references.push_back({2.0, "2 dE00", false, "#999999"});
    chart.references.push_back({5.0, "5 dE00", false, "#999999"});
    for (const BakeSetSlot& slot : bench.bake_set.manifest.slots)
        if (!slot.utc.empty())
            chart.references.push_back({(parseIso8601Utc(slot.utc) - bench.bake_midnight_utc) / 3600.0,
                                        "slot " + slot.name, true, "#2ca02c"});
    const std::string svg = renderSvgChart(chart);
    writeBytesAtomically(bench.settings.output + "/day.svg", svg.data(), svg.size());
}

}  // namespace

void runDay(Bench& bench) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.sweep_width, height = settings.sweep_height;
    const double noon = bench.bake_midnight_utc + 12 * 3600.0;
    const double sunrise = horizonCrossing(bench, bench.bake_midnight_utc, noon);
    const double sunset = horizonCrossing(bench, bench.bake_midnight_utc + 24 * 3600.0, noon);
    const CameraResponse response = benchCameraResponses()[0];
    bench.runtimeFor(width, height);  // opened before the table is printed, as the steps use it
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
    const DaySteps day = measureDaySteps(bench, sunrise, sunset, match_mode, response);
    Json findings;
    reportBlendAboveThresholds(bench, day.blend_errors, findings);
    reportWhy(bench, day.blend_errors, response, findings);
    bench.results["day"] = {{"size", std::to_string(width) + "x" + std::to_string(height)},
                            {"truth_samples", settings.sweep_samples}, {"sunrise", bench.localTime(sunrise)},
                            {"sunset", bench.localTime(sunset)}, {"steps", day.steps}, {"findings", findings}};
    writeDayChart(bench, day);
}

}  // namespace gusuku::bench

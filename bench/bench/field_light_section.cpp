// gusuku-bench's field light section (issue 41 item 4): whether the sun is out, and how strong, read from camera
// frames of skies the single cloud cover cannot say, by today's image-statistics estimate and by the estimate from
// the site's own shadows (gusuku/maths/sun_from_shadows.h), on frames neither was tuned on.
//
// The skies, per instant: clear; the sun behind a cloud with blue sky around it (the sunny sky, its sun removed);
// thin cloud (the sun at a third, the sky 1.5 times as bright); overcast. Each through the bench's camera responses
// at -2, 0 and +2 EV. Per frame it reports the sun's state each estimate reads (and whether the frame shows a site
// shadow boundary: both of the site's predicted lit and shadowed ground in view), the strength, and the composite's
// error against the truth of that instant with the weather each estimate gives beside the true weather's. Last, a
// cloud passing over the sun for ten seconds: the frames' readings through the SunVisibilityFilter at 30 frames a
// second, and the state changes it makes.

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_run.h"
#include "gusuku/maths/sun_cue_choice.h"
#include "gusuku/maths/sun_evidence.h"
#include "gusuku/maths/sun_visibility.h"
#include "gusuku/maths/weather_estimate.h"
#include "gusuku/runtime/runtime_sun_evidence.h"
#include "runtime_modes.h"

namespace gusuku::bench {
namespace {

struct FieldSky {
    const char* name;
    float cloud_cover, sun_scale, sky_scale;
    bool sun_out;  ///< the truth of the sun's state
    /// The sun-to-sky ratio against the bake's (sun_scale / sky_scale): what the frame shows and what the runtime's
    /// sun takes once the ground colour match's gain has absorbed the sky's brightness (sun_evidence.h).
    float sunToSkyRatio() const { return sun_scale / sky_scale; }
};

// Thin cloud: the beam at a third (an optical depth of about 1.1), the light it loses partly scattered into a sky
// 1.5 times as bright; the slots still blend as sunny (the sky is blue-white, not overcast).
const std::vector<FieldSky>& fieldSkies() {
    static const std::vector<FieldSky> skies{
        {"clear", 0.0f, 1.0f, 1.0f, true},
        {"sun_behind_cloud", 0.0f, 0.0f, 1.0f, false},
        {"thin_cloud", 0.0f, 1.0f / 3.0f, 1.5f, true},
        {"overcast", 1.0f, 0.0f, 1.0f, false},
    };
    return skies;
}

// One estimate's reading of a frame, and the weather it gives the runtime.
struct SunReading {
    bool sun_out = true;
    float sun_strength = 1.0f;  ///< E_sun's scale while out
    float cloud_cover = 0.0f;   ///< what blends the slots
    SunEvidence evidence;       ///< the shadows' reading as SunVisibilityFilter takes it (default: no cue)
    bool boundary_in_view = false;
    uint32_t lit_samples = 0, shadowed_samples = 0;  ///< the shadows' estimate's sample counts
    std::string cue;
    Weather weather() const {
        Weather result;
        result.cloud_cover = cloud_cover;
        result.sun_scale = sun_out ? std::clamp(sun_strength, 0.0f, Weather::kMaxSunScale) : 0.0f;
        return result;
    }
};

// Today's estimate: one cover from the frame's statistics (weather_estimate.h), the sun at (1 - cover).
SunReading readByStatistics(const std::vector<uint8_t>& camera, uint32_t width, uint32_t height) {
    const CloudEstimate estimate = estimateCloudCover(camera, width, height);
    SunReading reading;
    reading.cloud_cover = estimate.cloud_cover;
    reading.sun_out = estimate.cloud_cover < 0.5f;
    reading.sun_strength = 1.0f - estimate.cloud_cover;
    reading.cue = estimate.sky_in_view ? "sky blueness" : "shadow contrast";
    return reading;
}

// The estimate from the site's shadows, which the runtime measures on the GPU on its ground colour match's frames
// (runtime_sun_evidence.h): a steady feed of the frame, then the newest reading, which must be one of these frames.
// The sky's state for the slots comes from today's statistics when the sun is hidden (no weather service here).
SunReading readByShadows(Runtime& runtime, const FrameInput& input, const SunReading& statistics) {
    const std::optional<RuntimeSunEvidence> before = latestSunEvidence(runtime);
    steadyComposite(runtime, input);
    const std::optional<RuntimeSunEvidence> after = latestSunEvidence(runtime);
    SunReading reading;
    reading.cloud_cover = statistics.cloud_cover;
    if (!after || (before && after->frame_index <= before->frame_index)) {
        reading.cue = "no reading";
        reading.sun_out = statistics.sun_out;
        reading.sun_strength = statistics.sun_strength;
        return reading;
    }
    const SunEvidenceEstimate& estimate = after->estimate;
    // The bench's exposure is the frame's own metered one (its middle grey, bench_run.cpp), as a phone's EV100 is:
    // the metered ground counts where no boundary is in view.
    const SunCueChoice choice = sunEvidenceForFilter(estimate, /*exposure_is_metered=*/true);
    reading.evidence = choice.evidence;
    reading.boundary_in_view =
        estimate.lit_samples >= kSunEvidenceMinSamples && estimate.shadowed_samples >= kSunEvidenceMinSamples;
    reading.lit_samples = estimate.lit_samples;
    reading.shadowed_samples = estimate.shadowed_samples;
    if (choice.cue == SunEvidenceCue::kNone) {
        // No cue in view: the estimate says nothing, and the app keeps its prior; here, today's statistics.
        reading.cue = "none (statistics)";
        reading.sun_out = statistics.sun_out;
        reading.sun_strength = statistics.sun_strength;
        return reading;
    }
    reading.cue = sunEvidenceCueName(choice.cue);
    reading.sun_out = choice.evidence.sun_out_probability >= 0.5f;
    reading.sun_strength = estimate.strength;
    if (reading.sun_out) reading.cloud_cover = 0.0f;
    return reading;
}

struct Tally {
    size_t frames = 0, right = 0, boundary_frames = 0, boundary_right = 0;
    size_t strength_frames = 0, strength_within_20 = 0;
    double excess_de00_sum = 0.0, excess_de00_max = 0.0;
    size_t excess_within_half = 0;
    std::map<std::string, std::pair<size_t, size_t>> by_cue;  ///< the cue that decided: frames, state right
    void add(const SunReading& reading, const FieldSky& sky, bool boundary, double excess_de00) {
        const bool state_right = reading.sun_out == sky.sun_out;
        ++by_cue[reading.cue].first;
        by_cue[reading.cue].second += state_right;
        ++frames;
        right += state_right;
        if (boundary) ++boundary_frames, boundary_right += state_right;
        if (sky.sun_out && reading.sun_out) {
            ++strength_frames;
            strength_within_20 += std::abs(reading.sun_strength / sky.sunToSkyRatio() - 1.0f) <= 0.2f;
        }
        excess_de00_sum += excess_de00;
        excess_de00_max = std::max(excess_de00_max, excess_de00);
        excess_within_half += excess_de00 <= 0.5;
    }
    std::string cueLine() const {
        std::string line;
        for (const auto& [cue, counts] : by_cue)
            line += (line.empty() ? "" : "; ") + cue + " " + std::to_string(counts.second) + "/" +
                    std::to_string(counts.first) + " right";
        return line;
    }
    Json json() const {
        Json cues = Json::object();
        for (const auto& [cue, counts] : by_cue) cues[cue] = {{"frames", counts.first}, {"state_right", counts.second}};
        return {{"by_cue", cues}, {"frames", frames}, {"state_right", right}, {"boundary_frames", boundary_frames},
                {"boundary_state_right", boundary_right}, {"strength_frames", strength_frames},
                {"strength_within_20_percent", strength_within_20},
                {"mean_excess_de00", frames ? excess_de00_sum / double(frames) : 0.0},
                {"max_excess_de00", excess_de00_max}, {"excess_within_half_de00", excess_within_half}};
    }
    std::string line(const std::string& name) const {
        auto share = [](size_t part, size_t whole) {
            return std::to_string(part) + "/" + std::to_string(whole) +
                   (whole ? " (" + fixed(100.0 * double(part) / double(whole), 0) + " %)" : "");
        };
        return "| " + name + " | " + share(right, frames) + " | " + share(boundary_right, boundary_frames) + " | " +
               share(strength_within_20, strength_frames) + " | " + fixed(frames ? excess_de00_sum / double(frames) : 0.0) +
               " | " + fixed(excess_de00_max) + " | " + share(excess_within_half, frames) + " |";
    }
};

// The frames' readings of one sky through the filter, for the passing cloud.
struct SkyReadings {
    std::vector<SunEvidence> evidence;
    std::vector<bool> statistics_sun_out;
};

// A cloud over the sun for ten seconds within thirty, at 30 frames a second, each frame's reading one of that
// sky's frames with a site shadow boundary in view, in turn (responses and exposures varying as a phone's auto
// exposure would).
Json passingCloud(Bench& bench, const SkyReadings& clear, const SkyReadings& hidden) {
    SunVisibilityFilter filter;
    size_t statistics_changes = 0;
    bool statistics_state = true;
    const int frames = 30 * 30;
    for (int frame = 0; frame < frames; ++frame) {
        const double seconds = frame / 30.0;
        const SkyReadings& readings = seconds >= 10.0 && seconds < 20.0 ? hidden : clear;
        const size_t index = size_t(frame) % readings.evidence.size();
        filter.update(seconds, SkyRegime::kBroken, &readings.evidence[index]);
        const bool statistics_out = readings.statistics_sun_out[index];
        if (frame > 0 && statistics_out != statistics_state) ++statistics_changes;
        statistics_state = statistics_out;
    }
    bench.say("passing cloud (10 s over the sun within 30 s, 30 frames a second): the filter on the shadows' "
              "reading changes state " + std::to_string(filter.state().changes) + " times (goal at most 2); today's "
              "statistics, read per frame with no filter, " + std::to_string(statistics_changes) + " times");
    return {{"filter_changes", filter.state().changes}, {"statistics_changes", statistics_changes}};
}

// The goals' table: each estimate's tally over the frames, and which cue decided the shadows' reading.
void sayTallies(Bench& bench, const Tally& statistics, const Tally& shadows) {
    bench.say("");
    bench.say("| estimate | sun state right, all frames (goal 85 %) | with a site shadow boundary (goal 95 %) | "
              "strength within 20 % | mean dE00 over the true weather's | max | within 0.5 dE00 |");
    bench.say("| --- | --- | --- | --- | --- | --- | --- |");
    bench.say(statistics.line("today's image statistics"));
    bench.say(shadows.line("the site's shadows"));
    bench.say("the cue that decided the site's shadows' reading, frames and state right: " + shadows.cueLine());
}

}  // namespace

Json runFieldLightUnder(Bench& bench, const SkySet& skies) {
    const Settings& settings = bench.settings;
    // Twice the sweep's sides: the estimate reads the ground match's sample grid (a sample every few pixels), and
    // at 160x90 a site shadow a few metres across holds too few samples to count (kSunEvidenceMinSamples).
    const uint32_t width = 2 * settings.sweep_width, height = 2 * settings.sweep_height;
    const CameraIntrinsics intrinsics = CameraIntrinsics::fromFieldOfView(width, height, bench.view.horizontal_fov_deg);
    // The bench's view (from the south: the sunlit faces, their shadows behind them) and its mirror from the north
    // (the site's shadows towards the camera): a visitor sees either.
    BenchView north = bench.view;
    north.position_enu.y = -north.position_enu.y;
    north.look_at_enu.y = -north.look_at_enu.y;
    const std::vector<std::pair<std::string, BenchView>> views{{"south", bench.view}, {"north", north}};
    RuntimeOptions options = bench.runtimeOptions(width, height);
    const std::unique_ptr<Runtime> runtime_owner = Runtime::open(*bench.context, *skies.bake_set, options);
    Runtime& runtime = *runtime_owner;
    // The ground colour match: with the camera's response and exposure unknown, as in the field, its gain takes
    // what the bake's light cannot say (the sky's brightness under thin cloud among it); the estimate needs the
    // same ground albedo.
    if (!skies.has_ground_albedo) {
        bench.say("field light, " + skies.label + ": not run: the bake set has no ground albedo (ground_grid.albedo), "
                  "which the estimate from the site's shadows and the ground colour match need");
        return "not run: no ground albedo";
    }
    const RuntimeMode mode = runtimeModeNamed("proposed_ground_match");
    const std::vector<double> hours = settings.quick ? std::vector<double>{8.0} : std::vector<double>{8.0, 12.0, 16.5};
    const std::vector<float> exposure_steps_ev{-2.0f, 0.0f, 2.0f};
    bench.say("");
    bench.say("**Light from the field, " + skies.label + " (" + std::to_string(width) + "x" + std::to_string(height) +
              ")**");
    bench.say("| view | site clock | sky | response | EV | boundary | statistics: sun, strength | shadows: sun, strength, "
              "confidence, cue | dE00 true weather | dE00 statistics | dE00 shadows |");
    bench.say("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    Json rows = Json::array();
    Tally statistics_tally, shadows_tally;
    SkyReadings clear_readings, hidden_readings;
    for (const auto& [view_name, view] : views) {
    const CameraPose pose = lookAtPose(view.position_enu, view.look_at_enu);
    for (double hour : hours) {
        const double utc = bench.bake_midnight_utc + hour * 3600.0;
        for (const FieldSky& sky : fieldSkies()) {
            BenchCondition condition{utc, sky.cloud_cover};
            condition.sun_scale = sky.sun_scale;
            condition.sky_scale = sky.sky_scale;
            const ConditionFrames frames =
                traceCondition(*skies.renderer, view, width, height, condition, settings.sweep_samples);
            for (const CameraResponse& base_response : benchCameraResponses())
                for (float ev : exposure_steps_ev) {
                    CameraResponse response = base_response;
                    response.exposure_scale *= std::exp2(ev);
                    const auto [truth, camera, mask] = respondedFrames(frames, response);
                    const float exposure = frames.exposure * response.exposure_scale;
                    auto composite_error = [&](const Weather& weather) {
                        FrameInput input = frameInputFor(mode, camera, intrinsics, pose, utc, 0.0f, exposure);
                        input.weather = weather;
                        return summariseError(steadyComposite(runtime, input), truth, mask).mean_de00;
                    };
                    Weather true_weather;
                    true_weather.cloud_cover = sky.cloud_cover;
                    true_weather.sun_scale = sky.sunToSkyRatio();
                    const double truth_error = composite_error(true_weather);
                    const SunReading by_statistics = readByStatistics(camera, width, height);
                    FrameInput reading_input = frameInputFor(mode, camera, intrinsics, pose, utc, 0.0f, exposure);
                    const SunReading by_shadows = readByShadows(runtime, reading_input, by_statistics);
                    const double statistics_error = composite_error(by_statistics.weather());
                    const double shadows_error = composite_error(by_shadows.weather());
                    // Whether the frame shows a site shadow boundary is the geometry's (the shadows' prediction
                    // of lit and shadowed ground in view), whatever the sky: both estimates are scored on it.
                    const bool boundary = by_shadows.boundary_in_view;
                    statistics_tally.add(by_statistics, sky, boundary, statistics_error - truth_error);
                    shadows_tally.add(by_shadows, sky, boundary, shadows_error - truth_error);
                    const std::string sky_name = sky.name;
                    SkyReadings* sequence = sky_name == "clear"              ? &clear_readings
                                            : sky_name == "sun_behind_cloud" ? &hidden_readings
                                                                             : nullptr;
                    // The passing cloud is seen by a camera that keeps a site shadow boundary in view (a visitor
                    // standing still): frames without one would leave the filter to its prior on every other frame.
                    if (sequence && boundary) {
                        sequence->evidence.push_back(by_shadows.evidence);
                        sequence->statistics_sun_out.push_back(by_statistics.sun_out);
                    }
                    auto said = [](const SunReading& reading) {
                        return std::string(reading.sun_out ? "out" : "hidden") + ", " + fixed(reading.sun_strength);
                    };
                    bench.say("| " + view_name + " | " + bench.localTime(utc) + " | " + sky.name + " | " + base_response.name + " | " +
                              fixed(ev, 0) + " | " + (boundary ? "yes" : "no") + " (" +
                              std::to_string(by_shadows.lit_samples) + " lit, " +
                              std::to_string(by_shadows.shadowed_samples) + " shadowed) | " + said(by_statistics) + " | " +
                              said(by_shadows) + ", " + fixed(by_shadows.evidence.confidence) + ", " + by_shadows.cue + " | " +
                              fixed(truth_error) + " | " + fixed(statistics_error) + " | " + fixed(shadows_error) + " |");
                    rows.push_back({{"view", view_name}, {"local_time", bench.localTime(utc)}, {"sky", sky.name},
                                    {"camera_response", base_response.name}, {"exposure_ev", ev},
                                    {"boundary_in_view", boundary},
                                    {"lit_samples", by_shadows.lit_samples},
                                    {"shadowed_samples", by_shadows.shadowed_samples}, {"true_sun_out", sky.sun_out},
                                    {"true_sun_to_sky_ratio", sky.sunToSkyRatio()},
                                    {"statistics", {{"sun_out", by_statistics.sun_out},
                                                    {"sun_strength", by_statistics.sun_strength},
                                                    {"cloud_cover", by_statistics.cloud_cover},
                                                    {"mean_de00", statistics_error}}},
                                    {"shadows", {{"sun_out", by_shadows.sun_out},
                                                 {"sun_strength", by_shadows.sun_strength},
                                                 {"confidence", by_shadows.evidence.confidence}, {"cue", by_shadows.cue},
                                                 {"mean_de00", shadows_error}}},
                                    {"true_weather_mean_de00", truth_error}});
                }
        }
    }
    }
    sayTallies(bench, statistics_tally, shadows_tally);
    Json passing = clear_readings.evidence.empty() || hidden_readings.evidence.empty()
                       ? Json(nullptr)
                       : passingCloud(bench, clear_readings, hidden_readings);
    return {{"skies", skies.label}, {"rows", rows}, {"statistics", statistics_tally.json()},
            {"shadows", shadows_tally.json()}, {"passing_cloud", passing}};
}

}  // namespace gusuku::bench

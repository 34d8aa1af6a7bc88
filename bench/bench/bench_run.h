#pragma once
// What gusuku-bench's sections share (gusuku_bench_main.cpp runs them in order): the run's settings, the bench's
// state (the bake set, the Vulkan context, the path tracer, the results and the summary), the error summaries'
// JSON and text, and the truth and camera frames of one condition.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_views.h"
#include "camera_response.h"
#include "camera_view.h"
#include "frame_spread.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/runtime/runtime.h"
#include "image_metrics.h"
#include "truth_renderer.h"

namespace gusuku::bench {

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
using bench_common::lookAtPose;
using bench_common::Spread;
using bench_common::spreadOf;

struct Settings {
    std::string bake_set, output, cache;
    std::optional<std::string> site_json;
    std::optional<std::string> photographed_bake_set;
    bool quick = false;
    std::vector<std::string> only;
    // The site section (--views): the visitor poses, and the sample's results.json to compare the frame with.
    std::vector<NamedView> views;
    std::optional<std::string> sample_results;
    // The sample's bake set (--sample-bakeset): its frame is timed in the same run, interleaved with the site's
    // frames from the same pose, so that "over the sample's" is a ratio of one run (the machine is shared).
    std::optional<std::string> sample_bake_set;
    // The runtime's anti-aliasing and texture filtering (--msaa, --anisotropy), so that a run can measure what
    // each costs and buys; by default the runtime's own (RuntimeOptions), so that every frame-time goal is read
    // as an app gets it (tests/test_bench_tool_defaults.cpp). The bench's device enables samplerAnisotropy where
    // it exists: --anisotropy 16 took the shrine's quick views from 2.51-2.55 to 2.21-2.37 mean dE00.
    uint32_t msaa_samples = RuntimeOptions{}.msaa_samples;
    float max_anisotropy = RuntimeOptions{}.max_anisotropy;
    // --cycles-truth: Cycles' renders of the poses (bench/cycles/cycles_view_render.py), checked at the baked instant.
    std::optional<std::string> cycles_truth;
    // Derived from quick.
    uint32_t accuracy_width = 320, accuracy_height = 180, truth_samples = 512;
    uint32_t sweep_width = 160, sweep_height = 90, sweep_samples = 256;
    uint32_t day_step_minutes = 15;
    uint32_t timed_frames = 40, warm_up_frames = 5;
    std::vector<uint32_t> tracer_samples{1, 4, 16, 64};
    uint32_t tracer_timed_max_samples = 64;  ///< above this, the tracer's 640x360 time is scaled from it
    bool wants(const std::string& section) const {
        if (section == "site" && views.empty()) return false;  // the site section needs its poses
        return only.empty() || std::find(only.begin(), only.end(), section) != only.end();
    }
    /// The main section (truth, every mode, the chart) runs unless --only names the site or field sections alone
    /// (each has its own truths).
    bool wantsMain() const {
        return only.empty() || std::any_of(only.begin(), only.end(), [](const std::string& section) {
                   return section != "site" && section != "field";
               });
    }
};

inline double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// JSON has no infinity: PSNR of equal frames is written as null.
inline Json finiteOrNull(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

inline Json errorJson(const ErrorSummary& summary) {
    return Json{{"mean_de00", summary.mean_de00}, {"p95_de00", summary.p95_de00},
                {"psnr_db", finiteOrNull(summary.psnr_db)}, {"pixels", summary.pixel_count}};
}

inline std::string fixed(double value, int digits = 2) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// Error of a frame against the truth over the changed pixels and the whole frame.
struct RegionErrors {
    ErrorSummary changed, whole;
};
inline RegionErrors regionErrors(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                          const std::vector<uint8_t>& mask) {
    return {summariseError(frame, truth, mask), summariseError(frame, truth)};
}
inline Json regionJson(const RegionErrors& errors) {
    return Json{{"building_and_shadow", errorJson(errors.changed)}, {"whole_frame", errorJson(errors.whole)}};
}

// Everything one condition (view, instant, weather) needs for accuracy: the linear truth and camera frames.
struct ConditionFrames {
    ImageRGBA truth, camera;  // with and without the building, same seed
    float exposure = 1.0f;    // the camera's auto exposure (middle grey of the camera frame)
    double trace_seconds = 0.0;
};

ConditionFrames traceCondition(TruthRenderer& renderer, const BenchView& view, uint32_t width, uint32_t height,
                               const BenchCondition& condition, uint32_t samples);

// One condition's frames as a camera with `response` records them (8-bit), and the pixels where the building
// changes the truth: what the weather sections compare each runtime composite with.
struct RespondedFrames {
    std::vector<uint8_t> truth, camera, mask;
};
RespondedFrames respondedFrames(const ConditionFrames& frames, const CameraResponse& response);

// One pair of skies the weather sections run under: the path tracer of the site under them and the runtime with
// the bake set baked under them, at the sweep size.
struct SkySet {
    std::string label;
    TruthRenderer* renderer = nullptr;
    Runtime* runtime = nullptr;
    bool has_ground_albedo = false;  ///< its bake set can run the ground match
    const BakeSetData* bake_set = nullptr;  ///< for a section that opens a runtime at another size
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
                ground_match_available, &bake_set};
    }
    SkySet photographedSkies() {
        return {photographed->label, photographed->renderer.get(), photographed->runtime.get(),
                !photographed->bake_set.manifest.ground_grid.albedo.empty(), &photographed->bake_set};
    }

    void say(const std::string& line) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
        summary.push_back(line);
    }
    void note(const std::string& line) {
        std::fprintf(stderr, "gusuku-bench: %s\n", line.c_str());
    }
    /// The runtime's options at this frame size, with the run's multisampling and anisotropy.
    RuntimeOptions runtimeOptions(uint32_t width, uint32_t height) const {
        RuntimeOptions options;
        options.frame_width = width;
        options.frame_height = height;
        options.msaa_samples = settings.msaa_samples;
        options.max_anisotropy = settings.max_anisotropy;
        return options;
    }
    Runtime& runtimeFor(uint32_t width, uint32_t height) {
        const std::string key = std::to_string(width) + "x" + std::to_string(height);
        auto& runtime = runtimes[key];
        if (!runtime) runtime = Runtime::open(*context, bake_set, runtimeOptions(width, height));
        return *runtime;
    }
    std::string localTime(double utc) const { return formatIso8601(utc, utc_offset_minutes).substr(11, 5); }
    void writePng(const std::string& name, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
        writePngRgba8(settings.output + "/frames/" + name, int(width), int(height), rgba8);
    }
};

/// Truth, accuracy of every mode, timing, the goals and the chart (main_section.cpp): always run.
void runMain(Bench& bench);
/// The day in steps: nearest slot, blend of two, direct-only (day_section.cpp).
void runDay(Bench& bench);
/// The goals from each visitor pose (--views) at a baked instant and 1.5 hours from it (site_section.cpp).
void runSiteGoals(Bench& bench);
/// Whether the sun is out and how strong, from frames of field skies, by today's estimate and by the site's
/// shadows (field_light_section.cpp, issue 41 item 4).
Json runFieldLightUnder(Bench& bench, const SkySet& skies);

}  // namespace gusuku::bench

// gusuku-render: a composite of the baked building into a camera frame with gusuku's runtime, and its frame
// time. Reads a bake set (gusuku_assets' loader), makes or reads the camera frame, opens the runtime on a headless
// device (one runtime per mode, as an app has), renders warm-up frames, times the whole frame (one fenced
// submission) for the proposed method and for direct-only (interleaved, so the machine's drift hits both), profiles
// each pass of both modes, and writes the PNGs.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <time.h>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/gpu/vulkan_context.h"
#include "bakeset_site.h"
#include "camera_image.h"
#include "camera_view.h"
#include "frame_spread.h"
#include "render_outputs.h"
#include "render_request.h"
#include "sample_camera.h"

namespace gusuku::render_cli {
namespace {

using bench_common::lookAtPose;
using bench_common::Spread;
using bench_common::spreadOf;
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The process's CPU time, every thread (llvmpipe's workers run in this process): on a machine shared with other
// jobs the wall clock swings with their load, while the work a frame costs in CPU time holds (within a few %).
double processCpuMilliseconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

// The instant to render: --time, or the bake date at 12:00 on the site's clock.
double frameInstant(const RenderRequest& request, const BakeSetManifest& manifest) {
    if (request.time_iso) return parseIso8601Utc(*request.time_iso);
    return bench_common::bakeDateMidnightUtc(request.bake_set, manifest, "--time") + 12 * 3600.0;
}

// The camera frame under the composite: the sample site traced without the building, or a photograph.
struct RenderCamera {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;
    float exposure = kImageCameraExposure;
};

RenderCamera renderCamera(const RenderRequest& request, VulkanContext& context, const std::string& sample_site_json,
                          double utc_seconds) {
    RenderCamera out;
    out.width = request.width;
    out.height = request.height;
    out.exposure = request.exposure.value_or(kImageCameraExposure);
    if (request.camera == "sample") {
        const Clock::time_point start = Clock::now();
        const bench::BenchView view{request.position_enu, request.look_at_enu, request.horizontal_fov_deg};
        SampleCameraFrame frame = renderSampleCameraFrame(
            context, sample_site_json, view, out.width, out.height, {utc_seconds, request.cloud_cover},
            request.camera_samples, request.exposure.value_or(0.0f));
        std::printf("camera frame:    path-traced and denoised, %u spp, %.1f s\n", request.camera_samples,
                    millisecondsSince(start) / 1000.0);
        out.rgba8 = std::move(frame.rgba8);
        out.exposure = frame.exposure;
    } else {
        CameraImage image = readCameraImage(request.camera);
        out.width = image.width;
        out.height = image.height;
        out.rgba8 = std::move(image.srgb_rgba8);
    }
    return out;
}

// Both modes' frame times, each on a runtime of its own, interleaved ABBA.
struct ModeTimings {
    std::vector<double> proposed_ms, direct_ms, proposed_cpu_ms, direct_cpu_ms;  // fenced frames, wall and CPU
    std::vector<double> pair_ratios, pair_cpu_ratios;                             // each pair's proposed / direct
    std::vector<PassTimings> passes, direct_passes;                               // the profiled frames' passes
};

void printModeTimings(const ModeTimings& timings, uint32_t timed_frames) {
    auto passMedian = [&](double PassTimings::*field, const std::vector<PassTimings>& of) {
        std::vector<double> values;
        for (const PassTimings& pass_timings : of) values.push_back(pass_timings.*field);
        return spreadOf(values).median;
    };
    const Spread proposed = spreadOf(timings.proposed_ms), baseline = spreadOf(timings.direct_ms);
    std::printf("frame (fenced):  proposed %.2f ms [%.2f, %.2f], direct-only %.2f ms [%.2f, %.2f], ratio %.3f\n",
                proposed.median, proposed.low, proposed.high, baseline.median, baseline.low, baseline.high,
                proposed.median / baseline.median);
    const Spread proposed_cpu = spreadOf(timings.proposed_cpu_ms), baseline_cpu = spreadOf(timings.direct_cpu_ms);
    std::printf("frame CPU time:  proposed %.2f ms [%.2f, %.2f], direct-only %.2f ms [%.2f, %.2f], ratio %.3f (all "
                "threads; steadier than the wall clock under load)\n",
                proposed_cpu.median, proposed_cpu.low, proposed_cpu.high, baseline_cpu.median, baseline_cpu.low,
                baseline_cpu.high, proposed_cpu.median / baseline_cpu.median);
    std::printf("frame pairs:     median of each pair's proposed / direct-only: wall %.3f, CPU time %.3f\n",
                spreadOf(timings.pair_ratios).median, spreadOf(timings.pair_cpu_ratios).median);
    for (int mode = 0; mode < 2; ++mode) {
        const std::vector<PassTimings>& of = mode == 0 ? timings.passes : timings.direct_passes;
        std::printf("passes, %-11s (profiling mode, medians of %u): upload %.2f, statistics %.2f, shadows %.2f, "
                    "occluder %.2f, building %.2f, ground %.2f, readback %.2f ms\n",
                    mode == 0 ? "proposed" : "direct-only", timed_frames,
                    passMedian(&PassTimings::upload_ms, of), passMedian(&PassTimings::statistics_ms, of),
                    passMedian(&PassTimings::shadow_ms, of), passMedian(&PassTimings::occluder_ms, of),
                    passMedian(&PassTimings::building_ms, of), passMedian(&PassTimings::ground_ms, of),
                    passMedian(&PassTimings::readback_ms, of));
    }
}

int run(const RenderRequest& request) {
    const BakeSetData bake_set = loadBakeSet(request.bake_set);
    const std::string sample_site_json =
        request.camera == "sample" ? bench_common::siteJsonOf(request.bake_set, bake_set.manifest, request.site_json)
                                   : std::string();
    refuseOutputsThatAreInputs(request, renderInputFiles(request, sample_site_json));
    const double utc_seconds = frameInstant(request, bake_set.manifest);
    VulkanContext context(vulkanOptionsFromEnvironment());
    std::fprintf(stderr, "gusuku-render: device %s\n", context.deviceDescription().c_str());

    // The camera frame.
    RenderCamera camera_frame = renderCamera(request, context, sample_site_json, utc_seconds);
    const uint32_t width = camera_frame.width, height = camera_frame.height;
    const std::vector<uint8_t>& camera = camera_frame.rgba8;
    const float exposure = camera_frame.exposure;
    const CameraPose pose = lookAtPose(request.position_enu, request.look_at_enu);
    if (request.camera_png) writePngRgba8(*request.camera_png, int(width), int(height), camera);

    RuntimeOptions options;
    options.frame_width = width;
    options.frame_height = height;
    if (request.ground_change_threshold) options.ground_change_threshold = *request.ground_change_threshold;
    options.msaa_samples = request.msaa_samples;
    options.max_anisotropy = request.max_anisotropy;
    std::unique_ptr<Runtime> runtime = Runtime::open(context, bake_set, options);
    // Direct-only on a runtime of its own, as an app that draws one mode has: one runtime switching modes every
    // frame would choose the ground quads again every frame (ground_pass.h), a host cost no app pays.
    std::unique_ptr<Runtime> direct_runtime = Runtime::open(context, bake_set, options);

    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = CameraIntrinsics::fromFieldOfView(width, height, request.horizontal_fov_deg);
    frame.pose = pose;
    frame.utc_unix_seconds = utc_seconds;
    frame.weather.cloud_cover = request.cloud_cover;
    frame.exposure = exposure;
    frame.colour_match = request.colour_match;
    FrameInput direct_only = frame;
    direct_only.mode = RenderMode::kDirectOnly;

    std::vector<uint8_t> composite(camera.size()), direct(camera.size());
    FrameInfo info;
    for (uint32_t warm_up = 0; warm_up < request.warm_up_frames; ++warm_up) {
        info = runtime->renderFrame(frame, composite.data());
        direct_runtime->renderFrame(direct_only, direct.data());
    }
    // Interleaved, the order swapped every pair (ABBA), so the shared machine's drift lands on both alike; the
    // ratio is what to read, and the median of each pair's own ratio is the steadiest under load.
    ModeTimings timings;
    std::vector<double>&proposed_ms = timings.proposed_ms, &direct_ms = timings.direct_ms,
                       &proposed_cpu_ms = timings.proposed_cpu_ms, &direct_cpu_ms = timings.direct_cpu_ms;
    auto timeFrame = [&](Runtime& target, const FrameInput& input, uint8_t* out, std::vector<double>& wall_ms,
                         std::vector<double>& cpu_ms) {
        const Clock::time_point start = Clock::now();
        const double cpu_start = processCpuMilliseconds();
        info = target.renderFrame(input, out);
        wall_ms.push_back(millisecondsSince(start));
        cpu_ms.push_back(processCpuMilliseconds() - cpu_start);
    };
    for (uint32_t index = 0; index < request.timed_frames; ++index) {
        if (index % 2 == 0) {
            timeFrame(*runtime, frame, composite.data(), proposed_ms, proposed_cpu_ms);
            timeFrame(*direct_runtime, direct_only, direct.data(), direct_ms, direct_cpu_ms);
        } else {
            timeFrame(*direct_runtime, direct_only, direct.data(), direct_ms, direct_cpu_ms);
            timeFrame(*runtime, frame, composite.data(), proposed_ms, proposed_cpu_ms);
        }
        timings.pair_ratios.push_back(proposed_ms.back() / direct_ms.back());
        timings.pair_cpu_ratios.push_back(proposed_cpu_ms.back() / direct_cpu_ms.back());
    }
    // Each pass alone, both modes interleaved in the same way.
    std::vector<PassTimings>&passes = timings.passes, &direct_passes = timings.direct_passes;
    passes.resize(request.timed_frames);
    direct_passes.resize(request.timed_frames);
    std::vector<uint8_t> profiled(camera.size());
    for (uint32_t index = 0; index < request.timed_frames; ++index) {
        if (index % 2 == 0) runtime->renderFrameProfiled(frame, profiled.data(), passes[index]);
        direct_runtime->renderFrameProfiled(direct_only, profiled.data(), direct_passes[index]);
        if (index % 2 == 1) runtime->renderFrameProfiled(frame, profiled.data(), passes[index]);
    }
    info = runtime->renderFrame(frame, composite.data());  // the proposed runtime's own figures (quads drawn)

    writePngRgba8(request.output_png, int(width), int(height), composite);
    if (request.direct_only_png) writePngRgba8(*request.direct_only_png, int(width), int(height), direct);

    std::printf("composite:       %s (%u x %u)\n", request.output_png.c_str(), width, height);
    std::printf("time (UTC):      %s\n", formatIso8601(utc_seconds, 0).c_str());
    std::printf("sun:             azimuth %.2f deg, elevation %.2f deg%s\n", info.sun_azimuth_deg,
                info.sun_apparent_elevation_deg, info.sun_above_horizon ? "" : " (below the horizon)");
    auto slotName = [&](int slot) { return slot >= 0 ? bake_set.manifest.slots[size_t(slot)].name : std::string("-"); };
    std::printf("slots:           %s %.2f, %s %.2f, %s %.2f (cloud cover %.2f)\n", slotName(info.slot_a).c_str(),
                info.slot_a >= 0 ? (1.0 - info.overcast_weight) * (1.0 - info.slot_b_weight) : 0.0,
                slotName(info.slot_b).c_str(),
                info.slot_b >= 0 ? (1.0 - info.overcast_weight) * info.slot_b_weight : 0.0,
                slotName(info.overcast_slot).c_str(), double(info.overcast_weight), double(request.cloud_cover));
    printModeTimings(timings, request.timed_frames);
    std::printf("ground ratio:    %u of %u grid quads drawn (the rest of the frame is not touched)\n",
                info.ground_quads_drawn, info.ground_quads_total);
    std::printf("GPU memory:      %.1f MiB held by the runtime\n", double(runtime->deviceMemoryBytes()) / (1 << 20));
    return 0;
}

}  // namespace
}  // namespace gusuku::render_cli

int main(int argc, char** argv) {
    using namespace gusuku::render_cli;
    return gusuku::runToolMain("gusuku-render", [&] {
        const RenderRequest request = parseRenderRequest(std::vector<std::string>(argv + 1, argv + argc));
        if (request.help) {
            std::printf("%s", formatHelp(renderHelp()).c_str());
            return 0;
        }
        return run(request);
    });
}

// gusuku-frame-paths: the frame's two paths, measured in one run, interleaved. A benchmark, not a test.
//   fenced    host bytes in, the composite read back into host bytes, one slot: the host waits on every frame
//             (0.1.0's only path; tools and tests keep it);
//   resident  host bytes in, no read-back, frames_in_flight slots: the host records frame N+1 while the GPU
//             draws frame N, and waits only when every slot is busy (an app then takes compositeImage()).
// Both on the same in-memory bake set (gusuku/synthetic/synthetic_bakeset.h) at the given size, for each
// multisample count of --msaa (RuntimeOptions::msaa_samples) and each render mode of --mode; rounds run every
// combination in turn (the order reversed every other round) so that a noisy shared machine slows them alike.
// Prints each one's median milliseconds a frame, resident over fenced, and each count's cost over the first's.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "gusuku/runtime/runtime.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace {

using namespace gusuku;
using Clock = std::chrono::steady_clock;

struct Settings {
    // The runtime's own defaults (RuntimeOptions), never restated.
    long width = RuntimeOptions{}.frame_width, height = RuntimeOptions{}.frame_height, rounds = 7, frames_per_round = 20;
    std::vector<uint32_t> msaa_counts{RuntimeOptions{}.msaa_samples};
    std::vector<RenderMode> modes{RenderMode::kBakedLight};
    long profiled_frames = 0;  // --profile N: N profiled frames per combination after the rounds
    bool ground_ratio = true;  // --no-ground-ratio: the last pass keeps only what it must (the resolve)
    ColourMatch colour_match = ColourMatch::kOff;  // --colour-match: FrameInput::colour_match of every frame
};

struct PathRun {
    std::unique_ptr<Runtime> runtime;
    uint32_t msaa_samples = 1;
    RenderMode mode = RenderMode::kBakedLight;
    bool read_back = false;
    std::vector<double> frame_ms;  // per round: mean milliseconds a frame
    std::vector<PassTimings> profiles;
};

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

// "1,4": each a count RuntimeOptions::msaa_samples allows (the runtime says which the device has).
std::vector<uint32_t> parseMsaaCounts(const CommandLine& line, const std::string& text) {
    std::vector<uint32_t> counts;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        if (item != "1" && item != "2" && item != "4" && item != "8")
            line.fail("--msaa: '" + item + "' in '" + text + "' is not 1, 2, 4 or 8");
        counts.push_back(uint32_t(std::stoul(item)));
    }
    if (counts.empty()) line.fail("--msaa: '" + text + "' names no sample count");
    return counts;
}

Settings parseSettings(int argc, char** argv, bool& help) {
    Settings settings;
    CommandLine line("gusuku-frame-paths", std::vector<std::string>(argv + 1, argv + argc));
    help = line.helpRequested();
    if (help) {
        std::printf("usage: gusuku-frame-paths [--width W] [--height H] [--rounds N] [--frames N]\n"
                    "                          [--msaa COUNTS (e.g. 1,4; default %u, the runtime's)]\n"
                    "                          [--mode baked-light|direct-only|both (default baked-light;\n"
                    "                           proposed: baked-light's old spelling)]\n"
                    "                          [--profile N (N profiled frames each: every pass alone)]\n"
                    "                          [--no-ground-ratio (FrameInput::ground_ratio off)]\n"
                    "                          [--colour-match off|reinhard|preserve|ground (default off;\n"
                    "                           paper: reinhard's old spelling)]\n",
                    RuntimeOptions{}.msaa_samples);
        return settings;
    }
    settings.width = long(line.integer("--width", 16, 8192).value_or(settings.width));
    settings.height = long(line.integer("--height", 16, 8192).value_or(settings.height));
    settings.rounds = long(line.integer("--rounds", 1, 1000).value_or(settings.rounds));
    settings.frames_per_round = long(line.integer("--frames", 1, 100000).value_or(settings.frames_per_round));
    if (const std::optional<std::string> msaa = line.text("--msaa")) settings.msaa_counts = parseMsaaCounts(line, *msaa);
    settings.ground_ratio = !line.flag("--no-ground-ratio");
    settings.profiled_frames = long(line.integer("--profile", 0, 1000).value_or(0));
    // "proposed" (RenderMode's old name) stays accepted so that existing scripts keep working; 0 and 3 both keep
    // the default, kBakedLight.
    const size_t mode = line.choice("--mode", {"proposed", "direct-only", "both", "baked-light"}).value_or(0);
    if (mode == 1) settings.modes = {RenderMode::kDirectOnly};
    if (mode == 2) settings.modes = {RenderMode::kBakedLight, RenderMode::kDirectOnly};
    // "paper" (ColourMatch's old name) stays accepted so that existing scripts keep working.
    const ColourMatch matches[5] = {ColourMatch::kOff, ColourMatch::kReinhard, ColourMatch::kPreserve,
                                    ColourMatch::kGround, ColourMatch::kReinhard};
    const size_t match =
        line.choice("--colour-match", {"off", "reinhard", "preserve", "ground", "paper"}).value_or(0);
    settings.colour_match = matches[match];
    line.positionals();
    line.finish();
    return settings;
}

const char* modeName(RenderMode mode) { return mode == RenderMode::kDirectOnly ? "direct-only" : "proposed"; }

void printResults(const Settings& settings, const std::vector<PathRun>& runs) {
    const char* match_names[4] = {"off", "paper", "preserve", "ground"};
    std::printf("frame paths, %ldx%ld, colour match %s, %ld rounds x %ld frames each, interleaved (medians of round "
                "means)\n",
                settings.width, settings.height, match_names[uint32_t(settings.colour_match)], settings.rounds,
                settings.frames_per_round);
    for (const PathRun& run : runs)
        std::printf("  msaa %u, %-11s  %-34s %8.2f ms a frame\n", run.msaa_samples, modeName(run.mode),
                    run.read_back ? "fenced   (read back, 1 slot):" : "resident (no read back, 2 slots):",
                    median(run.frame_ms));
    for (size_t index = 0; index < runs.size(); index += 2 * settings.modes.size())
        std::printf("  msaa %u: %.1f MiB of device memory held by a one-slot runtime\n", runs[index].msaa_samples,
                    double(runs[index].runtime->deviceMemoryBytes()) / double(1 << 20));
    // Runs come in pairs (fenced, resident), for each count then each mode.
    for (size_t index = 0; index + 1 < runs.size(); index += 2) {
        const double fenced_ms = median(runs[index].frame_ms), resident_ms = median(runs[index + 1].frame_ms);
        std::printf("  msaa %u, %-11s  resident / fenced: %.3f\n", runs[index].msaa_samples,
                    modeName(runs[index].mode), fenced_ms > 0.0 ? resident_ms / fenced_ms : 0.0);
    }
    const size_t per_count = 2 * settings.modes.size();
    for (size_t index = per_count; index < runs.size(); ++index) {
        const PathRun& base = runs[index % per_count];
        const double base_ms = median(base.frame_ms);
        std::printf("  %-8s %-11s  msaa %u / msaa %u: %.3f\n", runs[index].read_back ? "fenced" : "resident",
                    modeName(runs[index].mode), runs[index].msaa_samples, base.msaa_samples,
                    base_ms > 0.0 ? median(runs[index].frame_ms) / base_ms : 0.0);
    }
    for (const PathRun& run : runs) {
        if (run.profiles.empty() || !run.read_back) continue;
        auto passMedian = [&](double PassTimings::*pass) {
            std::vector<double> values;
            for (const PassTimings& timings : run.profiles) values.push_back(timings.*pass);
            return median(values);
        };
        std::printf("  msaa %u, %-11s  profile (each pass alone, ms): uniforms + camera pack %.2f, colour statistics "
                    "%.2f, camera in + occluder %.2f, building %.2f, ground ratio + resolve %.2f, read-back %.2f, "
                    "total %.2f\n",
                    run.msaa_samples, modeName(run.mode), passMedian(&PassTimings::upload_ms),
                    passMedian(&PassTimings::statistics_ms), passMedian(&PassTimings::occluder_ms),
                    passMedian(&PassTimings::building_ms), passMedian(&PassTimings::ground_ms),
                    passMedian(&PassTimings::readback_ms), passMedian(&PassTimings::total_ms));
        if (settings.colour_match != ColourMatch::kOff) {
            // The camera is measured one frame in kColourStatisticsInterval: the median is a frame between
            // measurements, the largest a measuring one, the mean what a frame pays on average.
            std::vector<double> match_ms;
            for (const PassTimings& timings : run.profiles)
                match_ms.push_back(timings.upload_ms + timings.statistics_ms);
            double sum = 0.0;
            for (double value : match_ms) sum += value;
            std::printf("  msaa %u, %-11s  uniforms + camera pack + colour statistics (ms): median %.2f, mean %.2f, "
                        "largest %.2f over %zu profiled frames\n",
                        run.msaa_samples, modeName(run.mode), median(match_ms), sum / double(match_ms.size()),
                        *std::max_element(match_ms.begin(), match_ms.end()), match_ms.size());
        }
    }
    if (settings.modes.size() == 2)
        for (size_t index = 0; index < runs.size(); index += per_count)
            for (size_t path = 0; path < 2; ++path) {
                const PathRun& proposed = runs[index + path];
                const PathRun& direct = runs[index + 2 + path];
                std::printf("  msaa %u, %-8s proposed / direct-only: %.3f\n", proposed.msaa_samples,
                            proposed.read_back ? "fenced" : "resident",
                            median(proposed.frame_ms) / std::max(median(direct.frame_ms), 1e-9));
            }
}

}  // namespace

int main(int argc, char** argv) {
    Settings settings;
    try {
        bool help = false;
        settings = parseSettings(argc, argv, help);
        if (help) return 0;
    } catch (const UsageError& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    try {
        testing::SyntheticBakeSetOptions bake_options;
        bake_options.ground_albedo = 0.4f;  // so that --colour-match ground can run
        const BakeSetData bake_set = testing::makeSyntheticBakeSet(bake_options);
        std::vector<PathRun> runs;
        for (uint32_t samples : settings.msaa_counts) {
            RuntimeOptions options;
            options.frame_width = uint32_t(settings.width);
            options.frame_height = uint32_t(settings.height);
            options.msaa_samples = samples;
            for (RenderMode mode : settings.modes)
                for (bool read_back : {true, false}) {
                    options.frames_in_flight = read_back ? 1 : 2;
                    PathRun run;
                    run.runtime = Runtime::openHeadless(bake_set, options);
                    run.msaa_samples = samples;
                    run.mode = mode;
                    run.read_back = read_back;
                    runs.push_back(std::move(run));
                }
        }

        const long width = settings.width, height = settings.height;
        std::vector<uint8_t> camera(size_t(width) * size_t(height) * 4), output(camera.size());
        for (size_t i = 0; i < camera.size(); ++i) camera[i] = i % 4 == 3 ? 255 : uint8_t(i * 7);
        FrameInput frame;
        frame.camera_rgba8 = camera.data();
        const double focal = 0.9 * double(width);
        frame.intrinsics = {focal, focal, width / 2.0, height / 2.0, uint32_t(width), uint32_t(height)};
        frame.weather = Weather::sunny();
        frame.exposure = 0.1f;
        frame.ground_ratio = settings.ground_ratio;
        frame.colour_match = settings.colour_match;
        auto runRound = [&](PathRun& path, long round) {
            frame.mode = path.mode;
            const Clock::time_point start = Clock::now();
            for (long index = 0; index < settings.frames_per_round; ++index) {
                frame.pose = CameraPose::lookingAt({3.0 + 0.01 * double(index), -12, 3}, {0, 0, 1});
                frame.utc_unix_seconds =
                    testing::syntheticLocalTime(15, 0) + double(round * settings.frames_per_round + index);
                path.runtime->renderFrame(frame, path.read_back ? output.data() : nullptr);
            }
            path.runtime->waitIdle();  // the round's last frame is done on every path
            path.frame_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count() /
                                    double(settings.frames_per_round));
        };
        for (PathRun& run : runs) {  // warm-up: pipelines' first use
            runRound(run, -1);
            run.frame_ms.clear();
        }
        for (long round = 0; round < settings.rounds; ++round)
            for (size_t index = 0; index < runs.size(); ++index)
                runRound(runs[round % 2 == 0 ? index : runs.size() - 1 - index], round);
        for (PathRun& run : runs)
            for (long index = 0; index < settings.profiled_frames && run.read_back; ++index) {
                frame.mode = run.mode;
                run.profiles.emplace_back();
                run.runtime->renderFrameProfiled(frame, output.data(), run.profiles.back());
            }
        printResults(settings, runs);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-frame-paths: %s\n", error.what());
        return 1;
    }
    return 0;
}

// gusuku-frame-paths: the frame's two paths, measured in one run, interleaved. A benchmark, not a test.
//   fenced    host bytes in, the composite read back into host bytes, one slot: the host waits on every frame
//             (0.1.0's only path; tools and tests keep it);
//   resident  host bytes in, no read-back, frames_in_flight slots: the host records frame N+1 while the GPU
//             draws frame N, and waits only when every slot is busy (an app then takes compositeImage()).
// Both on the same in-memory bake set (tests/support/synthetic_bakeset.h) at the given size; rounds alternate
// the two so that a noisy shared machine slows both alike. Prints each path's median milliseconds a frame and
// their ratio.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "gusuku/runtime/runtime.h"
#include "gusuku/tools/command_line.h"
#include "synthetic_bakeset.h"

namespace {

using namespace gusuku;
using Clock = std::chrono::steady_clock;

struct PathRun {
    std::unique_ptr<Runtime> runtime;
    bool read_back = false;
    std::vector<double> frame_ms;  // per round: mean milliseconds a frame
};

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    long width = 1280, height = 720, rounds = 7, frames_per_round = 20;
    try {
        CommandLine line("gusuku-frame-paths", std::vector<std::string>(argv + 1, argv + argc));
        if (line.helpRequested()) {
            std::printf("usage: gusuku-frame-paths [--width W] [--height H] [--rounds N] [--frames N]\n");
            return 0;
        }
        width = long(line.integer("--width", 16, 8192).value_or(width));
        height = long(line.integer("--height", 16, 8192).value_or(height));
        rounds = long(line.integer("--rounds", 1, 1000).value_or(rounds));
        frames_per_round = long(line.integer("--frames", 1, 100000).value_or(frames_per_round));
        line.positionals();
        line.finish();
    } catch (const UsageError& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    try {
        const BakeSetData bake_set = testing::makeSyntheticBakeSet();
        RuntimeOptions options;
        options.frame_width = uint32_t(width);
        options.frame_height = uint32_t(height);
        PathRun fenced, resident;
        options.frames_in_flight = 1;
        fenced.runtime = Runtime::openHeadless(bake_set, options);
        fenced.read_back = true;
        options.frames_in_flight = 2;
        resident.runtime = Runtime::openHeadless(bake_set, options);

        std::vector<uint8_t> camera(size_t(width) * size_t(height) * 4), output(camera.size());
        for (size_t i = 0; i < camera.size(); ++i) camera[i] = i % 4 == 3 ? 255 : uint8_t(i * 7);
        FrameInput frame;
        frame.camera_rgba8 = camera.data();
        const double focal = 0.9 * double(width);
        frame.intrinsics = {focal, focal, width / 2.0, height / 2.0, uint32_t(width), uint32_t(height)};
        frame.weather = Weather::sunny();
        frame.exposure = 0.1f;
        auto runRound = [&](PathRun& path, long round) {
            const Clock::time_point start = Clock::now();
            for (long index = 0; index < frames_per_round; ++index) {
                frame.pose = CameraPose::lookingAt({3.0 + 0.01 * double(index), -12, 3}, {0, 0, 1});
                frame.utc_unix_seconds = testing::syntheticLocalTime(15, 0) + double(round * frames_per_round + index);
                path.runtime->renderFrame(frame, path.read_back ? output.data() : nullptr);
            }
            path.runtime->waitIdle();  // the round's last frame is done on both paths
            path.frame_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count() /
                                    double(frames_per_round));
        };
        runRound(fenced, -1);  // warm-up: pipelines' first use
        runRound(resident, -1);
        fenced.frame_ms.clear();
        resident.frame_ms.clear();
        for (long round = 0; round < rounds; ++round) {
            runRound(round % 2 == 0 ? fenced : resident, round);
            runRound(round % 2 == 0 ? resident : fenced, round);
        }
        const double fenced_ms = median(fenced.frame_ms), resident_ms = median(resident.frame_ms);
        std::printf("frame paths, %ldx%ld, %ld rounds x %ld frames each, interleaved (medians of round means)\n",
                    width, height, rounds, frames_per_round);
        std::printf("  fenced   (read back, 1 slot):   %8.2f ms a frame\n", fenced_ms);
        std::printf("  resident (no read back, 2 slots): %6.2f ms a frame\n", resident_ms);
        std::printf("  resident / fenced: %.3f\n", fenced_ms > 0.0 ? resident_ms / fenced_ms : 0.0);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-frame-paths: %s\n", error.what());
        return 1;
    }
    return 0;
}

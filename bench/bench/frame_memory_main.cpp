// gusuku-frame-memory: the runtime's host memory over many frames. A benchmark, not a test: it renders N frames
// (--frames N, default 10000) headless on a small in-memory bake set (gusuku/synthetic/synthetic_bakeset.h, a box on
// flat ground), through the C++ Runtime as the C API's gusuku_runtime_render does, and prints the process's
// resident set (VmRSS) after a warm-up and at the end, and the growth per frame. tests/test_runtime_memory.cpp
// holds the pass/fail bound; this shows the figure over a longer run.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "gusuku/runtime/runtime.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr long kWarmUpFrames = 50;

long long residentKilobytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
    return -1;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace gusuku;
    long frames = 10000;
    RenderMode mode = RenderMode::kBakedLight;
    try {
        // The tools' one command-line reader: ranges, repeated options and unknown words handled as everywhere.
        CommandLine line("gusuku-frame-memory", std::vector<std::string>(argv + 1, argv + argc));
        if (line.helpRequested()) {
            std::printf("usage: gusuku-frame-memory [--frames N] [--direct-only]\n");
            return 0;
        }
        frames = long(line.integer("--frames", 1, 100000000).value_or(frames));
        if (line.flag("--direct-only")) mode = RenderMode::kDirectOnly;
        line.positionals();
        line.finish();
    } catch (const UsageError& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    if (residentKilobytes() < 0) {
        std::fprintf(stderr, "gusuku-frame-memory: no VmRSS in /proc/self/status on this system\n");
        return 1;
    }
    try {
        RuntimeOptions options;
        options.frame_width = kWidth;
        options.frame_height = kHeight;
        options.shadow_map_size = 512;
        std::unique_ptr<Runtime> runtime = Runtime::openHeadless(testing::makeSyntheticBakeSet(), options);
        std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4), output(camera.size());
        for (size_t i = 0; i < camera.size(); ++i) camera[i] = i % 4 == 3 ? 255 : uint8_t(i * 7);
        FrameInput frame;
        frame.camera_rgba8 = camera.data();
        frame.intrinsics = {120.0, 120.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
        frame.weather = Weather::sunny();
        frame.exposure = 0.1f;
        frame.mode = mode;
        auto render = [&](long index) {
            frame.pose = CameraPose::lookingAt({3.0 + 0.001 * double(index % 100), -12, 3}, {0, 0, 1});
            frame.utc_unix_seconds = testing::syntheticLocalTime(15, 0) + double(index % 3600);
            runtime->renderFrame(frame, output.data());
        };
        const long warm_up = std::min(kWarmUpFrames, frames);
        for (long index = 0; index < warm_up; ++index) render(index);
        const long long after_warm_up = residentKilobytes();
        for (long index = warm_up; index < frames; ++index) render(index);
        const long long at_end = residentKilobytes();
        const long measured = frames - warm_up;
        std::printf("frames %ld (%ld warm-up, %ld measured), %ux%u, mode %s\n", frames, warm_up, measured, kWidth,
                    kHeight, mode == RenderMode::kBakedLight ? "proposed" : "direct-only");
        std::printf("VmRSS after warm-up: %lld KiB\n", after_warm_up);
        std::printf("VmRSS at the end:    %lld KiB\n", at_end);
        std::printf("growth: %lld KiB, %.2f KiB a frame\n", at_end - after_warm_up,
                    measured > 0 ? double(at_end - after_warm_up) / double(measured) : 0.0);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-frame-memory: %s\n", error.what());
        return 1;
    }
    return 0;
}

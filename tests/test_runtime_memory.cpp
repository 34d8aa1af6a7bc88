// The runtime's host memory stays flat over many frames: 500 frames after a warm-up grow the process's resident
// set (VmRSS) by less than 5 MB, headless on lavapipe, in each render mode and colour match the frame loop uses.
// A frame allocates nothing that lives past it, in gusuku or in the driver (runtime_submission.cpp says what
// lavapipe used to keep). Not timed: the figure is resident bytes, not seconds.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr int kWarmUpFrames = 50;
constexpr int kMeasuredFrames = 500;
constexpr int64_t kAllowedGrowthBytes = 5 * 1000 * 1000;

/// VmRSS of this process from /proc/self/status, in bytes (-1 where it cannot be read).
int64_t residentBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6)) * 1024;  // "VmRSS:   1234 kB"
    return -1;
}

struct ModeCase {
    const char* name;
    RenderMode mode;
    ColourMatch colour_match;
};

class RuntimeMemory : public ::testing::TestWithParam<ModeCase> {};

TEST_P(RuntimeMemory, FiveHundredFramesLeaveResidentMemoryFlat) {
    if (residentBytes() < 0) GTEST_SKIP() << "no /proc/self/status VmRSS on this system";
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 512;
    std::unique_ptr<Runtime> runtime = Runtime::openHeadless(makeSyntheticBakeSet(), options);

    std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4), output(camera.size());
    for (size_t index = 0; index < camera.size(); ++index) camera[index] = index % 4 == 3 ? 255 : uint8_t(index * 7);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {120.0, 120.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.weather = Weather::sunny();
    frame.exposure = 0.1f;
    frame.mode = GetParam().mode;
    frame.colour_match = GetParam().colour_match;
    // The camera walks a little and the clock runs, as in an app: the shadow maps and the ground selection are
    // redone now and then, the rest every frame.
    auto render = [&](int index) {
        frame.pose = CameraPose::lookingAt({3.0 + 0.001 * (index % 100), -12, 3}, {0, 0, 1});
        frame.utc_unix_seconds = syntheticLocalTime(15, 0) + index;
        runtime->renderFrame(frame, output.data());
    };
    for (int index = 0; index < kWarmUpFrames; ++index) render(index);
    const int64_t after_warm_up = residentBytes();
    for (int index = 0; index < kMeasuredFrames; ++index) render(kWarmUpFrames + index);
    const int64_t at_end = residentBytes();
    const int64_t growth = at_end - after_warm_up;
    EXPECT_LT(growth, kAllowedGrowthBytes)
        << GetParam().name << ": VmRSS " << after_warm_up << " bytes after " << kWarmUpFrames << " frames, " << at_end
        << " after " << kMeasuredFrames << " more: " << growth / kMeasuredFrames << " bytes a frame";
    RecordProperty("rss_growth_bytes", std::to_string(growth));
}

INSTANTIATE_TEST_SUITE_P(Modes, RuntimeMemory,
                         ::testing::Values(ModeCase{"proposed", RenderMode::kProposed, ColourMatch::kOff},
                                           ModeCase{"proposed_paper", RenderMode::kProposed, ColourMatch::kPaper},
                                           ModeCase{"direct_only", RenderMode::kDirectOnly, ColourMatch::kOff}),
                         [](const ::testing::TestParamInfo<ModeCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace gusuku

// "A frame allocates nothing" (runtime.h), counted: malloc and operator new replaced (tests/allocation), 100
// steady frames after a warm-up, the sun moving a few minutes a frame so the shadow maps, the ground quads and
// the blended slots all change, in each mode and colour match (the synthetic set with a ground albedo, so kGround
// and the default kAuto run the ground statistics); zero allocations by gusuku's side on the calling
// thread. The Vulkan side (loader, validation layer, lavapipe) is not counted: it allocates per recorded command
// by its own design (allocation_counter.h).

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "allocation_counter.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr int kWarmUpFrames = 5;
constexpr int kCountedFrames = 100;
// 100 frames of 4 minutes each: 09:00 to 15:40 local, past the 12:00 slot, so the blended pair changes.
constexpr double kSecondsPerFrame = 240.0;

struct AllocationCase {
    const char* name;
    RenderMode mode;
    ColourMatch colour_match;
    bool read_back;  // the host-bytes path (output bytes) or the GPU-resident one (no output)
};

class RuntimeAllocations : public ::testing::TestWithParam<AllocationCase> {};

TEST_P(RuntimeAllocations, HundredFramesAllocateNothing) {
    const AllocationCase& test_case = GetParam();
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    testing::SyntheticBakeSetOptions bake_options;
    bake_options.ground_albedo = 0.4f;  // so that the ground match (kGround, and kAuto's choice) runs
    std::unique_ptr<Runtime> runtime = Runtime::openHeadless(makeSyntheticBakeSet(bake_options), options);

    std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4), output(camera.size());
    for (size_t index = 0; index < camera.size(); ++index) camera[index] = index % 4 == 3 ? 255 : uint8_t(index * 7);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {120.0, 120.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.weather = Weather::sunny();
    frame.exposure = 0.1f;
    frame.mode = test_case.mode;
    frame.colour_match = test_case.colour_match;
    frame.pose = CameraPose::lookingAt({3.0, -12, 3}, {0, 0, 1});
    // Counted without allocating (the test's own allocations would count too).
    std::pair<int, int> last_slots{-2, -2};
    int slot_changes = 0;
    auto render = [&](int index) {
        frame.pose.position_enu.x = 3.0 + 0.001 * index;
        frame.utc_unix_seconds = syntheticLocalTime(9, 0) + kSecondsPerFrame * index;
        const FrameInfo info = runtime->renderFrame(frame, test_case.read_back ? output.data() : nullptr);
        const std::pair<int, int> slots{info.slot_a, info.slot_b};
        if (slots != last_slots) ++slot_changes;
        last_slots = slots;
    };
    for (int index = 0; index < kWarmUpFrames; ++index) render(index);
    slot_changes = 0;

    testing::startCountingAllocations();
    for (int index = 0; index < kCountedFrames; ++index) render(kWarmUpFrames + index);
    const size_t allocations = testing::stopCountingAllocations();
    EXPECT_EQ(allocations, 0u) << test_case.name << ": " << allocations << " host allocations in " << kCountedFrames
                               << " frames; the first ones:\n"
                               << testing::countedAllocationStacks();
    EXPECT_GE(slot_changes, 2) << "the frames should cross a change of blended slots";
}

INSTANTIATE_TEST_SUITE_P(
    Modes, RuntimeAllocations,
    ::testing::Values(AllocationCase{"proposed", RenderMode::kProposed, ColourMatch::kOff, true},
                      AllocationCase{"proposed_gpu_resident", RenderMode::kProposed, ColourMatch::kOff, false},
                      AllocationCase{"proposed_paper", RenderMode::kProposed, ColourMatch::kPaper, true},
                      AllocationCase{"proposed_preserve", RenderMode::kProposed, ColourMatch::kPreserve, true},
                      AllocationCase{"proposed_ground", RenderMode::kProposed, ColourMatch::kGround, true},
                      AllocationCase{"proposed_auto_gpu_resident", RenderMode::kProposed, ColourMatch::kAuto, false},
                      AllocationCase{"direct_only", RenderMode::kDirectOnly, ColourMatch::kOff, true}),
    [](const ::testing::TestParamInfo<AllocationCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace gusuku

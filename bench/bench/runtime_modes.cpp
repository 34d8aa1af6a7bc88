// The runtime's modes for the bench (see runtime_modes.h).

#include "runtime_modes.h"

#include <stdexcept>

namespace gusuku::bench {

std::vector<RuntimeMode> benchRuntimeModes(bool with_ground_match) {
    std::vector<RuntimeMode> modes;
    modes.push_back({"direct_only", RenderMode::kDirectOnly, ColourMatch::kOff, false, false});
    // The proposed method as the runtime ships it: the camera's exposure given, no colour match.
    modes.push_back({"proposed", RenderMode::kProposed, ColourMatch::kOff, true, true});
    modes.push_back({"proposed_no_slot_blend", RenderMode::kProposed, ColourMatch::kOff, false, true});
    modes.push_back({"proposed_no_ground_ratio", RenderMode::kProposed, ColourMatch::kOff, true, false});
    modes.push_back({"proposed_preserve_match", RenderMode::kProposed, ColourMatch::kPreserve, true, true});
    // The ground match: the camera's ground against the bake set's prediction (needs ground albedo).
    if (with_ground_match)
        modes.push_back({"proposed_ground_match", RenderMode::kProposed, ColourMatch::kGround, true, true});
    modes.push_back({"proposed_paper_match", RenderMode::kProposed, ColourMatch::kPaper, true, true});
    return modes;
}

RuntimeMode runtimeModeNamed(const std::string& name) {
    for (const RuntimeMode& mode : benchRuntimeModes(true))
        if (mode.name == name) return mode;
    throw std::invalid_argument("no runtime mode named " + name);
}

FrameInput frameInputFor(const RuntimeMode& mode, const std::vector<uint8_t>& camera_rgba8,
                         const CameraIntrinsics& intrinsics, const CameraPose& pose, double utc_seconds,
                         float cloud_cover, float exposure) {
    FrameInput frame;
    frame.camera_rgba8 = camera_rgba8.data();
    frame.intrinsics = intrinsics;
    frame.pose = pose;
    frame.utc_unix_seconds = utc_seconds;
    frame.weather.cloud_cover = cloud_cover;
    frame.exposure = exposure;
    frame.mode = mode.mode;
    frame.colour_match = mode.colour_match;
    frame.blend_slots = mode.blend_slots;
    frame.ground_ratio = mode.ground_ratio;
    return frame;
}

std::vector<uint8_t> steadyComposite(Runtime& runtime, const FrameInput& frame, uint32_t frames) {
    std::vector<uint8_t> composite(size_t(frame.intrinsics.width) * frame.intrinsics.height * 4);
    runtime.resetColourStatistics();
    for (uint32_t index = 0; index < std::max(frames, 1u); ++index) runtime.renderFrame(frame, composite.data());
    return composite;
}

std::vector<uint8_t> resizeNearest(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height,
                                   uint32_t new_width, uint32_t new_height) {
    std::vector<uint8_t> resized(size_t(new_width) * new_height * 4);
    for (uint32_t y = 0; y < new_height; ++y) {
        const uint32_t source_y = uint32_t((uint64_t(y) * height) / new_height);
        for (uint32_t x = 0; x < new_width; ++x) {
            const uint32_t source_x = uint32_t((uint64_t(x) * width) / new_width);
            for (int channel = 0; channel < 4; ++channel)
                resized[(size_t(y) * new_width + x) * 4 + channel] =
                    rgba8[(size_t(source_y) * width + source_x) * 4 + channel];
        }
    }
    return resized;
}

}  // namespace gusuku::bench

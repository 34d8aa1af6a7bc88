// The runtime's modes for the bench (see runtime_modes.h).

#include "runtime_modes.h"

#include <cmath>
#include <stdexcept>

#include "gusuku/maths/colour.h"

namespace gusuku::bench {

std::vector<RuntimeMode> benchRuntimeModes(bool with_ground_match) {
    std::vector<RuntimeMode> modes;
    modes.push_back({"direct_only", RenderMode::kDirectOnly, ColourMatch::kOff, false, false});
    // The proposed method as the runtime ships it: the camera's exposure given, no colour match.
    modes.push_back({"proposed", RenderMode::kBakedLight, ColourMatch::kOff, true, true});
    modes.push_back({"proposed_no_slot_blend", RenderMode::kBakedLight, ColourMatch::kOff, false, true});
    modes.push_back({"proposed_no_ground_ratio", RenderMode::kBakedLight, ColourMatch::kOff, true, false});
    modes.push_back({"proposed_preserve_match", RenderMode::kBakedLight, ColourMatch::kPreserve, true, true});
    // The ground match: the camera's ground against the bake set's prediction (needs ground albedo).
    if (with_ground_match)
        modes.push_back({"proposed_ground_match", RenderMode::kBakedLight, ColourMatch::kGround, true, true});
    modes.push_back({"proposed_paper_match", RenderMode::kBakedLight, ColourMatch::kReinhard, true, true});
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

std::vector<uint8_t> averageDown2x(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height) {
    if (rgba8.size() != size_t(width) * height * 16)
        throw std::invalid_argument("averageDown2x: the frame is not 2 width x 2 height RGBA8");
    std::vector<uint8_t> averaged(size_t(width) * height * 4);
    const size_t source_row = size_t(width) * 2 * 4;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t corner = size_t(2 * y) * source_row + size_t(2 * x) * 4;
            const size_t block[4] = {corner, corner + 4, corner + source_row, corner + source_row + 4};
            uint8_t* out = &averaged[(size_t(y) * width + x) * 4];
            for (int channel = 0; channel < 3; ++channel) {
                double linear = 0.0;
                for (size_t at : block) linear += srgbDecode(double(rgba8[at + channel]) / 255.0);
                out[channel] = uint8_t(std::lround(255.0 * srgbEncode(linear / 4.0)));
            }
            unsigned alpha = 0;
            for (size_t at : block) alpha += rgba8[at + 3];
            out[3] = uint8_t((alpha + 2) / 4);
        }
    return averaged;
}

}  // namespace gusuku::bench

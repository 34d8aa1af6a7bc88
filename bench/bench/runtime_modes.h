#pragma once
// The runtime's modes the bench compares, and how it drives them: direct-only (what AR apps draw today), the
// proposed method, and the proposed method with one part off at a time (slot blend, ground ratio, colour match).

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/runtime/runtime.h"

namespace gusuku::bench {

struct RuntimeMode {
    std::string name;  ///< "direct_only", "proposed", "proposed_no_slot_blend", ...
    RenderMode mode = RenderMode::kBakedLight;
    ColourMatch colour_match = ColourMatch::kPreserve;
    bool blend_slots = true;
    bool ground_ratio = true;
};

/// direct_only, proposed (as shipped: exposure given, no colour match), proposed_no_slot_blend,
/// proposed_no_ground_ratio, proposed_preserve_match (the chroma-keeping match on), proposed_ground_match (the
/// ground match on; only with_ground_match: the bake set has the ground albedo it needs, so a bench of an older
/// set runs without that mode), proposed_paper_match (the paper's Reinhard transfer on).
std::vector<RuntimeMode> benchRuntimeModes(bool with_ground_match);
/// The mode of that name among every mode benchRuntimeModes knows (std::invalid_argument when none).
RuntimeMode runtimeModeNamed(const std::string& name);

/// The frame input for a mode: the camera bytes (kept by the caller), view, instant, weather and exposure.
FrameInput frameInputFor(const RuntimeMode& mode, const std::vector<uint8_t>& camera_rgba8,
                         const CameraIntrinsics& intrinsics, const CameraPose& pose, double utc_seconds,
                         float cloud_cover, float exposure);

/// The composite of a mode as a steady camera feed would get it: the colour statistics forgotten, then
/// `frames` frames of the same input (the statistics smooth over frames), the last one returned.
std::vector<uint8_t> steadyComposite(Runtime& runtime, const FrameInput& frame, uint32_t frames = 16);

/// Nearest-neighbour resize of an RGBA8 frame (the accuracy-size camera frame shown at the timing sizes: the
/// runtime's cost depends on the pixels it touches, which the resize keeps where they were).
std::vector<uint8_t> resizeNearest(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height,
                                   uint32_t new_width, uint32_t new_height);

/// An RGBA8 frame of 2 width x 2 height averaged down to width x height: each pixel the mean of its 2 x 2 block
/// in linear light (sRGB decoded, averaged, encoded, rounded; alpha averaged as it is). A frame the runtime drew
/// at twice the size, averaged so, has 4 times the samples a pixel (16 at msaa 4) and 4 shadings: against the
/// truth it reads how right the light is with the pixel sampling's share mostly gone.
std::vector<uint8_t> averageDown2x(const std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height);

}  // namespace gusuku::bench

#pragma once
// gusuku-view --render: a session composited headless, frame by frame, into a folder of PNG frames (no window,
// no windowing library: the runtime on a headless device, as gusuku-render draws one frame).

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"
#include "view_session.h"

namespace gusuku::view {

struct SessionRenderOptions {
    std::string mode = "proposed";  ///< a gusuku-bench mode (bench/bench/runtime_modes.h), as gusuku-view's --mode
    /// Each output frame is the composite with the direct-only frame (what AR apps draw today) to its right.
    bool beside_direct_only = false;
    uint32_t msaa_samples = RuntimeOptions{}.msaa_samples;
    bool show_progress = true;  ///< the progress bar on stderr
};

/// True when `out` names an animated PNG (it ends in .png) rather than a folder of frames.
bool isAnimatedOutput(const std::string& out);

/// The name of output frame `index` inside the output folder: "frame_000000.png".
std::string outputFrameName(size_t index);

/// Throws InputError(out, option, ...) when `out` is, lies inside or holds one of `inputs` (empty ones skipped).
void refuseOutputOverInputs(const std::string& out, const std::string& option, const std::vector<std::string>& inputs);

/// Throws InputError(out_folder, "--render", ...) when the output folder would overwrite what the render reads
/// (it is or lies inside the session or the bake set, or holds them) or something else than a previous render
/// (an existing non-empty folder holding anything but frame_*.png; for an animated PNG, anything but a file).
/// Touches nothing.
void refuseUnsafeRenderFolder(const std::string& out_folder, const std::string& session_folder,
                              const std::string& bake_set_folder);

/// Composites every frame of `session` on `bake_set` in options.mode (camera, pose, instant, cloud cover and
/// exposure from its row; a row without exposure gets 1, the colour match modes replace it), one runtime for all
/// frames as a camera feed would (the colour statistics carry over) and writes them as out_folder/frame_NNNNNN.png,
/// or, when out_folder ends in .png, as that one looping animated PNG (view_apng.h). The frames go into a temporary
/// sibling folder renamed into place (or assembled) at the end: a bad frame image (InputError) or an interruption
/// leaves no output half-written. Returns the number of frames written.
size_t renderSession(const GpuDevice& gpu, const BakeSetData& bake_set, const Session& session,
                     const std::string& out_folder, const SessionRenderOptions& options);

}  // namespace gusuku::view

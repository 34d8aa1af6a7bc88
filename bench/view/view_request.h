#pragma once
// What one gusuku-view run is asked to do, read from its command line (gusuku/tools/command_line.h), and its one
// option table (gusuku/tools/option_table.h: --help and docs/view.md's table).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/runtime/runtime.h"
#include "gusuku/tools/option_table.h"

namespace gusuku::view {

struct ViewRequest {
    std::string bake_set;                  ///< a bake set folder, or a runtime pack folder (holding pack.bin)
    std::string camera = "sample";         ///< "sample" (the site path-traced without the building) or a photo
    std::optional<std::string> site_json;  ///< for --camera sample; default: the site the manifest names
    uint32_t width = 960, height = 540;    ///< the frame the runtime draws, and the window's first size
    glm::dvec3 position_enu{0.0, -25.0, 6.0};
    glm::dvec3 look_at_enu{0.0, 0.0, 2.0};
    double horizontal_fov_deg = 60.0;
    std::optional<std::string> time_iso;   ///< default: the bake date at 12:00 on the site's clock
    float cloud_cover = 0.0f;
    std::string mode = "proposed";         ///< a gusuku-bench mode name (bench/bench/runtime_modes.h)
    std::optional<float> exposure;         ///< default: middle grey of the first sample frame, else 1
    uint32_t camera_samples = 16;          ///< path-traced samples a pixel of the sample background
    /// The runtime's own defaults (RuntimeOptions), never restated here.
    uint32_t msaa_samples = RuntimeOptions{}.msaa_samples;
    std::optional<std::string> actions;    ///< scripted input, ';'-separated (view_script.h); the tests drive it so
    /// Headless (view_session_command.h): --render composites a session into PNG frames, --sample-session
    /// path-traces the sample walk into a session folder; neither opens a window.
    std::optional<std::string> render_out;
    std::optional<std::string> sample_session_out;
    bool beside_direct_only = false;
    uint32_t walk_frames = 28, walk_width = 256, walk_height = 144, walk_samples = 8;  ///< SampleWalkOptions'
    bool help = false;
};

/// The sides --size accepts, pixels (gusuku-render's).
inline constexpr unsigned kMinFrameSide = 16, kMaxFrameSide = 4096;

CommandHelp viewHelp();

/// Parses the command line; UsageError / OptionValueError (gusuku/tools/command_line.h) on a bad one.
ViewRequest parseViewRequest(const std::vector<std::string>& args);

/// "WxH" with each side in [minimum, maximum], or nullopt.
std::optional<std::pair<uint32_t, uint32_t>> parseSize(const std::string& text, unsigned minimum, unsigned maximum);

}  // namespace gusuku::view

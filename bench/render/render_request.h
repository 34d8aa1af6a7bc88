#pragma once
// What one gusuku-render run is asked to do, read from its command line (gusuku/tools/command_line.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/runtime/runtime.h"
#include "gusuku/tools/option_table.h"

namespace gusuku::render_cli {

struct RenderRequest {
    std::string bake_set;                   ///< the bake set folder
    std::string output_png;                 ///< the composite
    std::string camera = "sample";          ///< "sample" (path-traced from the site) or an image (any bit depth)
    std::optional<std::string> site_json;   ///< for --camera sample; default: the site the manifest names
    uint32_t width = RuntimeOptions{}.frame_width, height = RuntimeOptions{}.frame_height;
    glm::dvec3 position_enu{0.0, -25.0, 6.0};
    glm::dvec3 look_at_enu{0.0, 0.0, 2.0};
    double horizontal_fov_deg = 60.0;
    std::optional<std::string> time_iso;    ///< default: the bake date at 12:00 on the site's clock
    float cloud_cover = 0.0f;
    ColourMatch colour_match = ColourMatch::kOff;
    std::optional<std::string> direct_only_png;
    std::optional<std::string> camera_png;
    uint32_t camera_samples = 64;
    std::optional<float> exposure;          ///< default: middle grey of the sample camera frame, else 1
    std::optional<float> ground_change_threshold;  ///< RuntimeOptions::ground_change_threshold
    /// The runtime's own defaults (RuntimeOptions), never restated here, so that the frame times the tool prints
    /// are the runtime's as an app gets them (tests/test_bench_tool_defaults.cpp pins it).
    uint32_t msaa_samples = RuntimeOptions{}.msaa_samples;
    float max_anisotropy = RuntimeOptions{}.max_anisotropy;  ///< the tool's device enables samplerAnisotropy
    uint32_t timed_frames = 20;
    uint32_t warm_up_frames = 3;
    bool help = false;
};

/// The exposure of an IMAGE camera frame when --exposure is not given (a sample frame is exposed to middle grey).
inline constexpr float kImageCameraExposure = 1.0f;
/// The sides --size accepts, pixels.
inline constexpr unsigned kMinFrameSide = 16, kMaxFrameSide = 4096;

/// The command's option table: its --help (formatHelp), and what docs/runtime.md's table of gusuku-render must say.
CommandHelp renderHelp();

/// Parses the command line; UsageError / OptionValueError (gusuku/tools/command_line.h) on a bad one.
RenderRequest parseRenderRequest(const std::vector<std::string>& args);

}  // namespace gusuku::render_cli

// gusuku-render's command line (see render_request.h).

#include "render_request.h"

#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "enu_point_option.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"

namespace gusuku::render_cli {

namespace {

// --colour-match's choices, in the order of their names; "paper" (ColourMatch's old name) stays accepted so that
// existing scripts keep working.
constexpr ColourMatch kColourMatches[] = {ColourMatch::kOff, ColourMatch::kReinhard, ColourMatch::kPreserve,
                                          ColourMatch::kGround, ColourMatch::kReinhard};
constexpr const char* kColourMatchNames[] = {"off", "reinhard", "preserve", "ground", "paper"};

std::string colourMatchName(ColourMatch match) {
    for (size_t index = 0; index < std::size(kColourMatches); ++index)
        if (kColourMatches[index] == match) return kColourMatchNames[index];
    return "?";
}

std::string weatherName(float cloud_cover) {
    if (cloud_cover == 0.0f) return "sunny";
    if (cloud_cover == 1.0f) return "overcast";
    return defaultNumber(cloud_cover);
}

}  // namespace

CommandHelp renderHelp() {
    const RenderRequest defaults;
    CommandHelp help;
    help.usage = "usage: gusuku-render BAKESET -o COMPOSITE.png [options]";
    help.description =
        "Draws the baked building into a camera frame with gusuku's runtime (baked light, real-time sun and shadow,\n"
        "the ground ratio, the colour match), writes the composite as an sRGB PNG, and prints the frame time of each\n"
        "pass (profiling mode: each pass submitted alone) and of the whole frame (one submission, fence-timed).";
    help.options = {
        {"--output", "-o", "PNG", "the composite", ""},
        {"--camera", "", "sample|IMAGE",
         "the camera frame: `sample` path-traces the bake's site without the building from the pose, or an image, "
         "converted to the runtime's 8-bit sRGB frame: 8- and 16-bit files as sRGB-encoded, float files (.exr, "
         ".hdr) as linear, grey as RGB; 8 to 8192 pixels a side",
         defaults.camera},
        {"--site", "", "SITE.json", "the site for --camera sample", "the site.json the bake set was baked from"},
        {"--size", "", "WxH", "frame size, pixels, each side in [" + std::to_string(kMinFrameSide) + ", " +
                                  std::to_string(kMaxFrameSide) + "] (an IMAGE gives its own)",
         std::to_string(defaults.width) + "x" + std::to_string(defaults.height)},
        {"--position", "", "E,N,U", "camera centre, site ENU metres", enuPointText(defaults.position_enu)},
        {"--look-at", "", "E,N,U", "the point at the image centre", enuPointText(defaults.look_at_enu)},
        {"--fov", "", "DEG", "horizontal field of view, (1, 170) degrees", defaultNumber(defaults.horizontal_fov_deg)},
        {"--time", "", "ISO8601", "the instant, with its offset", "the bake date, 12:00 site clock"},
        {"--weather", "", "W", "sunny, overcast, or a cloud cover in [0, 1]", weatherName(defaults.cloud_cover)},
        {"--colour-match", "", "M",
         "off, reinhard, preserve or ground (off: the camera's exposure is known; ground needs a bake set with ground "
         "albedo; paper: reinhard's old spelling)",
         colourMatchName(defaults.colour_match)},
        {"--exposure", "", "X", "display value per unit radiance",
         "the sample frame's middle grey, or " + defaultNumber(kImageCameraExposure) + " for an IMAGE"},
        {"--samples", "", "N", "path-traced samples per pixel of the sample camera frame",
         std::to_string(defaults.camera_samples)},
        {"--frames", "", "N", "frames timed after " + std::to_string(defaults.warm_up_frames) + " warm-up frames",
         std::to_string(defaults.timed_frames)},
        {"--ground-change", "", "R",
         "relative change of the baked ground light below which the building is taken to change nothing there "
         "(RuntimeOptions::ground_change_threshold)",
         "1/" + defaultNumber(1.0 / double(RuntimeOptions{}.ground_change_threshold))},
        {"--msaa", "", "N", "samples a pixel (RuntimeOptions::msaa_samples; 1 turns it off)",
         std::to_string(defaults.msaa_samples)},
        {"--anisotropy", "", "N",
         "texture anisotropy, [1, 16] (RuntimeOptions::max_anisotropy, clamped to the device's)",
         defaultNumber(defaults.max_anisotropy)},
        {"--direct-only", "", "PNG", "also write the direct-only frame (what AR apps draw today)", ""},
        {"--camera-out", "", "PNG", "also write the camera frame the composite was drawn into", ""},
    };
    help.notes = "Exit status: 0 ok, 1 bad input, 2 bad usage.";
    return help;
}

RenderRequest parseRenderRequest(const std::vector<std::string>& args) {
    RenderRequest request;
    CommandLine line("gusuku-render", args);
    line.useOptionTable(renderHelp().options);
    if (line.helpRequested()) {
        request.help = true;
        return request;
    }
    const std::optional<std::string> output = line.text("--output", "-o");
    if (const auto camera = line.text("--camera")) request.camera = *camera;
    request.site_json = line.text("--site");
    if (const auto size = line.text("--size")) {
        unsigned width = 0, height = 0;
        char separator = 0;
        std::istringstream stream(*size);
        stream >> width >> separator >> height;
        if (!stream || separator != 'x' || !stream.eof() || width < kMinFrameSide || height < kMinFrameSide ||
            width > kMaxFrameSide || height > kMaxFrameSide)
            line.failValue("--size", "'" + *size + "' is not WxH with each side in [" + std::to_string(kMinFrameSide) +
                                         ", " + std::to_string(kMaxFrameSide) + "]");
        request.width = width;
        request.height = height;
    }
    if (const auto position = line.text("--position"))
        request.position_enu = parseEnuPoint(line, "--position", *position);
    if (const auto target = line.text("--look-at")) request.look_at_enu = parseEnuPoint(line, "--look-at", *target);
    request.horizontal_fov_deg = line.number("--fov", 1.0, 170.0).value_or(request.horizontal_fov_deg);
    request.time_iso = line.text("--time");
    if (const auto weather = line.text("--weather")) {
        if (*weather == "sunny") {
            request.cloud_cover = 0.0f;
        } else if (*weather == "overcast") {
            request.cloud_cover = 1.0f;
        } else {
            const std::optional<double> cover = parseDecimal(*weather);  // decimal only: "0x1" is no cover
            if (!cover || !(*cover >= 0.0 && *cover <= 1.0))
                line.failValue("--weather", quotedForMessage(*weather) +
                                                " is not sunny, overcast or a cloud cover in [0, 1]");
            request.cloud_cover = float(*cover);
        }
    }
    if (const auto mode = line.choice("--colour-match", {kColourMatchNames[0], kColourMatchNames[1],
                                                         kColourMatchNames[2], kColourMatchNames[3],
                                                         kColourMatchNames[4]}))
        request.colour_match = kColourMatches[*mode];
    if (const auto exposure = line.number("--exposure", 1e-9, 1e9)) request.exposure = float(*exposure);
    request.camera_samples = uint32_t(line.integer("--samples", 1, 65536).value_or(request.camera_samples));
    if (const auto threshold = line.number("--ground-change", 0.0, 1.0)) request.ground_change_threshold = float(*threshold);
    if (const auto msaa = line.integer("--msaa", 1, 64)) request.msaa_samples = uint32_t(*msaa);
    if (const auto anisotropy = line.integer("--anisotropy", 1, 16)) request.max_anisotropy = float(*anisotropy);
    request.timed_frames = uint32_t(line.integer("--frames", 1, 100000).value_or(request.timed_frames));
    request.direct_only_png = line.text("--direct-only");
    request.camera_png = line.text("--camera-out");
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() != 1) line.fail("needs exactly one BAKESET folder (see --help)");
    if (!output) line.fail("needs -o COMPOSITE.png (see --help)");
    request.bake_set = positionals[0];
    request.output_png = *output;
    return request;
}

}  // namespace gusuku::render_cli

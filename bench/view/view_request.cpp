// gusuku-view's command line (see view_request.h).

#include "view_request.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "enu_point_option.h"
#include "gusuku/tools/command_line.h"
#include "view_modes.h"

namespace gusuku::view {

namespace {

std::string modeList() {
    std::string list;
    for (const char* name : kViewModeNames) list += (list.empty() ? "" : ", ") + std::string(name);
    return list;
}

}  // namespace

std::optional<std::pair<uint32_t, uint32_t>> parseSize(const std::string& text, unsigned minimum, unsigned maximum) {
    unsigned width = 0, height = 0;
    char separator = 0;
    std::istringstream stream(text);
    stream >> width >> separator >> height;
    if (!stream || separator != 'x' || !stream.eof() || width < minimum || height < minimum || width > maximum ||
        height > maximum)
        return std::nullopt;
    return std::make_pair(uint32_t(width), uint32_t(height));
}

CommandHelp viewHelp() {
    const ViewRequest defaults;
    CommandHelp help;
    help.usage = "usage: gusuku-view BAKESET_OR_PACK [options]\n"
                 "       gusuku-view SESSION [options]   (plays a recorded session, docs/session.md)\n"
                 "       gusuku-view --render OUT SESSION_OR_BAKESET [options]   (headless)\n"
                 "       gusuku-view --sample-session DIR BAKESET [options]      (headless)";
    help.description =
        "Opens a window and draws the runtime's composite of the baked building over a camera background, on the\n"
        "GPU-resident path an app runs (bench/view/view_frame_loop.cpp). Mouse: left drag orbits about the point\n"
        "looked at, the wheel walks towards it; W A S D walk; , and . move the hour by 15 minutes; C steps the cloud\n"
        "cover; M steps the mode; X turns multisampling on or off; R re-traces the background; O hides the overlay;\n"
        "F12 writes a screenshot; Esc closes. The overlay and the title show the sun, the slot weights, the weather\n"
        "and the frame time per pass.";
    help.options = {
        {"--camera", "", "sample|PHOTO",
         "the background: `sample` path-traces the bake's site without the building from the view (cached, traced "
         "again when the view stops moving), or a photo taken from --position towards --look-at (its own size)",
         defaults.camera},
        {"--site", "", "SITE.json", "the site for --camera sample", "the site.json the bake set was baked from"},
        {"--size", "", "WxH",
         "the frame the runtime draws and the window's first size, each side in [" + std::to_string(kMinFrameSide) +
             ", " + std::to_string(kMaxFrameSide) + "]; the window scales it to fit",
         std::to_string(defaults.width) + "x" + std::to_string(defaults.height)},
        {"--position", "", "E,N,U", "camera centre, site ENU metres", render_cli::enuPointText(defaults.position_enu)},
        {"--look-at", "", "E,N,U", "the point at the image centre (the orbit's centre)",
         render_cli::enuPointText(defaults.look_at_enu)},
        {"--fov", "", "DEG", "horizontal field of view, (1, 170) degrees", defaultNumber(defaults.horizontal_fov_deg)},
        {"--time", "", "ISO8601", "the instant, with its offset", "the bake date, 12:00 site clock"},
        {"--weather", "", "C", "the cloud cover in [0, 1] (0 sunny, 1 overcast)", defaultNumber(defaults.cloud_cover)},
        {"--mode", "", "M", "the frame: " + modeList() + " (gusuku-bench's modes)", defaults.mode},
        {"--exposure", "", "X", "display value per unit radiance",
         "the first sample frame's middle grey, or 1 for a PHOTO"},
        {"--samples", "", "N", "path-traced samples per pixel of the sample background",
         std::to_string(defaults.camera_samples)},
        {"--msaa", "", "N", "samples a pixel (RuntimeOptions::msaa_samples; 1 turns it off; X toggles it)",
         std::to_string(defaults.msaa_samples)},
        {"--actions", "", "LIST",
         "scripted input, ';'-separated, run in order then the window closes: orbit DEG, pitch DEG, walk M, hour H, "
         "time ISO8601, weather C, mode M, msaa N, frame N, frames N, resize WxH, screenshot PNG, quit",
         ""},
        {"--render", "", "OUT",
         "headless, no window: composite the session SESSION (a folder with session.json, docs/session.md), or the "
         "sample walk of a BAKESET, in --mode into OUT, a folder of PNG frames frame_000000.png, ..., or OUT.png, "
         "one animated PNG at 4 frames a second; with a progress bar; then exit",
         ""},
        {"--beside-direct-only", "", "", "with --render: each frame is the composite with direct-only to its right",
         ""},
        {"--sample-session", "", "DIR",
         "headless: path-trace the sample walk (around the building, 08:00 to 17:00 of the bake day, a cloud passing "
         "after noon) of BAKESET's site into the session folder DIR; then exit",
         ""},
        {"--walk-frames", "", "N", "frames of the sample walk", std::to_string(defaults.walk_frames)},
        {"--walk-size", "", "WxH", "the sample walk's frame size",
         std::to_string(defaults.walk_width) + "x" + std::to_string(defaults.walk_height)},
        {"--walk-samples", "", "N", "path-traced samples a pixel of the sample walk's frames",
         std::to_string(defaults.walk_samples)},
    };
    help.notes =
        "Exit status: 0 ok, 1 bad input or a Vulkan failure, 2 bad usage. GUSUKU_VALIDATION=1 turns on the Khronos\n"
        "validation layer (each message printed as 'gusuku-view: Vulkan validation: ...'); GUSUKU_DEVICE picks the\n"
        "device by name.";
    return help;
}

ViewRequest parseViewRequest(const std::vector<std::string>& args) {
    ViewRequest request;
    CommandLine line("gusuku-view", args);
    line.useOptionTable(viewHelp().options);
    if (line.helpRequested()) {
        request.help = true;
        return request;
    }
    if (const auto camera = line.text("--camera")) request.camera = *camera;
    request.site_json = line.text("--site");
    if (const auto size = line.text("--size")) {
        const auto parsed = parseSize(*size, kMinFrameSide, kMaxFrameSide);
        if (!parsed)
            line.failValue("--size", "'" + *size + "' is not WxH with each side in [" + std::to_string(kMinFrameSide) +
                                         ", " + std::to_string(kMaxFrameSide) + "]");
        request.width = parsed->first;
        request.height = parsed->second;
    }
    if (const auto position = line.text("--position"))
        request.position_enu = render_cli::parseEnuPoint(line, "--position", *position);
    if (const auto target = line.text("--look-at"))
        request.look_at_enu = render_cli::parseEnuPoint(line, "--look-at", *target);
    if (glm::length(request.look_at_enu - request.position_enu) < 1e-3)
        line.failValue("--look-at", "the same point as --position");
    request.horizontal_fov_deg = line.number("--fov", 1.0, 170.0).value_or(request.horizontal_fov_deg);
    request.time_iso = line.text("--time");
    request.cloud_cover = float(line.number("--weather", 0.0, 1.0).value_or(request.cloud_cover));
    if (const auto mode = line.text("--mode")) {
        if (!viewModeIndex(*mode)) line.failValue("--mode", quotedForMessage(*mode) + " is not one of " + modeList());
        request.mode = *mode;
    }
    if (const auto exposure = line.number("--exposure", 1e-9, 1e9)) request.exposure = float(*exposure);
    request.camera_samples = uint32_t(line.integer("--samples", 1, 65536).value_or(request.camera_samples));
    if (const auto msaa = line.integer("--msaa", 1, 64)) request.msaa_samples = uint32_t(*msaa);
    request.actions = line.text("--actions");
    request.render_out = line.text("--render");
    request.beside_direct_only = line.flag("--beside-direct-only");
    request.sample_session_out = line.text("--sample-session");
    request.walk_frames = uint32_t(line.integer("--walk-frames", 1, 10000).value_or(request.walk_frames));
    if (const auto size = line.text("--walk-size")) {
        const auto parsed = parseSize(*size, kMinFrameSide, kMaxFrameSide);
        if (!parsed) line.failValue("--walk-size", "'" + *size + "' is not WxH with each side in [16, 4096]");
        request.walk_width = parsed->first;
        request.walk_height = parsed->second;
    }
    request.walk_samples = uint32_t(line.integer("--walk-samples", 1, 65536).value_or(request.walk_samples));
    if (request.render_out && request.sample_session_out)
        line.fail("--render and --sample-session are two runs: give one");
    const std::vector<std::string> positionals = line.positionals();
    line.finish();
    if (positionals.size() != 1)
        line.fail(request.render_out ? "--render needs exactly one SESSION or BAKESET folder (see --help)"
                                     : "needs exactly one BAKESET_OR_PACK folder (see --help)");
    request.bake_set = positionals[0];
    return request;
}

}  // namespace gusuku::view

// gusuku-render's command line (see render_request.h).

#include "render_request.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "gusuku/tools/command_line.h"

namespace gusuku::render_cli {

const char* const kRenderUsage =
    "usage: gusuku-render BAKESET -o COMPOSITE.png [options]\n"
    "\n"
    "Draws the baked building into a camera frame with gusuku's runtime (baked light, real-time sun and shadow,\n"
    "the ground ratio, the colour match), writes the composite as an sRGB PNG, and prints the frame time of each\n"
    "pass (profiling mode: each pass submitted alone) and of the whole frame (one submission, fence-timed).\n"
    "\n"
    "  --camera sample|IMAGE  the camera frame: `sample` path-traces the bake's site without the building from the\n"
    "                         pose (default), or an image, converted to the runtime's 8-bit sRGB frame: 8- and\n"
    "                         16-bit files as sRGB-encoded, float files (.exr, .hdr) as linear, grey as RGB;\n"
    "                         8 to 8192 pixels a side\n"
    "  --site SITE.json       the site for --camera sample (default: the site.json the bake set was baked from)\n"
    "  --size WxH             frame size, pixels (default 1280x720; an IMAGE gives its own)\n"
    "  --position E,N,U       camera centre, site ENU metres (default 0,-25,6)\n"
    "  --look-at E,N,U        the point at the image centre (default 0,0,2)\n"
    "  --fov DEG              horizontal field of view, (1, 170) degrees (default 60)\n"
    "  --time ISO8601         the instant, with its offset (default: the bake date, 12:00 site clock)\n"
    "  --weather W            sunny, overcast, or a cloud cover in [0, 1] (default sunny)\n"
    "  --colour-match M       off, reinhard, preserve or ground (default off: the camera's exposure is known;\n"
    "                         ground needs a bake set with ground albedo; paper: reinhard's old spelling)\n"
    "  --exposure X           display value per unit radiance (default: the sample frame's middle grey, or 1)\n"
    "  --samples N            path-traced samples per pixel of the sample camera frame (default 64)\n"
    "  --frames N             frames timed after 3 warm-up frames (default 20)\n"
    "  --ground-change R      relative change of the baked ground light below which the building is taken to\n"
    "                         change nothing there (default 1/255; see RuntimeOptions::ground_change_threshold)\n"
    "  --msaa N               samples a pixel (RuntimeOptions::msaa_samples; default 4, 1 turns it off)\n"
    "  --anisotropy N         texture anisotropy, [1, 16] (RuntimeOptions::max_anisotropy; default 16, clamped\n"
    "                         to the device's)\n"
    "  --direct-only PNG      also write the direct-only frame (what AR apps draw today)\n"
    "  --camera-out PNG       also write the camera frame the composite was drawn into\n"
    "\n"
    "Exit status: 0 ok, 1 bad input, 2 bad usage.\n";

namespace {

glm::dvec3 parseTriple(const CommandLine& line, const std::string& option, const std::string& text) {
    std::istringstream stream(text);
    glm::dvec3 value;
    char comma1 = 0, comma2 = 0;
    stream >> value.x >> comma1 >> value.y >> comma2 >> value.z;
    if (!stream || comma1 != ',' || comma2 != ',' || !stream.eof() || !std::isfinite(value.x) ||
        !std::isfinite(value.y) || !std::isfinite(value.z) || glm::length(value) > 1e5)
        line.failValue(option, "'" + text + "' is not E,N,U in metres (three finite numbers within 100 km)");
    return value;
}

}  // namespace

RenderRequest parseRenderRequest(const std::vector<std::string>& args) {
    RenderRequest request;
    CommandLine line("gusuku-render", args);
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
        if (!stream || separator != 'x' || !stream.eof() || width < 16 || height < 16 || width > 4096 ||
            height > 4096)
            line.failValue("--size", "'" + *size + "' is not WxH with each side in [16, 4096]");
        request.width = width;
        request.height = height;
    }
    if (const auto position = line.text("--position")) request.position_enu = parseTriple(line, "--position", *position);
    if (const auto target = line.text("--look-at")) request.look_at_enu = parseTriple(line, "--look-at", *target);
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
    // "paper" (ColourMatch's old name) stays accepted so that existing scripts keep working.
    if (const auto mode = line.choice("--colour-match", {"off", "reinhard", "preserve", "ground", "paper"})) {
        const ColourMatch modes[5] = {ColourMatch::kOff, ColourMatch::kReinhard, ColourMatch::kPreserve,
                                      ColourMatch::kGround, ColourMatch::kReinhard};
        request.colour_match = modes[*mode];
    }
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

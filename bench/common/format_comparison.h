#pragma once
// What the format tools (gusuku-lightmap-formats, gusuku-texture-formats) share: their command line's points and
// frame size, the default view of the building, the exposure of their mid-grey camera frame, and the pixels a
// composite changes. One copy, so both tools compare formats the same way.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::bench_common {

/// The tools' command line: one bake set folder and options that each take a value. `read_option(option, value)`
/// reads an option it knows and returns true, else false; an option without a value, an unknown argument or a
/// second folder throws std::invalid_argument, and so does no folder (with `usage` as the message).
std::string readFolderAndOptions(int argc, char** argv, const char* usage,
                                 const std::function<bool(const std::string& option, const char* value)>& read_option);

/// "E,N,U" as a point; std::invalid_argument "OPTION: 'TEXT' is not E,N,U" otherwise.
glm::dvec3 parsePointOption(const std::string& option, const std::string& text);

/// --size's "WxH" into width and height, each at least 16; std::invalid_argument naming --size otherwise.
void parseFrameSizeOption(const char* value, uint32_t& width, uint32_t& height);

struct BuildingView {
    glm::dvec3 position, look_at;
};

/// South-east of the building's bounds, 1.8 radii out (at least 1 m of radius) and 0.6 up, looking at their centre.
BuildingView southEastViewOf(const BakeSetData& bake_set);

/// The mean Rec. 709 luminance of a lightmap's valid texels (alpha > 0); 0 with none.
double meanLightmapLuminance(const BakeSetImage& image);

/// The exposure that puts a face of albedo 0.5 lit by the lightmap's mean plus `sun_luminance` at display value 0.6.
float sunlitGreyExposure(const BakeSetImage& lightmap, double sun_luminance);

/// 1 where `composite` differs from the camera frame in any of R, G, B (the building and its ground effect), else 0.
std::vector<uint8_t> changedRegion(const std::vector<uint8_t>& composite, const std::vector<uint8_t>& camera);

}  // namespace gusuku::bench_common

// An option's E,N,U point in site metres (--position, --look-at), as gusuku-render and gusuku-view read and print it.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "gusuku/tools/command_line.h"

namespace gusuku::render_cli {

// "E,N,U" with each number as --help prints defaults (defaultNumber).
std::string enuPointText(const glm::dvec3& point_enu_m);

// Three finite numbers separated by commas, within 100 km of the site's origin; anything else fails through
// line.failValue naming the option and the text.
glm::dvec3 parseEnuPoint(const CommandLine& line, const std::string& option, const std::string& text);

}  // namespace gusuku::render_cli

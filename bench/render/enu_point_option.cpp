// An option's E,N,U point (see enu_point_option.h).

#include "enu_point_option.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "gusuku/tools/option_table.h"

namespace gusuku::render_cli {

std::string enuPointText(const glm::dvec3& point_enu_m) {
    return defaultNumber(point_enu_m.x) + "," + defaultNumber(point_enu_m.y) + "," + defaultNumber(point_enu_m.z);
}

glm::dvec3 parseEnuPoint(const CommandLine& line, const std::string& option, const std::string& text) {
    std::istringstream stream(text);
    glm::dvec3 point_enu_m;
    char comma1 = 0, comma2 = 0;
    stream >> point_enu_m.x >> comma1 >> point_enu_m.y >> comma2 >> point_enu_m.z;
    // 100 km: a camera farther from the site's origin is a typo (a latitude pasted as metres), not a view.
    if (!stream || comma1 != ',' || comma2 != ',' || !stream.eof() || !std::isfinite(point_enu_m.x) ||
        !std::isfinite(point_enu_m.y) || !std::isfinite(point_enu_m.z) || glm::length(point_enu_m) > 1e5)
        line.failValue(option, "'" + text + "' is not E,N,U in metres (three finite numbers within 100 km)");
    return point_enu_m;
}

}  // namespace gusuku::render_cli

#include "gusuku_bake/ground_control.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "gusuku/assets/site.h"  // the site's latitude, longitude and height ranges
#include "gusuku/formats/input_error.h"
#include "gusuku/tools/command_line.h"  // parseDecimal

namespace gusuku::bake {

namespace {

std::string trimmed(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> splitColumns(const std::string& line) {
    std::vector<std::string> columns;
    std::stringstream stream(line);
    std::string column;
    while (std::getline(stream, column, ',')) columns.push_back(trimmed(column));
    if (!line.empty() && line.back() == ',') columns.push_back("");  // getline drops a trailing empty column
    return columns;
}

std::string joined(const std::vector<std::string>& columns) {
    std::string text;
    for (const std::string& column : columns) text += (text.empty() ? "" : ",") + column;
    return text;
}

std::string numberText(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// One row's reader: every problem names the file, the line and the column.
struct RowReader {
    const std::string& path;
    int line;
    const std::vector<std::string>& header;
    const std::vector<std::string>& columns;

    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(path, "line " + std::to_string(line), problem);
    }
    double number(size_t index, double minimum, double maximum) const {
        const std::optional<double> value = parseDecimal(columns[index]);
        if (!value)
            fail(header[index] + ": " + quotedForMessage(columns[index]) + " is not a decimal number");
        if (*value < minimum || *value > maximum)
            fail(header[index] + ": " + numberText(*value) + " is outside [" + numberText(minimum) + ", " +
                 numberText(maximum) + "]");
        return *value;
    }
};

}  // namespace

std::vector<GroundControlPoint> readGroundControlPoints(const std::string& path, const std::string& text,
                                                       const GeodeticPoint& origin,
                                                       const std::optional<UtmZone>& zone) {
    std::vector<GroundControlPoint> points;
    std::vector<std::string> header;
    bool grid = false;
    std::istringstream stream(text);
    std::string raw;
    for (int line = 1; std::getline(stream, raw); ++line) {
        const std::string content = trimmed(raw);
        if (content.empty() || content[0] == '#') continue;
        const std::vector<std::string> columns = splitColumns(content);
        if (header.empty()) {
            const std::string written = joined(columns);
            if (written != kGeodeticControlHeader && written != kGridControlHeader)
                throw InputError(path, "line " + std::to_string(line),
                                 "the header " + quotedForMessage(written) + " is neither " +
                                     kGeodeticControlHeader + " nor " + kGridControlHeader);
            header = columns;
            grid = written == kGridControlHeader;
            if (grid && !zone)
                throw InputError(path, "line " + std::to_string(line),
                                 "easting/northing columns need the grid's zone: give --utm-zone (e.g. 52N)");
            continue;
        }
        const RowReader row{path, line, header, columns};
        if (columns.size() != header.size())
            row.fail("has " + std::to_string(columns.size()) + " columns, the header " + std::to_string(header.size()) +
                     " (" + joined(header) + ")");
        GroundControlPoint point;
        point.name = columns[0];
        point.line = line;
        if (point.name.empty()) row.fail("name: empty");
        for (const GroundControlPoint& earlier : points)
            if (earlier.name == point.name)
                row.fail("name: " + quotedForMessage(point.name) + " repeats line " + std::to_string(earlier.line));
        for (int axis = 0; axis < 3; ++axis) point.mesh[axis] = row.number(1 + axis, -1e9, 1e9);
        GeodeticPoint surveyed;
        if (grid) {
            // UTM eastings lie within about 166 km to 834 km, northings within 0 to 10,000 km; GeographicLib
            // refuses what lies beyond its zone.
            const double easting = row.number(4, 0.0, 1e6), northing = row.number(5, 0.0, 1e7);
            const double height = row.number(6, kSiteHeightRangeM.minimum, kSiteHeightRangeM.maximum);
            try {
                surveyed = utmToGeodetic(*zone, easting, northing, height);
            } catch (const std::invalid_argument& error) {
                row.fail(std::string("easting_m, northing_m: ") + error.what());
            }
        } else {
            surveyed.latitude_deg = row.number(4, kSiteLatitudeRangeDeg.minimum, kSiteLatitudeRangeDeg.maximum);
            surveyed.longitude_deg = row.number(5, kSiteLongitudeRangeDeg.minimum, kSiteLongitudeRangeDeg.maximum);
            surveyed.height_m = row.number(6, kSiteHeightRangeM.minimum, kSiteHeightRangeM.maximum);
        }
        point.enu_m = geodeticToEnu(origin, surveyed);
        const double distance_m = glm::length(point.enu_m);
        if (!(distance_m <= kMaxControlDistanceM))
            row.fail("the surveyed point is " + numberText(distance_m / 1000.0) + " km from the ENU origin (at most " +
                     numberText(kMaxControlDistanceM / 1000.0) + " km): a wrong " +
                     (grid ? "zone, " : "") + "origin or column order?");
        points.push_back(point);
    }
    if (header.empty())
        throw InputError(path, "", "no header line; the first line must be " + std::string(kGeodeticControlHeader) +
                                       " or " + kGridControlHeader);
    return points;
}

}  // namespace gusuku::bake

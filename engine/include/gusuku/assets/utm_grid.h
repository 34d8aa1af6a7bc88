#pragma once
// Projected grid coordinates (UTM, Universal Transverse Mercator, on WGS84) back to geodetic latitude and
// longitude, through GeographicLib's UTMUPS, so that a survey given as grid easting/northing can be placed in
// the site's ENU frame (gusuku/assets/geodetic.h). Kept apart from geodetic.h, which site.h includes everywhere.

#include <optional>
#include <string>

#include "gusuku/assets/geodetic.h"

namespace gusuku {

/// A UTM zone: its number, 1 to 60, and its hemisphere.
struct UtmZone {
    int number = 0;
    bool north = true;
};

/// "52N", "52n", "7S": the zone number and N or S for the hemisphere (not a latitude band letter, which would
/// make "52S" ambiguous). nullopt for anything else.
std::optional<UtmZone> parseUtmZone(const std::string& text);

/// The point whose UTM easting and northing (metres, false easting and northing included) in `zone` are
/// given; height_m is copied through and must already be above the WGS84 ellipsoid (a grid's height above sea
/// level needs the geoid undulation added first). Throws std::invalid_argument, naming the coordinate, when
/// GeographicLib refuses it (an easting far outside the zone).
GeodeticPoint utmToGeodetic(const UtmZone& zone, double easting_m, double northing_m, double height_m);

}  // namespace gusuku

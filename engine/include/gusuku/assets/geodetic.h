#pragma once
// Geodetic (WGS84 latitude, longitude, ellipsoidal height) to the site's local east-north-up frame, through
// GeographicLib's LocalCartesian. The origin is the site reference point from site.json.

#include <glm/vec3.hpp>

namespace gusuku {

struct GeodeticPoint {
    double latitude_deg = 0.0;
    double longitude_deg = 0.0;
    double height_m = 0.0;  ///< above the WGS84 ellipsoid
};

/// ENU metres of `point` relative to `origin` (x east, y north, z up).
glm::dvec3 geodeticToEnu(const GeodeticPoint& origin, const GeodeticPoint& point);

}  // namespace gusuku

#include "gusuku/assets/geodetic.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

namespace gusuku {

glm::dvec3 geodeticToEnu(const GeodeticPoint& origin, const GeodeticPoint& point) {
    // LocalCartesian is exactly the site's ENU frame: x east, y north, z up, tangent to the WGS84 ellipsoid at
    // the origin. Constructing it per call is cheap (a few trigonometric terms) and keeps this free of state.
    const GeographicLib::LocalCartesian frame(origin.latitude_deg, origin.longitude_deg, origin.height_m,
                                              GeographicLib::Geocentric::WGS84());
    glm::dvec3 enu{0.0};
    frame.Forward(point.latitude_deg, point.longitude_deg, point.height_m, enu.x, enu.y, enu.z);
    return enu;
}

}  // namespace gusuku

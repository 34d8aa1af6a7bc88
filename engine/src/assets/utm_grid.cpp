#include "gusuku/assets/utm_grid.h"

#include <stdexcept>

#include <GeographicLib/UTMUPS.hpp>

namespace gusuku {

std::optional<UtmZone> parseUtmZone(const std::string& text) {
    if (text.size() < 2 || text.size() > 3) return std::nullopt;
    const char hemisphere = text.back();
    const std::string digits = text.substr(0, text.size() - 1);
    for (const char digit : digits)
        if (digit < '0' || digit > '9') return std::nullopt;
    UtmZone zone;
    zone.number = std::stoi(digits);
    if (zone.number < 1 || zone.number > 60) return std::nullopt;
    if (hemisphere == 'N' || hemisphere == 'n') zone.north = true;
    else if (hemisphere == 'S' || hemisphere == 's') zone.north = false;
    else return std::nullopt;
    return zone;
}

GeodeticPoint utmToGeodetic(const UtmZone& zone, double easting_m, double northing_m, double height_m) {
    GeodeticPoint point;
    point.height_m = height_m;
    try {
        // mgrslimits = false: the range UTMUPS accepts for a zone, wider than MGRS's strict limits.
        GeographicLib::UTMUPS::Reverse(zone.number, zone.north, easting_m, northing_m, point.latitude_deg,
                                       point.longitude_deg);
    } catch (const GeographicLib::GeographicErr& error) {
        throw std::invalid_argument(std::string("not a position in this zone: ") + error.what());
    }
    return point;
}

}  // namespace gusuku

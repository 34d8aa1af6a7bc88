#pragma once
// The sun's place in a sky photo, and the north it gives (issue 42 item 4): with the photo's time and the site's
// position the sun's computed azimuth is known, so the image column the sun stands in fixes the column that faces
// north. site.json's `"north_azimuth_in_image_deg": "auto"` (with `taken_at`) resolves through it at load, and
// `gusuku-bake check` / `preview` compare a given north with it. Equirect convention of gusuku/maths/equirect.h:
// row 0 the zenith, azimuth = 360 u - north_azimuth_in_image_deg.

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "gusuku/maths/image_rgba.h"

namespace gusuku {

/// Where the brightest compact region of a sky map stands, in the image's own terms (no north needed).
struct SkySunSighting {
    bool found = false;               ///< false: no compact bright region (overcast, sun hidden), nothing below holds
    double image_azimuth_deg = 0.0;   ///< 360 u of the region's luminance-weighted centre, [0, 360)
    double elevation_deg = 0.0;       ///< 90 - its polar angle
    int core_texels = 0;              ///< texels of the region (luminance >= half the peak, connected to the peak)
    double core_radius_deg = 0.0;     ///< largest angle from the centre to a texel of the region
};

/// A bright region wider than this is a cloud or clipped overcast, not the sun (0.27 deg) with its glare; the
/// bake's disc extraction uses the same bound (gusuku_bake/sky_light.h).
inline constexpr double kSkySunMaxCoreRadiusDeg = 10.0;

/// The brightest texel (Rec.709 luminance; NaN, infinite and negative channels count as 0), its core (8-connected,
/// columns wrapping, luminance >= half the peak) and the core's luminance-weighted centre. Not found when the map is
/// empty or black, or the core reaches beyond kSkySunMaxCoreRadiusDeg. A clipped sun's flat top is its core.
SkySunSighting findSkySun(const ImageRGBA& sky);

/// The north_azimuth_in_image_deg that puts a sun seen at `sun_image_azimuth_deg` (360 u) at the computed azimuth
/// `sun_azimuth_deg` (east of north): 360 u - azimuth, wrapped to [0, 360).
double northAzimuthInImageFromSun(double sun_image_azimuth_deg, double sun_azimuth_deg);

/// The sighting's direction in the site's east-north-up frame for a given north_azimuth_in_image_deg.
glm::dvec3 skySunDirectionEnu(const SkySunSighting& sighting, double north_azimuth_in_image_deg);

/// What site.json says of when a sky was photographed (its `taken_at`) and whether its north is "auto"; read
/// again from the file (loadSiteConfig has validated it) because SiteConfig keeps only the resolved north.
struct SkyCaptureTime {
    std::optional<double> taken_at_utc_seconds;
    std::string taken_at_text;  ///< as written, for messages
    bool north_auto = false;
};
/// `sky_name` is "sunny" or "overcast"; an absent sky or field gives the defaults.
SkyCaptureTime readSkyCaptureTime(const std::string& site_json_path, const std::string& sky_name);

}  // namespace gusuku

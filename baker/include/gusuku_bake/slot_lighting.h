#pragma once
// What lights each bake slot: the sky map (sun disc removed) and the sun, placed by NREL SPA from the slot's
// time and the site's position, with an irradiance E_sun measured from the map's disc where the map holds it
// unclipped, else from the clear-sky model (docs/design.md 3). The source is recorded in the manifest.

#include <string>
#include <vector>

#include "gusuku/assets/site.h"
#include "gusuku/maths/sun.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/sky_light.h"

namespace gusuku::bake {

/// A sky map ready to trace: loaded, checked (no NaN or negative texels), its sun disc removed.
struct PreparedSky {
    std::string path;
    SunDiscEstimate disc;
    SkySamplingTables tables;
    /// Diffuse horizontal irradiance of the map without its sun, per channel (upper hemisphere): what the
    /// clear-sky fallback is calibrated on.
    glm::dvec3 diffuse_horizontal_rgb{0.0};
    /// Its luminance.
    double diffuse_horizontal_luminance = 0.0;
};

/// Reads the map (readSkyRadiance: an HDR map, or 8-bit photos turned into radiance with their clipped texels at
/// the saturation white; bad input is an InputError naming the file), removes the disc.
PreparedSky prepareSky(const SkyConfig& sky);

/// E_sun on a plane facing the sun (direct normal irradiance, the map's units) for a sunny slot:
///  - the map's disc found, unclipped and above 0.5 deg: the measured disc carried from the photo's sun elevation
///    to the slot's by air mass (gusuku/maths/sun_air_mass.h carryMeasuredSunRgb: Rayleigh plus a fitted aerosol depth,
///    per channel; identity when the slot's sun stands where the photo's did);
///  - the disc found but clipped, above 0.5 deg, and the sky's global_horizontal_lux given: E_sun by energy from
///    that reading (sunFromGlobalHorizontalLux);
///  - else the clear-sky fallback calibrated on the map's own diffuse light (calibratedClearSkySunRgb: aerosol
///    depth from the diffuse light's colour, luminance from ESRA's clear-sky direct/diffuse ratio), evaluated at
///    the clipped disc's elevation when the map shows one, else at the slot's own elevation.
struct SlotLighting {
    BakeSlot slot;
    SunPosition sun_position;        ///< SPA at the slot's instant (meaningless for overcast)
    SunLight sun;                    ///< present only for a sunny slot with the sun above the horizon
    std::string sun_irradiance_source;  ///< "sky map sun disc", "clear-sky model", "none: overcast", ...
    const PreparedSky* sky = nullptr;
    std::vector<std::string> warnings;
};

/// E_sun (direct normal, the map's units, per channel) at to_elevation_deg from a lux meter's reading taken
/// with 8-bit photos, whose exposure puts them in absolute units (kRadianceWhiteEfficacy cd m^-2 per unit of
/// luminance; gusuku/maths/exposure.h). The reading less the photos' own diffuse horizontal illuminance (the
/// sky with its sun removed, sky.diffuse_horizontal_luminance x 179) is the direct beam on the horizontal; over
/// sin(photo_sun_elevation_deg) it is the beam's normal illuminance at the photo's sun. Colour and the carry to
/// to_elevation_deg are the clear-sky fallback's (calibratedClearSkySunRgb), scaled to that luminance. Throws
/// InputError(site_file, "/skies/sunny/global_horizontal_lux", ...) when the reading is not above the diffuse
/// illuminance (a shaded meter, or a wrong exposure). photo_sun_elevation_deg must be > 0.
glm::dvec3 sunFromGlobalHorizontalLux(const PreparedSky& sky, double global_horizontal_lux,
                                      double photo_sun_elevation_deg, double to_elevation_deg,
                                      const std::string& site_file);

SlotLighting lightSlot(const SiteConfig& site, const BakeSlot& slot, const PreparedSky& sunny,
                       const PreparedSky* overcast);

}  // namespace gusuku::bake

#include "gusuku_bake/slot_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/maths/exposure.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun_air_mass.h"

namespace gusuku::bake {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

glm::dvec3 diffuseHorizontalRgb(const ImageRGBA& sky) {
    glm::dvec3 irradiance(0.0);
    for (int y = 0; y < sky.height / 2; ++y) {
        const double cos_zenith = std::cos((y + 0.5) / sky.height * std::numbers::pi);
        const double solid_angle = equirectTexelSolidAngle(y, sky.width, sky.height);
        for (int x = 0; x < sky.width; ++x) {
            const float* texel = sky.texel(x, y);
            irradiance += glm::dvec3(texel[0], texel[1], texel[2]) * (solid_angle * cos_zenith);
        }
    }
    return irradiance;
}

std::string luxText(double lux) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", lux);
    return text;
}

/// What the clear-sky fallback's warning adds: how the user can do better than the model.
std::string clearSkyFallbackAdvice(const SkyConfig& sky, const SunDiscEstimate& disc) {
    // An HDR map: its units are its own, so a lux reading cannot scale it; only a map that holds the disc can.
    if (sky.photos.empty())
        return disc.found ? ": the map's brightest pixels are cut off, so it cannot say how strong the sun was; "
                            "merge the map from a bracket whose darkest exposure shows the sun as a small disc (an "
                            "ND filter, or 1/8000 s at f/16), or give the photos themselves as skies/sunny/bracket "
                            "with the lux meter's reading as global_horizontal_lux"
                          : "; if the sun was out when the sky was captured, the map lost it: merge the map from "
                            "a bracket whose darkest exposure shows the sun as a small disc";
    if (!disc.found)
        return sky.global_horizontal_lux ? "; /skies/sunny/global_horizontal_lux not used: the photos show no sun "
                                           "disc to place the capture's sun"
                                         : "";
    return ": one photo cannot hold the sun's strength (the model assumes a clear sky's turbidity and overestimates "
           "a sun veiled by cloud); give a bracket whose darkest photo holds the disc unclipped, or the lux meter's "
           "reading at the capture as /skies/sunny/global_horizontal_lux";
}

}  // namespace

PreparedSky prepareSky(const SkyConfig& sky) {
    PreparedSky prepared;
    prepared.path = sky.path;
    ImageRGBA radiance = readSkyRadiance(sky);  // an HDR map, or 8-bit photos turned into radiance
    prepared.disc = extractSunDisc(radiance, sky.north_azimuth_in_image_deg);
    prepared.diffuse_horizontal_rgb = diffuseHorizontalRgb(radiance);
    prepared.diffuse_horizontal_luminance = luminanceRec709(prepared.diffuse_horizontal_rgb);
    prepared.tables = buildSkySamplingTables(radiance, sky.north_azimuth_in_image_deg);
    return prepared;
}

// Energy, where the clear-sky model can only assume a turbidity: see slot_lighting.h.
glm::dvec3 sunFromGlobalHorizontalLux(const PreparedSky& sunny, double lux, double photo_elevation_deg,
                                      double slot_elevation_deg, const std::string& site_file) {
    if (!(photo_elevation_deg > 0.0))
        throw std::invalid_argument("sunFromGlobalHorizontalLux: the photo's sun is not above the horizon");
    const double diffuse_lux = sunny.diffuse_horizontal_luminance * kRadianceWhiteEfficacy;
    const double direct_horizontal_lux = lux - diffuse_lux;
    if (!(direct_horizontal_lux > 0.0))
        throw InputError(site_file, "/skies/sunny/global_horizontal_lux",
                         luxText(lux) + " lux is not above the photos' own diffuse horizontal illuminance " +
                             luxText(diffuse_lux) + " lux (sun removed): the meter was shaded, or the photos' " +
                             "exposure is off");
    const double direct_normal = direct_horizontal_lux / kRadianceWhiteEfficacy /
                                 std::sin(photo_elevation_deg / kDegrees);
    const glm::dvec3 model_at_photo =
        calibratedClearSkySunRgb(sunny.diffuse_horizontal_rgb, photo_elevation_deg, photo_elevation_deg);
    const double model_luminance = luminanceRec709(model_at_photo);
    if (!(model_luminance > 0.0))  // a black sky gives no colour: the sun above the air's, carried by clean air
        return carryMeasuredSunRgb(extraterrestrialSunColourRgb() * direct_normal, photo_elevation_deg,
                                   slot_elevation_deg);
    const double scale = direct_normal / model_luminance;
    return calibratedClearSkySunRgb(sunny.diffuse_horizontal_rgb, photo_elevation_deg, slot_elevation_deg) * scale;
}

SlotLighting lightSlot(const SiteConfig& site, const BakeSlot& slot, const PreparedSky& sunny,
                       const PreparedSky* overcast) {
    SlotLighting lighting;
    lighting.slot = slot;
    if (slot.sky == SlotSky::Overcast) {
        if (overcast == nullptr) throw std::invalid_argument("slot " + slot.name + " is overcast but no overcast sky");
        lighting.sky = overcast;
        lighting.sun_irradiance_source = "none: overcast";
        return lighting;
    }
    lighting.sky = &sunny;
    const SunObserver observer = site.site.sunObserver();
    lighting.sun_position = computeSunPosition(observer, slot.utc_seconds);
    const double elevation = lighting.sun_position.apparent_elevation_deg;
    if (!lighting.sun_position.above_horizon) {
        lighting.sun_irradiance_source = "none: sun below the horizon";
        lighting.warnings.push_back("slot " + slot.name + ": the sun is below the horizon (apparent elevation " +
                                    std::to_string(elevation) + " deg); baked with sky light only");
        return lighting;
    }
    lighting.sun.present = true;
    lighting.sun.direction_enu = lighting.sun_position.direction_enu;
    const SunDiscEstimate& disc = sunny.disc;
    const double photo_elevation = disc.found ? std::asin(std::clamp(disc.direction_enu.z, -1.0, 1.0)) * kDegrees
                                              : -90.0;
    const bool lux_given = site.sunny_sky.global_horizontal_lux.has_value();
    if (disc.found && !disc.clipped && photo_elevation > 0.5) {
        lighting.sun.irradiance_rgb = carryMeasuredSunRgb(disc.irradiance_rgb, photo_elevation, elevation);
        lighting.sun_irradiance_source = "sky map sun disc (measured at " + std::to_string(photo_elevation) +
                                         " deg elevation, carried by air mass)";
        if (lux_given)
            lighting.warnings.push_back("slot " + slot.name + ": /skies/sunny/global_horizontal_lux not used: the "
                                        "photos hold the sun's disc unclipped, so it is measured");
    } else if (lux_given && disc.found && photo_elevation > 0.5) {
        lighting.sun.irradiance_rgb = sunFromGlobalHorizontalLux(sunny, *site.sunny_sky.global_horizontal_lux,
                                                                 photo_elevation, elevation, site.file);
        lighting.sun_irradiance_source = "global_horizontal_lux less the photos' diffuse light (clipped disc at " +
                                         std::to_string(photo_elevation) + " deg elevation, carried by air mass)";
    } else {
        // A clipped disc still says where the photo's sun stood; without one, assume the slot's own elevation.
        const double calibration_elevation = (disc.found && photo_elevation > 0.5) ? photo_elevation : elevation;
        lighting.sun.irradiance_rgb =
            calibratedClearSkySunRgb(sunny.diffuse_horizontal_rgb, calibration_elevation, elevation);
        lighting.sun_irradiance_source = disc.found ? "clear-sky model (map's sun disc is clipped)"
                                                    : "clear-sky model (no sun disc in the map)";
        lighting.warnings.push_back("slot " + slot.name + ": E_sun from the " + lighting.sun_irradiance_source +
                                    clearSkyFallbackAdvice(site.sunny_sky, disc));
    }
    return lighting;
}

}  // namespace gusuku::bake

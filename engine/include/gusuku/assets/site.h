#pragma once
// site.json: where the site is, what is baked and with what. The format is documented in docs/site-json.md.
// loadSiteConfig validates every field and resolves relative paths against the file's directory.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "gusuku/assets/geodetic.h"
#include "gusuku/maths/sun.h"

namespace gusuku {

struct SiteLocation {
    std::string name;
    GeodeticPoint reference;         ///< origin of the ENU frame
    int utc_offset_minutes = 0;      ///< the site's clock, minutes east of UTC (used for slot times)
    double pressure_mbar = -1.0;     ///< <0: standard atmosphere at the reference height
    double temperature_c = 15.0;

    /// The sun's observer at the reference point, with this site's air (for refraction).
    SunObserver sunObserver() const {
        SunObserver observer;
        observer.latitude_deg = reference.latitude_deg;
        observer.longitude_deg = reference.longitude_deg;
        observer.height_m = reference.height_m;
        observer.pressure_mbar = pressure_mbar;
        observer.temperature_c = temperature_c;
        return observer;
    }
};

/// The photogrammetry (SfM) mesh of the real site. Its similarity transform maps the glTF file's own
/// coordinates (after its node hierarchy, with no implicit axis change) into ENU: p_enu = s R p + t.
struct SfmMeshConfig {
    std::string path;                       ///< absolute
    double scale = 1.0;
    std::array<double, 4> rotation_wxyz{1, 0, 0, 0};  ///< unit quaternion
    glm::dvec3 translation_enu_m{0.0};
    glm::dmat4 enuFromModel() const;
};

/// The lost building. Placed by geodetic position or ENU offset (exactly one), turned to a compass heading.
/// Its glTF is Y-up: glTF (x, y, z) -> ENU (x, -z, y), then scale, then heading, then translation.
struct BuildingConfig {
    std::string path;                         ///< absolute
    std::optional<GeodeticPoint> position;    ///< where the model's origin stands
    std::optional<glm::dvec3> enu_offset_m;   ///< or: the origin's ENU offset from the site reference
    double heading_deg = 0.0;  ///< compass heading (clockwise from north) that the model's north (-Z) faces
    double scale = 1.0;
    /// Full transform from the glTF file's coordinates to ENU (axis change included).
    glm::dmat4 enuFromModel(const GeodeticPoint& site_reference) const;
};

/// An equirectangular sky photo: row 0 is the zenith, column u in [0, 1) from the left edge.
/// north_azimuth_in_image_deg is 360 * u of the column that faces north; azimuth east of north grows with u:
/// azimuth_deg = 360 * u - north_azimuth_in_image_deg (mod 360).
/// One 8-bit photo of a sky (gusuku/assets/sky_photo.h): its file and, when site.json gives it, its EV100
/// (otherwise read from the photo's EXIF).
struct SkyPhotoConfig {
    std::string path;  ///< absolute, .jpg, .jpeg or .png
    std::optional<double> ev100;
};

struct SkyConfig {
    std::string path;  ///< absolute: the HDR map (.hdr, .exr), or the first of `photos`
    double north_azimuth_in_image_deg = 0.0;
    /// 8-bit photos of one view (an exposure bracket when more than one); empty for an HDR map.
    std::vector<SkyPhotoConfig> photos;
    /// Photos only: the global horizontal illuminance a lux meter lying flat read when the photos were taken
    /// (lux). When the photos clip the sun's disc it sets E_sun by energy (the reading less the photos' diffuse
    /// horizontal illuminance, over the sine of the clipped disc's elevation) in place of the clear-sky model.
    std::optional<double> global_horizontal_lux;
};

enum class SlotSky { Sunny, Overcast };

struct BakeSlot {
    std::string name;               ///< unique, [a-z0-9_]+, names output files
    SlotSky sky = SlotSky::Sunny;
    std::string local_time;         ///< "hh:mm" site clock on bake.date; empty for overcast
    double utc_seconds = 0.0;       ///< the instant (sunny slots); filled by loadSiteConfig
};

struct BakeSettings {
    std::string date;               ///< "YYYY-MM-DD", site clock
    std::vector<BakeSlot> slots;    ///< default: sunny 09:00, 12:00, 15:00, and overcast given skies.overcast
    double texels_per_metre = 8.0;  ///< building lightmap density
    int samples_per_texel = 256;
    int max_bounces = 4;
    uint32_t seed = 1;
    double ground_cell_m = 0.25;    ///< ground grid cell size
};

struct SiteConfig {
    std::string file;               ///< the site.json path, as given
    SiteLocation site;
    std::optional<SfmMeshConfig> sfm_mesh;
    BuildingConfig building;
    SkyConfig sunny_sky;
    std::optional<SkyConfig> overcast_sky;  ///< required when a slot is overcast
    BakeSettings bake;
};

/// A closed range of values site.json accepts.
struct SiteValueRange {
    double minimum;
    double maximum;
};
/// The reference point's and the air's ranges (docs/site-json.md). `gusuku-bake sun` checks its options against
/// the same ranges, so it refuses what site.json refuses.
inline constexpr SiteValueRange kSiteLatitudeRangeDeg{-90.0, 90.0};
inline constexpr SiteValueRange kSiteLongitudeRangeDeg{-180.0, 180.0};
inline constexpr SiteValueRange kSiteHeightRangeM{-1000.0, 10000.0};
inline constexpr SiteValueRange kSitePressureRangeMbar{100.0, 1100.0};
inline constexpr SiteValueRange kSiteTemperatureRangeC{-90.0, 60.0};
/// A sky photo's EV100, whether site.json gives it (`ev100`) or the photo's EXIF does (gusuku/assets/sky_photo.h):
/// -10 is a moonless night at a long exposure, 30 far above the sun through a dense filter. Beyond it an EXIF
/// value is corrupt (an FNumber of 2e9 gave EV100 72 and a sun of 1e20 W/m^2 after a whole bake).
inline constexpr SiteValueRange kSkyPhotoEv100Range{-10.0, 30.0};

/// Reads and validates site.json. Every field is checked: type, range, unknown names, referenced files exist.
/// Throws InputError(path, "/json/pointer", problem) on the first problem found.
SiteConfig loadSiteConfig(const std::string& path);

}  // namespace gusuku

#pragma once
// What a bake set's manifest.json says (docs/bakeset.md), as plain data: the baker fills it and writes it, the
// runtime (or the app for it) reads it, and both see the same fields. This header needs only glm and the
// standard library, so the runtime can hold a manifest without the I/O stack; reading and writing the JSON
// lives in gusuku_assets (gusuku/assets/bakeset_manifest_json.h).
//
// Frame and units, throughout: directions and positions in the site's east-north-up frame (metres), angles in
// degrees, azimuth east of north, sun elevation APPARENT (refracted, as SunPosition gives it), irradiance per
// linear Rec.709 channel in the sky maps' radiance units times steradians. File names are relative to the
// bake set's folder.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/formats/ground_grid.h"

namespace gusuku {

/// The layout version written as "format"; a reader refuses any other. Change it with any change a reader of
/// the old layout would misread.
inline constexpr const char* kBakeSetFormat = "gusuku-bakeset/1";

/// One input file of the bake, with the FNV-1a 64 hash of its bytes (16 lower-case hex digits).
struct BakeSetInput {
    std::string role;     ///< "site", "building", "sfm_mesh", "sunny_sky", "overcast_sky"
    /// Relative to the bake set's folder (or absolute), so the set moves with its inputs; in a manifest with
    /// input_paths_relative_to_folder false (written before this rule), as the bake named it. Resolve it with
    /// gusuku/assets/bakeset_loader.h's resolveBakeSetInputPath.
    std::string path;
    std::string fnv1a64;
    bool operator==(const BakeSetInput& other) const;  ///< every member equal
    bool operator!=(const BakeSetInput& other) const { return !(*this == other); }
};

/// Where the site is (site.json's reference point) and its clock.
struct BakeSetSite {
    std::string name;
    double latitude_deg = 0.0;   ///< geodetic, WGS84, north positive
    double longitude_deg = 0.0;  ///< east positive
    double height_m = 0.0;       ///< above the WGS84 ellipsoid
    int utc_offset_minutes = 0;  ///< the site's clock, minutes east of UTC
    bool operator==(const BakeSetSite& other) const;  ///< every member equal
    bool operator!=(const BakeSetSite& other) const { return !(*this == other); }
};

struct BakeSetSettings {
    uint32_t samples_per_texel = 0;  ///< per lightmap texel and per ground cell
    int max_bounces = 0;
    uint32_t seed = 0;
    bool denoised = false;           ///< the building lightmaps went through the edge-keeping filter
    bool operator==(const BakeSetSettings& other) const;  ///< every member equal
    bool operator!=(const BakeSetSettings& other) const { return !(*this == other); }
};

/// The building as baked. Fixed by the format (written, and checked by the reader): the mesh's frame is site
/// ENU metres in glTF Y-up axes, glTF (x, y, z) = ENU (x, z, -y); the lightmap UVs are TEXCOORD_1.
struct BakeSetBuilding {
    std::string mesh = "building.glb";
    std::string lightmap_uv_source;  ///< "TEXCOORD_1 from the glTF" or "generated charts (...)"
    int lightmap_resolution = 0;     ///< lightmaps are lightmap_resolution^2 texels
    double texels_per_metre = 0.0;   ///< the density the charts were laid out with
    uint64_t texels = 0;             ///< lightmap texels that lie on the building
    /// The building's sun horizons (gusuku/formats/sun_horizon.h, docs/bakeset.md "Sun horizons"), a KTX2 file of
    /// VK_FORMAT_R8G8B8A8_UNORM whose two layers lie one above the other; empty in bake sets made before them.
    std::string sun_horizon;
    bool operator==(const BakeSetBuilding& other) const;  ///< every member equal
    bool operator!=(const BakeSetBuilding& other) const { return !(*this == other); }
};

/// The ground grid: its addressing is gusuku/formats/ground_grid.h (column 0 west, row 0 north).
struct BakeSetGroundGrid {
    std::string geometry = "ground_geometry.exr";  ///< RGB: unit normal (ENU), A: height (ENU z, metres)
    GroundGrid grid;
    std::string ground_source;  ///< "sfm_mesh" or "flat plane at z = 0" (no SfM mesh in site.json)
    /// RGB: the ground's base colour (linear albedo, texture times factor) at each cell's ground point, A: 1 where
    /// the cell has ground. Empty in bake sets made before it existed: they load, and the runtime's ground colour
    /// match (ColourMatch::kGround) then refuses to run (docs/bakeset.md "Ground albedo").
    std::string albedo;
    bool operator==(const BakeSetGroundGrid& other) const;  ///< every member equal
    bool operator!=(const BakeSetGroundGrid& other) const { return !(*this == other); }
};

/// The real site's surfaces for the runtime's depth-only pass (docs/design.md 8, pass 4): the SfM mesh simplified
/// to what occlusion needs, positions and indices only. Present only when site.json has an SfM mesh. Fixed by
/// the format (written, and checked by the reader): the mesh's frame is the building's (site ENU metres in glTF
/// Y-up axes).
struct BakeSetOccluderInfo {
    std::string mesh = "occluder.glb";
    uint64_t triangles = 0;         ///< in the simplified mesh
    uint64_t source_triangles = 0;  ///< in the SfM mesh as loaded
    double target_error_m = 0.0;    ///< the simplifier's error bound, metres
    double simplification_error_m = 0.0;  ///< the error it reached (the simplifier's own estimate), metres
    bool operator==(const BakeSetOccluderInfo& other) const;  ///< every member equal
    bool operator!=(const BakeSetOccluderInfo& other) const { return !(*this == other); }
};

enum class BakeSetSky { Sunny, Overcast };

/// Where the sun stood for a sunny slot (SPA at the slot's instant), above the horizon or not.
struct BakeSetSunPosition {
    double azimuth_deg = 0.0;             ///< east of north, [0, 360)
    double apparent_elevation_deg = 0.0;  ///< refracted
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};  ///< unit, towards the sun: (cos e sin A, cos e cos A, sin e)
    bool operator==(const BakeSetSunPosition& other) const;  ///< every member equal
    bool operator!=(const BakeSetSunPosition& other) const { return !(*this == other); }
};

struct BakeSetSun {
    /// True only for a sunny slot with the sun above the horizon; then irradiance_rgb and angular_radius_deg
    /// hold, and the runtime adds the direct sun.
    bool present = false;
    /// Where E_sun came from: "sky map sun disc (measured at E deg elevation, carried by the clear-sky model)",
    /// "clear-sky model (...)", "none: overcast", "none: sun below the horizon".
    std::string irradiance_source;
    std::optional<BakeSetSunPosition> position;  ///< sunny slots only
    /// E_sun on a plane facing the sun, at position->apparent_elevation_deg; carry it to another elevation with
    /// gusuku/maths/sun_air_mass.h's carryMeasuredSunRgb (what the baker and the runtime do).
    glm::dvec3 irradiance_rgb{0.0};
    double angular_radius_deg = 0.0;  ///< of the sun disc the tracer samples
    bool operator==(const BakeSetSun& other) const;  ///< every member equal
    bool operator!=(const BakeSetSun& other) const { return !(*this == other); }
};

/// CIE Lab (D65) mean and standard deviation of the baked appearance rho/pi (E_ind + V E_sun cos) over the valid
/// lightmap texels: the source side of the runtime's colour match (docs/design.md 4).
struct BakeSetColourStatistics {
    glm::dvec3 lab_mean{0.0};
    glm::dvec3 lab_sigma{0.0};
    uint64_t texels = 0;
    bool operator==(const BakeSetColourStatistics& other) const;  ///< every member equal
    bool operator!=(const BakeSetColourStatistics& other) const { return !(*this == other); }
};

struct BakeSetSlot {
    std::string name;
    BakeSetSky sky = BakeSetSky::Sunny;
    std::string sky_map;     ///< the sky map's path, an input path like BakeSetInput::path
    std::string local_time;  ///< sunny slots: the slot's time on the site's clock (ISO 8601 with offset)
    std::string utc;         ///< sunny slots: the same instant in UTC ("...Z")
    BakeSetSun sun;
    std::string sky_sampling_method;  ///< "cosine" or "cosine + map (MIS)"
    double cosine_relative_variance = 0.0;  ///< the sky's measure that chose the method
    std::string building_irradiance;                 ///< building_<slot>.exr
    std::string ground_irradiance_with_building;     ///< ground_<slot>_with.exr
    std::string ground_irradiance_without_building;  ///< ground_<slot>_without.exr
    uint64_t invalid_texels = 0;  ///< texels inside geometry, filled by dilation
    std::optional<BakeSetColourStatistics> colour_statistics;
    bool operator==(const BakeSetSlot& other) const;  ///< every member equal
    bool operator!=(const BakeSetSlot& other) const { return !(*this == other); }
};

/// This bake's own cost (differs between runs of the same inputs). A merged set's (gusuku-bake merge): rays and
/// trace seconds summed over its partial sets, rays_per_second their ratio, wall_seconds the longest partial's.
struct BakeSetStatistics {
    uint64_t rays_traced = 0;
    double trace_seconds = 0.0;
    double rays_per_second = 0.0;
    double wall_seconds = 0.0;
    bool operator==(const BakeSetStatistics& other) const;  ///< every member equal
    bool operator!=(const BakeSetStatistics& other) const { return !(*this == other); }
};

/// A partial bake set: one slot of a site, baked alone (`gusuku-bake bake --slot NAME`) so that the slots can be
/// baked on several machines and joined by `gusuku-bake merge`. Its manifest holds that one slot; everything
/// else (inputs, settings, building, ground grid, occluder, warnings, input_hash) is what the whole bake writes.
/// loadBakeSet refuses a partial set.
struct BakeSetPartial {
    std::string slot;                     ///< the slot this set holds
    std::vector<std::string> site_slots;  ///< every slot of the site, in site.json's order
    /// FNV-1a 64 of the files every slot shares (building.glb, ground_geometry.exr, occluder.glb when present),
    /// in that order, each name then its bytes: partials of one site must agree on it, and merge recomputes it.
    uint64_t slot_independent_hash = 0;
    /// FNV-1a 64 of the set's own slot: its manifest entry as the writer writes it, then each of its three files
    /// (name, then bytes). Merge recomputes it, so an edited sun or a replaced lightmap is refused. Absent in
    /// partial sets of older bakes, which merge refuses.
    std::optional<uint64_t> slot_hash;
    bool operator==(const BakeSetPartial& other) const;  ///< every member equal
    bool operator!=(const BakeSetPartial& other) const { return !(*this == other); }
};

struct BakeSetManifest {
    /// Hash of everything that changes the traced sums (inputs' bytes, settings, tracer code); a rerun with the
    /// same hash has nothing to do. Written as 16 lower-case hex digits.
    uint64_t input_hash = 0;
    /// True (written as "input_paths": "relative to this manifest's folder"): relative input paths and sky maps
    /// are relative to the bake set's folder. False for a manifest written before that (no such field): its
    /// relative paths were relative to where its bake ran.
    bool input_paths_relative_to_folder = true;
    std::vector<BakeSetInput> inputs;
    BakeSetSite site;
    BakeSetSettings settings;
    BakeSetBuilding building;
    BakeSetGroundGrid ground_grid;
    std::optional<BakeSetOccluderInfo> occluder;  ///< none without an SfM mesh
    std::vector<BakeSetSlot> slots;
    BakeSetStatistics statistics;
    std::vector<std::string> warnings;
    std::optional<BakeSetPartial> partial;  ///< only in a partial set
    bool operator==(const BakeSetManifest& other) const;  ///< every member equal
    bool operator!=(const BakeSetManifest& other) const { return !(*this == other); }
};

}  // namespace gusuku

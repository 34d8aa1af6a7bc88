#pragma once
// The ranges a bake set's numbers must lie in, written once, one row per field: both bake set readers (the EXR
// set's manifest reader and loader, gusuku_assets; the runtime pack's reader, gusuku_pack_loader, which ships on
// phones) refuse a value outside them with a message naming the row's field, the writer refuses to write one (it
// reads back what it wrote), and docs/bakeset.md's "Ranges" table is tested to list exactly these rows
// (tests/test_bakeset_manifest.cpp); tests/test_bakeset_ranges.cpp feeds both readers a value outside every row.
// gusuku_maths: the standard library only.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

/// Where a row's values are found.
enum class BakeSetRangeSource {
    kManifest,  ///< a number (or each number of an array) of manifest.json; `field` is its JSON pointer
    kTexels,    ///< channels of decoded image texels (EXR or KTX2 alike, the pack's lightmaps after lightmap_scale)
};

/// One field's closed range [minimum, maximum]. Every value must also be finite (NaN and infinity lie outside
/// every range).
struct BakeSetRange {
    /// kManifest: the JSON pointer, "#" standing for each slot's index (so "/slots/#/invalid_texels"); the readers'
    /// messages name the pointer with the index. kTexels: the image and channels, as the readers' messages name them.
    const char* field;
    double minimum;
    double maximum;
    const char* unit;
    BakeSetRangeSource source = BakeSetRangeSource::kManifest;
    bool whole_number = false;  ///< a count: an integer as well
    /// A direction (3 values) when > 0: of length 1 within this (so never 0). The sun's is written from doubles,
    /// a ground normal is stored as floats.
    double length_tolerance = 0.0;
    bool when_sun_present = false;  ///< applies only to a slot whose sun is present
    /// kTexels: the first channel (0 R .. 3 A) and how many the row covers.
    int first_channel = 0;
    int channels = 0;
};

/// How far a sun's direction_enu may be from the direction its azimuth and elevation give, in degrees: the
/// writer rounds neither, so anything more is an edit.
inline constexpr double kBakeSetSunDirectionToleranceDeg = 0.01;

/// Irradiance, a texel's or the sun's: pi times the brightest radiance a sky may hold (1e15) with a thousandfold
/// margin for bounces, far enough below float's 3.4e38 that the runtime's sums over a lightmap stay finite.
inline constexpr double kBakeSetMaxIrradiance = 1e18;
/// The largest lightmap side: the runtime's texel counts (invalid_texels, colour statistics) fit 8192^2.
inline constexpr double kBakeSetMaxLightmapTexels = 67108864.0;
/// CIE Lab of the brightest irradiance: L = 116 cbrt(Y) - 16 with Y <= 1e18 / pi gives about 8e7, a and b about
/// five times that; 1e9 bounds them with a margin and keeps their squares finite in the runtime's floats.
inline constexpr double kBakeSetMaxLab = 1e9;

// Manifest rows (docs/bakeset.md names the fields). Reasons: the site's as site.json's (docs/site-json.md); ENU
// metres within site.json's own 100 km; the ground grid at most 16384 cells a side (the runtime's image limit).
inline constexpr BakeSetRange kBakeSetLatitudeDeg{"/site/latitude_deg", -90.0, 90.0, "degrees"};
inline constexpr BakeSetRange kBakeSetLongitudeDeg{"/site/longitude_deg", -180.0, 180.0, "degrees"};
inline constexpr BakeSetRange kBakeSetHeightM{"/site/height_m", -1000.0, 10000.0, "m"};
inline constexpr BakeSetRange kBakeSetUtcOffsetMinutes{"/site/utc_offset_minutes", -1440.0, 1440.0, "minutes",
                                                       BakeSetRangeSource::kManifest, true};
inline constexpr BakeSetRange kBakeSetLightmapResolution{"/building/lightmap_resolution", 1.0, 8192.0, "texels",
                                                         BakeSetRangeSource::kManifest, true};
/// As site.json's bake.texels_per_metre; 0 where the lightmap UVs came with the model.
inline constexpr BakeSetRange kBakeSetTexelsPerMetre{"/building/texels_per_metre", 0.0, 1000.0, "texels/m"};
inline constexpr BakeSetRange kBakeSetBuildingTexels{"/building/texels", 0.0, kBakeSetMaxLightmapTexels, "texels",
                                                     BakeSetRangeSource::kManifest, true};
/// The grid's south-west corner within site.json's own ENU bounds (100 km of the site reference).
inline constexpr BakeSetRange kBakeSetGroundOriginM{"/ground_grid/origin_enu_m", -1e5, 1e5, "m"};
/// Ground cells from a millimetre (finer is no ground survey) to the largest cell site.json allows.
inline constexpr BakeSetRange kBakeSetGroundCellM{"/ground_grid/cell_m", 1e-3, 100.0, "m"};
inline constexpr BakeSetRange kBakeSetGroundColumns{"/ground_grid/columns", 1.0, 16384.0, "cells",
                                                    BakeSetRangeSource::kManifest, true};
inline constexpr BakeSetRange kBakeSetGroundRows{"/ground_grid/rows", 1.0, 16384.0, "cells",
                                                 BakeSetRangeSource::kManifest, true};
/// Triangle counts: pack.bin's indices are 32-bit.
inline constexpr BakeSetRange kBakeSetOccluderSourceTriangles{"/occluder/source_triangles", 1.0, 4294967295.0,
                                                              "triangles", BakeSetRangeSource::kManifest, true};
inline constexpr BakeSetRange kBakeSetOccluderTriangles{"/occluder/triangles", 1.0, 4294967295.0, "triangles",
                                                        BakeSetRangeSource::kManifest, true};
inline constexpr BakeSetRange kBakeSetOccluderTargetErrorM{"/occluder/target_error_m", 0.0, 1e5, "m"};
inline constexpr BakeSetRange kBakeSetOccluderSimplificationErrorM{"/occluder/simplification_error_m", 0.0, 1e5, "m"};
inline constexpr BakeSetRange kBakeSetSunAzimuthDeg{"/slots/#/sun/azimuth_deg", 0.0, 360.0, "degrees"};
inline constexpr BakeSetRange kBakeSetSunElevationDeg{"/slots/#/sun/apparent_elevation_deg", -90.0, 90.0, "degrees"};
/// A present sun is above the horizon: its apparent (refracted) elevation may reach a little below 0 while its
/// disc still shows; a sun lower than that is absent.
inline constexpr BakeSetRange kBakeSetPresentSunElevationDeg{
    "/slots/#/sun/apparent_elevation_deg", -1.0, 90.0, "degrees", BakeSetRangeSource::kManifest, false, false, true};
inline constexpr BakeSetRange kBakeSetSunDirectionEnu{"/slots/#/sun/direction_enu", -1.0, 1.0, "unit vector",
                                                      BakeSetRangeSource::kManifest, false, 1e-6};
inline constexpr BakeSetRange kBakeSetSunIrradiance{"/slots/#/sun/irradiance_rgb", 0.0, kBakeSetMaxIrradiance,
                                                    "sky units x sr", BakeSetRangeSource::kManifest, false, false,
                                                    true};
inline constexpr BakeSetRange kBakeSetSunAngularRadiusDeg{"/slots/#/sun/angular_radius_deg", 0.0, 90.0, "degrees",
                                                          BakeSetRangeSource::kManifest, false, false, true};
/// pi * integral(L^2 cos) / integral(L cos)^2 - 1: >= 0 up to rounding (Cauchy-Schwarz), -1 its floor; one
/// bright texel of an 8192-wide map at the horizon gives about 1e10, so 1e15 is far above any sky's.
inline constexpr BakeSetRange kBakeSetCosineRelativeVariance{"/slots/#/sky_sampling/cosine_relative_variance", -1.0,
                                                             1e15, "ratio"};
inline constexpr BakeSetRange kBakeSetInvalidTexels{"/slots/#/invalid_texels", 0.0, kBakeSetMaxLightmapTexels,
                                                    "texels", BakeSetRangeSource::kManifest, true};
inline constexpr BakeSetRange kBakeSetLabMean{"/slots/#/colour_statistics/lab_mean", -kBakeSetMaxLab, kBakeSetMaxLab,
                                              "CIE Lab"};
inline constexpr BakeSetRange kBakeSetLabSigma{"/slots/#/colour_statistics/lab_sigma", 0.0, kBakeSetMaxLab, "CIE Lab"};
inline constexpr BakeSetRange kBakeSetColourTexels{"/slots/#/colour_statistics/texels", 0.0,
                                                   kBakeSetMaxLightmapTexels, "texels", BakeSetRangeSource::kManifest,
                                                   true};

// Texel rows: the images' channels as decoded (docs/bakeset.md, "Files").
inline constexpr BakeSetRange kBakeSetGroundNormal{"ground normal (ground_geometry RGB)", -1.0, 1.0, "unit vector",
                                                   BakeSetRangeSource::kTexels, false, 1e-3, false, 0, 3};
inline constexpr BakeSetRange kBakeSetGroundHeightM{"ground height (ground_geometry A)", -1e5, 1e5, "m",
                                                    BakeSetRangeSource::kTexels, false, false, false, 3, 1};
/// A material's base colour factor (glTF: [0, 1]) times its texture: a reflectance, and A 1 or 0 (ground or not).
inline constexpr BakeSetRange kBakeSetGroundAlbedo{"ground albedo (ground_albedo RGBA)", 0.0, 1.0, "reflectance",
                                                   BakeSetRangeSource::kTexels, false, false, false, 0, 4};
inline constexpr BakeSetRange kBakeSetTexelIrradiance{"irradiance (lightmap and ground irradiance RGB)", 0.0,
                                                      kBakeSetMaxIrradiance, "sky units x sr",
                                                      BakeSetRangeSource::kTexels, false, false, false, 0, 3};
/// A lightmap texel's validity, a ground cell's "ground here": 1 or 0 as written.
inline constexpr BakeSetRange kBakeSetTexelCoverage{"coverage (lightmap and ground irradiance A)", 0.0, 1.0, "fraction",
                                                    BakeSetRangeSource::kTexels, false, false, false, 3, 1};

/// Every row, in the order docs/bakeset.md lists them.
inline constexpr BakeSetRange kBakeSetRanges[] = {
    kBakeSetLatitudeDeg,        kBakeSetLongitudeDeg,           kBakeSetHeightM,
    kBakeSetUtcOffsetMinutes,   kBakeSetLightmapResolution,     kBakeSetTexelsPerMetre,
    kBakeSetBuildingTexels,     kBakeSetGroundOriginM,          kBakeSetGroundCellM,
    kBakeSetGroundColumns,      kBakeSetGroundRows,             kBakeSetOccluderSourceTriangles,
    kBakeSetOccluderTriangles,  kBakeSetOccluderTargetErrorM,   kBakeSetOccluderSimplificationErrorM,
    kBakeSetSunAzimuthDeg,      kBakeSetSunElevationDeg,        kBakeSetPresentSunElevationDeg,
    kBakeSetSunDirectionEnu,    kBakeSetSunIrradiance,          kBakeSetSunAngularRadiusDeg,
    kBakeSetCosineRelativeVariance, kBakeSetInvalidTexels,      kBakeSetLabMean,
    kBakeSetLabSigma,           kBakeSetColourTexels,           kBakeSetGroundNormal,
    kBakeSetGroundHeightM,      kBakeSetGroundAlbedo,           kBakeSetTexelIrradiance,
    kBakeSetTexelCoverage};

/// "[min, max]" as the messages and docs/bakeset.md write it (%g).
std::string describeBakeSetRange(const BakeSetRange& range);

/// Why `value` is outside the row (finite, whole when the row says so, within [minimum, maximum]), as
/// "VALUE is outside [min, max] (UNIT)" and the like; nothing when it is inside.
std::optional<std::string> bakeSetValueProblem(const BakeSetRange& range, double value);

/// A direction row (length_tolerance > 0)'s check of a whole vector (each component by bakeSetValueProblem first): nothing, or
/// "(x, y, z) has length L, not 1".
std::optional<std::string> bakeSetDirectionProblem(const BakeSetRange& range, double x, double y, double z);

/// The first texel of `image` (RGBA floats, width columns) outside one of the kTexels rows `ranges`, as the
/// field "texel (x, y) channel C" (x the column, y the row from the top) and the problem, which names the row's
/// field; nothing when every texel is inside. Linear in the image's size.
struct BakeSetTexelProblem {
    std::string field;
    std::string problem;
};
std::optional<BakeSetTexelProblem> findBakeSetTexelProblem(const BakeSetImage& image,
                                                           std::initializer_list<BakeSetRange> ranges);

}  // namespace gusuku

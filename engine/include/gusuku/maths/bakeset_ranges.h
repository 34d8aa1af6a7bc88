#pragma once
// The ranges a bake set's numbers must lie in, written once: the manifest reader refuses a value outside them,
// the writer refuses to write one (it reads back what it wrote), the loader checks the images' texels against
// them, and docs/bakeset.md's table is tested to list exactly these. gusuku_maths: the standard library only.

namespace gusuku {

/// A closed range [minimum, maximum] of one bake set field, with its unit and the reason for its bounds.
struct BakeSetRange {
    const char* field;  ///< as docs/bakeset.md names it
    double minimum;
    double maximum;
    const char* unit;
};

/// Ground cells from a millimetre (finer is no ground survey) to the largest cell site.json allows.
inline constexpr BakeSetRange kBakeSetGroundCellM{"ground_grid.cell_m", 1e-3, 100.0, "m"};
/// The grid's south-west corner within site.json's own ENU bounds (100 km of the site reference).
inline constexpr BakeSetRange kBakeSetGroundOriginM{"ground_grid.origin_enu_m", -1e5, 1e5, "m"};
/// Irradiance, a texel's or the sun's: pi times the brightest radiance a sky may hold (1e15) with a thousandfold
/// margin for bounces, far enough below float's 3.4e38 that the runtime's sums over a lightmap stay finite.
inline constexpr BakeSetRange kBakeSetIrradiance{"irradiance (texels' RGB, sun irradiance_rgb)", 0.0, 1e18,
                                                 "sky units x sr"};
/// A present sun is above the horizon: its apparent (refracted) elevation may reach a little below 0 while its
/// disc still shows; a sun lower than that is absent.
inline constexpr BakeSetRange kBakeSetPresentSunElevationDeg{"slots[].sun.apparent_elevation_deg (sun present)", -1.0,
                                                             90.0, "degrees"};
/// The texels a slot may count as invalid: at most every texel of the largest lightmap (8192^2).
inline constexpr BakeSetRange kBakeSetInvalidTexels{"slots[].invalid_texels", 0.0, 67108864.0, "texels"};

/// Every range above, in the order docs/bakeset.md lists them.
inline constexpr BakeSetRange kBakeSetRanges[] = {kBakeSetGroundCellM, kBakeSetGroundOriginM, kBakeSetIrradiance,
                                                  kBakeSetPresentSunElevationDeg, kBakeSetInvalidTexels};

/// How far a sun's direction_enu may be from the direction its azimuth and elevation give, in degrees: the
/// writer rounds neither, so anything more is an edit.
inline constexpr double kBakeSetSunDirectionToleranceDeg = 0.01;
/// How far a ground normal's length may be from 1.
inline constexpr double kBakeSetGroundNormalLengthTolerance = 1e-3;

}  // namespace gusuku

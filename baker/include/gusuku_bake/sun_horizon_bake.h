#pragma once
// The baker's sun horizons (gusuku/formats/sun_horizon.h, docs/bakeset.md "Sun horizons"): per lightmap texel,
// the elevation in each of eight world azimuths below which a ray from the texel meets the scene within
// kSunHorizonRadiusM. CPU rays through the bake's BVH (occludedCpu), on every hardware thread; about 150 short
// rays a texel (0.8 s for 40,000 texels on two cores).

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/formats/sun_horizon.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/lightmap_uv.h"

namespace gusuku::bake {

/// The horizon in degrees ([0, 90]) from `point` on a surface of unit geometric normal `normal` (the ray starts
/// 0.2 mm off it) at `azimuth_deg` east of north: the highest elevation whose ray is blocked within radius_m,
/// found on a 6-degree ladder from 0 and refined by bisection to 0.375 degrees. 0: nothing blocks even the
/// horizontal ray. A surface's own tangent plane counts (an east-facing roof's horizon to the west is its pitch).
double traceSunHorizonDeg(const Bvh& bvh, const glm::vec3& point, const glm::vec3& normal, double azimuth_deg,
                          double radius_m = kSunHorizonRadiusM, uint32_t skip_flags = 0);

/// Every texel's eight horizons, encoded (sun_horizon.h's layout) into a resolution^2 image pair. Texels no
/// texel covers take their chart's neighbours' horizons (dilateLightmapWithinCharts, 8 texels, as the
/// lightmaps), so bilinear reads at a chart's edge see no open horizon; with `reader_charts` empty, none are
/// filled (they stay open). skip_flags: triangles the rays pass (the bake passes alpha-masked ones, whose holes
/// the runtime's shadow map draws).
BakeSetSunHorizon bakeSunHorizons(const Bvh& bvh, const std::vector<LightmapTexel>& texels, int resolution,
                                  const std::vector<int32_t>& reader_charts, double radius_m = kSunHorizonRadiusM,
                                  uint32_t skip_flags = 0);

/// The horizons' resolution for a lightmap of `lightmap_resolution` at `texels_per_metre`: the lightmap's times
/// the smallest whole factor (at most kMaxSunHorizonFactor, the result at most kMaxSunHorizonResolution) that makes
/// a horizon texel at most kSunHorizonTargetTexelM (3.2 cm: a round tile row of 25 cm spans 8).
inline constexpr double kSunHorizonTargetTexelM = 1.0 / 32.0;
/// 2, not 4: the horizons are traced on the CPU (about 1,200 rays a texel), and a factor of 4 made the sample's
/// 1-sample bake's horizon image 624^2 (3.1 MB of its 4.2 MiB pack) and the test suite's house bake 4x slower
/// (10.8 s -> 42 s); at 2 the sample's texels are 6.25 cm, still 4 across a 25 cm tile row.
inline constexpr int kMaxSunHorizonFactor = 2;
int sunHorizonResolution(int lightmap_resolution, double texels_per_metre);

}  // namespace gusuku::bake

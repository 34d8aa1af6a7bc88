#pragma once
// What a bake refuses or warns about before it traces a single ray, shared by `gusuku-bake check` and
// `gusuku-bake bake` so both say the same thing: dates the sun code cannot place, suns below the horizon, a
// building with no surface to bake, a ground grid with no ground under it, and buffers the device cannot hold.

#include <cstdint>
#include <string>
#include <vector>

#include "bake_geometry.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku/maths/sun.h"
#include "gusuku_bake/sky_light.h"

namespace gusuku::bake {

struct SlotSun {
    std::string slot;
    SunPosition position;
};

/// NREL SPA for each sunny slot. A date outside the years SPA covers throws
/// InputError(site.file, "/bake/date", ...) rather than failing later inside the bake.
std::vector<SlotSun> slotSunPositions(const SiteConfig& site);

/// The lowest apparent elevation of the suns above the horizon (what sizes the ground grid), or -1 when no
/// slot has its sun up.
double lowestSunElevationDeg(const std::vector<SlotSun>& suns);

/// "slot X: the sun is below the horizon ..." for each sunny slot whose sun is down (it bakes with sky light
/// only).
std::vector<std::string> sunsBelowHorizon(const std::vector<SlotSun>& suns);

/// Throws InputError(site.file, "/building/path", ...) when the building has no lightmap texel to bake (no
/// triangles, or all of them degenerate, e.g. coordinates so large that float precision collapses them).
void refuseBuildingWithoutTexels(const SiteConfig& site, const BakeGeometry& geometry);

/// Empty when some ground cell lies on the ground; otherwise why none does (the ground terms will be empty:
/// the bake still runs, its ground images have alpha 0 everywhere).
std::string emptyGroundReason(const SiteConfig& site, const BakeGeometry& geometry);

/// Largest storage buffer the bake may use: the device's maxStorageBufferRange, lowered by the environment
/// variable GUSUKU_MAX_STORAGE_BUFFER_BYTES when set (to check a site for a smaller device than this one).
uint64_t storageBufferLimitBytes(uint64_t device_max_storage_buffer_range);

/// One storage buffer the tracer will create, the site.json field that sizes it, and its size.
struct DeviceBuffer {
    std::string field;  ///< JSON pointer into site.json
    std::string what;   ///< "building lightmap query points (1234567 texels)"
    uint64_t bytes = 0;
};

/// Every storage buffer of the bake whose size the site decides: the scene (BVH, shading, textures), each sky's
/// radiance and sampling tables, the building texels' and ground cells' points and sums.
std::vector<DeviceBuffer> bakeDeviceBuffers(const SiteConfig& site, const BakeGeometry& geometry,
                                            const std::vector<std::pair<std::string, const SkySamplingTables*>>& skies,
                                            int max_texture_size);

/// InputError(site.file, field, "... needs N MiB in one storage buffer, over the device's maxStorageBufferRange
/// of M MiB; ...") for each buffer over `limit_bytes`.
std::vector<InputError> deviceLimitProblems(const SiteConfig& site, const std::vector<DeviceBuffer>& buffers,
                                            uint64_t limit_bytes);

}  // namespace gusuku::bake

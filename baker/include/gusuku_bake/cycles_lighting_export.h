#pragma once
// A slot's lighting exactly as the bake traces it, written for another renderer (bench/cycles: Blender's Cycles
// bakes the same lightmap to compare against). The sky map is the one the tracer samples (the sun disc taken
// out, the same texels), re-laid out in Blender's equirectangular convention so it needs no mapping node; the
// sun is the tracer's disc light (direction, irradiance at normal incidence, angular radius).

#include <string>

#include "gusuku/assets/site.h"

namespace gusuku::bake {

/// Writes into `folder` (created if missing):
///  - `sky_<slot>.hdr`: the slot's sky without its sun, radiance per texel as the tracer reads it, laid out for
///    Blender's world equirectangular lookup with ENU as Blender's (x, y, z) (as the bake set's building.glb
///    imports): column u = 0.5 - atan2(y, x) / (2 pi), row 0 the zenith. Same size as the site's map.
///  - `sun_<slot>.json`: {"present", "direction_enu" [3], "irradiance_rgb" [3], "angular_radius_deg"}; present is
///    false for an overcast slot or a sun below the horizon.
/// Throws std::invalid_argument for a slot the site does not have; InputError for unreadable inputs.
void exportSlotLightingForCycles(const SiteConfig& site, const std::string& slot_name, const std::string& folder);

}  // namespace gusuku::bake

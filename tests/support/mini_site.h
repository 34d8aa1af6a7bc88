#pragma once
// A tiny site written to disk for bake tests: a 2 m box house on a flat stand-in ground (no sfm_mesh), a
// smooth sky with no sun disc (so E_sun comes from the clear-sky model), one sunny slot and one overcast slot.

#include <string>

namespace gusuku::testing {

struct MiniSiteOptions {
    int samples_per_texel = 4;
    double texels_per_metre = 4.0;
    int max_bounces = 2;
    bool with_overcast_slot = true;
};

/// Writes building.glb, sky_sunny.hdr, sky_overcast.hdr and site.json into dir; returns the site.json path.
std::string writeMiniSite(const std::string& dir, const MiniSiteOptions& options = {});

}  // namespace gusuku::testing

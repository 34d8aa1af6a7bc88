#pragma once
// A tiny site written to disk for bake tests: a 2 m box house on a flat stand-in ground (no sfm_mesh unless asked), a
// smooth sky with no sun disc (so E_sun comes from the clear-sky model), one sunny slot and one overcast slot.

#include <string>

#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"

namespace gusuku::testing {

struct MiniSiteOptions {
    int samples_per_texel = 4;
    double texels_per_metre = 4.0;
    int max_bounces = 2;
    bool with_overcast_slot = true;
    /// Adds site.glb as the sfm_mesh (Y-up glTF): a ground finely tessellated at z = 0 (12 m half size, 0.5 m
    /// quads) and a 1 m wall just south of the house, so the bake writes an occluder worth simplifying.
    bool with_sfm_mesh = false;
};

/// Writes building.glb, sky_sunny.hdr, sky_overcast.hdr, site.json (and site.glb) into dir; returns site.json's path.
std::string writeMiniSite(const std::string& dir, const MiniSiteOptions& options = {});

/// A mini site of `samples_per_texel` (the other options at their defaults) written into dir and loaded.
inline SiteConfig loadMiniSite(const std::string& dir, int samples_per_texel) {
    MiniSiteOptions options;
    options.samples_per_texel = samples_per_texel;
    return loadSiteConfig(writeMiniSite(dir, options));
}

/// Options for an in-process bake into output_dir that a test may stop anywhere: no progress bar, and one sample
/// per chunk (the chunks' length adapts to target_chunk_seconds), so every sample is a place to stop.
inline bake::BakeOptions stoppableBakeOptions(const std::string& output_dir) {
    bake::BakeOptions options;
    options.show_progress = false;
    options.target_chunk_seconds = 1e-6;
    options.output_dir = output_dir;
    return options;
}

}  // namespace gusuku::testing

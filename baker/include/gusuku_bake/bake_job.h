#pragma once
// A whole bake: site.json in, bake set out (manifest.json, the building with its lightmap UVs, per-slot
// lightmaps and ground terms as EXR). Progress on stderr; interruptible and resumable through checkpoints;
// every output written to a temporary name and renamed. The bake set format is documented in docs/bakeset.md.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/assets/site.h"
#include "gusuku/gpu/vulkan_context.h"

namespace gusuku::bake {

// The bake set layout's version, kBakeSetFormat, is gusuku/formats/bakeset_manifest.h's (gusuku::kBakeSetFormat).

/// The side the bake set's building textures are held to by default (BakeOptions::building_texture_size): the
/// camera tracer's own (camera_tracer.h), so that the runtime draws the texture detail the bench's truth traces.
constexpr int kDefaultBuildingTextureSize = 2048;

struct BakeOptions {
    std::string output_dir;
    bool force = false;             ///< bake even when the manifest says the bake set is up to date
    int samples_override = 0;       ///< > 0: use instead of bake.samples_per_texel
    bool denoise = true;            ///< edge-keeping filter on the building lightmap
    /// The building's samples from kMinAdaptiveSamples on: a quarter (at least 16) to every texel alike as a
    /// pilot, the rest by each texel's noise (adaptive_sampling.h); false: every texel alike. The ground's
    /// cells are always sampled alike.
    bool adaptive_sampling = true;
    bool show_progress = true;
    /// Non-empty: bake only this slot of the site into a partial bake set (manifest marked "partial", naming
    /// the slot; docs/bakeset.md), to be joined with the other slots' partial sets by mergePartialBakeSets
    /// (gusuku_bake/bake_merge.h). Everything but the slot's own files is what the whole bake writes.
    std::string slot;
    int max_texture_size = 512;     ///< albedo textures are downsampled to this for tracing
    /// The building's base-colour textures as building.glb (and the runtime pack) keep them for the runtime:
    /// downsampled to fit this side, never enlarged. The tracers still read them at max_texture_size (a
    /// bounce's albedo needs no detail), but the runtime draws them: at 512 the shared shrine's 2048^2
    /// structure texture lost the detail the camera tracer's truth (2048) shows (docs/measurements.md).
    int building_texture_size = kDefaultBuildingTextureSize;
    /// The length each GPU dispatch aims at (gusuku_bake/dispatch_budget.h): a stop waits for at most about
    /// one, and a pass over a large set is cut into point ranges to keep to it.
    double target_chunk_seconds = 0.25;
    /// Polled between setup steps and between dispatches; returning true checkpoints and stops
    /// (BakeReport::completed = false).
    std::function<bool()> should_stop;
};

/// One slot's invalid building texels (alpha 0 in its lightmap, filled by dilation) and why, by what their first
/// rays see from the texel's centre (invalid_texel_reasons.h): each texel counted once, under its main reason.
struct InvalidTexelCounts {
    std::string slot;
    size_t total = 0;
    size_t one_sided_backs = 0;      ///< behind a one-sided face of the building (a wall's inner side)
    size_t under_ground = 0;         ///< the site's ground seen from below: the building's foot, or a part sunk in it
    size_t closed_double_sided = 0;  ///< inside a closed part of double-sided faces, by its winding (closed_parts.h)
    size_t unexplained = 0;          ///< the re-traced rays found none of these (a texel at the limit of noise)
};

struct BakeReport {
    bool completed = false;         ///< false: stopped by should_stop; rerun to resume
    bool up_to_date = false;        ///< nothing to do: the manifest matches these inputs
    std::string manifest_path;
    uint32_t samples_per_point = 0;
    size_t building_texels = 0;
    size_t masked_triangles = 0;       ///< triangles of alpha-masked materials
    size_t alpha_tested_triangles = 0; ///< of those, the ones whose footprint holds a hole (the tracer tests these)
    size_t ground_cells = 0;
    int lightmap_resolution = 0;
    uint64_t rays_traced = 0;       ///< this run's rays (not those of resumed work)
    double trace_seconds = 0.0;     ///< this run's time in the trace loop
    double wall_seconds = 0.0;      ///< this run, all of it
    double resumed_fraction = 0.0;  ///< share of the work taken from checkpoints
    std::vector<std::string> warnings;
    std::vector<InvalidTexelCounts> invalid_texels;  ///< per slot traced, in the site's order
};

BakeReport runBake(VulkanContext& context, const SiteConfig& site, const BakeOptions& options);

/// Throws InputError(site.file, "/bake/slots", "has no slot ...", listing the site's slots) unless `slot` is one
/// of the site's slots. runBake checks BakeOptions::slot with it; a command line can check before it opens a device.
void requireSiteSlot(const SiteConfig& site, const std::string& slot);

}  // namespace gusuku::bake

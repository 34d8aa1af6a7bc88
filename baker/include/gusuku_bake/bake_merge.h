#pragma once
// Joining partial bake sets: a site's slots baked one per machine (`gusuku-bake bake --slot NAME`, BakeOptions::
// slot) are merged into the bake set one machine would have written, byte for byte except the manifest's
// `statistics` (docs/bakeset.md, "Baking on several machines").

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_manifest.h"

namespace gusuku::bake {

/// FNV-1a 64 over the files every slot of a bake set shares, each as its name then its bytes, in this order:
/// manifest.building.mesh, manifest.ground_grid.geometry, manifest.occluder->mesh when there is one (all in
/// `folder`). Every partial set of one site must give the same value. Throws InputError naming a file that
/// cannot be read.
uint64_t slotIndependentFilesHash(const std::string& folder, const BakeSetManifest& manifest);

/// FNV-1a 64 over one slot of a set in `folder`: its manifest entry as the writer writes it (bakeSetSlotJson),
/// then its building, ground-with and ground-without files, each as its name then its bytes. A partial set
/// records it (partial.slot_hash) and merge recomputes it. Throws InputError naming a file that cannot be read.
uint64_t slotHash(const std::string& folder, const BakeSetSlot& slot);

struct MergeReport {
    std::string manifest_path;
    size_t slots = 0;
    /// The merged manifest's statistics: rays and trace seconds summed over the partial sets (the work of all
    /// machines), rays_per_second their ratio, wall_seconds the longest partial bake's (they run side by side).
    BakeSetStatistics statistics;
};

/// Checks every partial set, then writes the whole bake set into output_dir. Refused, each as one InputError
/// `FILE: FIELD: PROBLEM` before anything is created or written:
///   - a folder without manifest.json, or whose manifest is not a partial set's (no "partial");
///   - partial sets of different inputs or settings: an input_hash, the site's slot list, the inputs' hashes,
///     site, settings, building, ground grid, occluder or warnings that differ from the first set's;
///   - shared files (building.glb, ground_geometry.exr, occluder.glb) whose bytes do not hash to what their
///     manifest recorded, or differ from the first set's;
///   - a slot given twice, a slot of the site given by none, a slot file missing;
///   - an output folder that is one of the partial sets, or that the output guard refuses
///     (gusuku_bake/output_guard.h: is or holds an input of the bake; is, holds or lies inside a bake set or pack
///     other than an earlier set of the same site);
///   - an output folder another bake or merge holds (its .lock).
/// Writing goes as a bake's does: the output's old manifest.json is removed first, every file is copied to a
/// temporary name and renamed, the manifest is written last; so a folder with a manifest is a complete set.
MergeReport mergePartialBakeSets(const std::vector<std::string>& partial_folders, const std::string& output_dir);

}  // namespace gusuku::bake

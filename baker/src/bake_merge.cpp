// mergePartialBakeSets (gusuku_bake/bake_merge.h): read and check every partial set first, write second.
#include "gusuku_bake/bake_merge.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/bake_folder_lock.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku_bake/output_guard.h"

namespace gusuku::bake {

namespace {

namespace fs = std::filesystem;

struct PartialSet {
    std::string folder;
    std::string manifest_path;
    BakeSetManifest manifest;
};

std::string hex(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

PartialSet readPartialSet(const std::string& folder) {
    PartialSet set{folder, folder + "/manifest.json", {}};
    std::error_code error;
    if (!fs::exists(set.manifest_path, error))
        throw InputError(set.manifest_path, "",
                         "file not found: not a partial bake set, or its bake has not finished (the manifest is "
                         "written last)");
    set.manifest = readBakeSetManifest(set.manifest_path);
    if (!set.manifest.partial)
        throw InputError(set.manifest_path, "/partial",
                         "missing: this is a whole bake set, not one slot's partial set (bake with --slot NAME)");
    return set;
}

/// The partial set must have been baked from the first one's inputs and settings: everything but its own slot
/// and the statistics must agree. The input_hash says it first; the rest names what differs when it does not.
void requireSameBake(const PartialSet& first, const PartialSet& other) {
    const BakeSetManifest& a = first.manifest;
    const BakeSetManifest& b = other.manifest;
    const std::string from = " differs from " + first.manifest_path + "'s";
    const std::string why = ": the partial sets were baked from different inputs or settings";
    if (a.input_hash != b.input_hash)
        throw InputError(other.manifest_path, "/input_hash",
                         "\"" + hex(b.input_hash) + "\"" + from + " \"" + hex(a.input_hash) + "\"" + why +
                             " (or by another gusuku-bake)");
    if (a.partial->site_slots != b.partial->site_slots)
        throw InputError(other.manifest_path, "/partial/site_slots", "the site's slot list" + from + why);
    if (a.inputs.size() != b.inputs.size())
        throw InputError(other.manifest_path, "/inputs", std::to_string(b.inputs.size()) + " inputs" + from + why);
    for (size_t i = 0; i < a.inputs.size(); ++i)
        if (a.inputs[i].role != b.inputs[i].role || a.inputs[i].fnv1a64 != b.inputs[i].fnv1a64)
            throw InputError(other.manifest_path, "/inputs/" + std::to_string(i),
                             "the " + b.inputs[i].role + " input (hash " + b.inputs[i].fnv1a64 + ")" + from + why);
    const auto require = [&](bool same, const char* pointer) {
        if (!same) throw InputError(other.manifest_path, pointer, std::string("the value") + from + why);
    };
    require(a.site == b.site, "/site");
    require(a.settings == b.settings, "/settings");
    require(a.building == b.building, "/building");
    require(a.ground_grid == b.ground_grid, "/ground_grid");
    require(a.occluder == b.occluder, "/occluder");
    require(a.warnings == b.warnings, "/warnings");
}

/// Recomputes the shared files' hash rather than trusting the manifest: it must be what the bake recorded (the
/// files were not changed since) and the first set's (the bakes agreed on charts, ground and occluder).
uint64_t checkedSharedFilesHash(const PartialSet& set) {
    const uint64_t actual = slotIndependentFilesHash(set.folder, set.manifest);
    if (actual != set.manifest.partial->slot_independent_hash)
        throw InputError(set.manifest_path, "/partial/slot_independent_hash",
                         "the shared files (" + set.manifest.building.mesh + ", " + set.manifest.ground_grid.geometry +
                             (set.manifest.occluder ? ", " + set.manifest.occluder->mesh : std::string()) +
                             (set.manifest.building.sun_horizon.empty() ? std::string()
                                                                        : ", " + set.manifest.building.sun_horizon) +
                             ") hash to " + hex(actual) + ", not the recorded " +
                             hex(set.manifest.partial->slot_independent_hash) + ": they changed after the bake");
    return actual;
}

/// folder/name, which must be a regular file (the manifest names it at `pointer`).
std::string requiredFile(const PartialSet& set, const std::string& pointer, const std::string& name) {
    const std::string path = set.folder + "/" + name;
    std::error_code error;
    if (name.find('/') != std::string::npos || name == "." || name == ".." || !fs::is_regular_file(path, error))
        throw InputError(set.manifest_path, pointer, "names \"" + name + "\", which is not a file in " + set.folder);
    return path;
}

bool sameFolder(const std::string& a, const std::string& b) {
    std::error_code error;
    return fs::exists(a, error) && fs::exists(b, error) && fs::equivalent(a, b, error);
}

// Read whole and written through writeBytesAtomically, whose checked writes name a full disk as "No space left
// on device" (std::filesystem::copy_file's kernel copy reported it as "Input/output error").
void copyAtomically(const std::string& from, const std::string& to) {
    const std::string bytes = readWholeFile(from);
    writeBytesAtomically(to, bytes.data(), bytes.size());
}

/// A slot's sky map in the merged manifest: the merged path of the input it is (the sets agree on their inputs'
/// roles and bytes, so this is the first set's path even when this set's machine saw the site somewhere else),
/// else its own path made relative to the output folder.
std::string mergedSkyMapPath(const PartialSet& set, const std::string& sky_map,
                             const std::vector<BakeSetInput>& merged_inputs, const std::string& output_dir) {
    const std::string resolved = resolveBakeSetInputPath(set.folder, set.manifest, sky_map);
    for (size_t i = 0; i < set.manifest.inputs.size() && i < merged_inputs.size(); ++i)
        if (resolveBakeSetInputPath(set.folder, set.manifest, set.manifest.inputs[i].path) == resolved)
            return merged_inputs[i].path;
    return bakeSetRelativeInputPath(output_dir, resolved);
}

}  // namespace

uint64_t slotIndependentFilesHash(const std::string& folder, const BakeSetManifest& manifest) {
    ContentHash hash;
    hash.addString(manifest.building.mesh).addFile(folder + "/" + manifest.building.mesh);
    hash.addString(manifest.ground_grid.geometry).addFile(folder + "/" + manifest.ground_grid.geometry);
    if (!manifest.ground_grid.albedo.empty())
        hash.addString(manifest.ground_grid.albedo).addFile(folder + "/" + manifest.ground_grid.albedo);
    if (manifest.occluder) hash.addString(manifest.occluder->mesh).addFile(folder + "/" + manifest.occluder->mesh);
    if (!manifest.building.sun_horizon.empty())
        hash.addString(manifest.building.sun_horizon).addFile(folder + "/" + manifest.building.sun_horizon);
    return hash.value();
}

uint64_t slotHash(const std::string& folder, const BakeSetSlot& slot) {
    ContentHash hash;
    hash.addString(bakeSetSlotJson(slot));
    for (const std::string* file :
         {&slot.building_irradiance, &slot.ground_irradiance_with_building, &slot.ground_irradiance_without_building})
        hash.addString(*file).addFile(folder + "/" + *file);
    return hash.value();
}

MergeReport mergePartialBakeSets(const std::vector<std::string>& partial_folders, const std::string& output_dir) {
    if (partial_folders.empty()) throw InputError(output_dir, "PARTIAL", "no partial sets to merge");
    // ---- Read and check everything; nothing is created or written until all of it passes.
    std::vector<PartialSet> sets;
    for (const std::string& folder : partial_folders) sets.push_back(readPartialSet(folder));
    const PartialSet& first = sets.front();
    const uint64_t shared_hash = checkedSharedFilesHash(first);
    for (size_t i = 1; i < sets.size(); ++i) {
        requireSameBake(first, sets[i]);
        const uint64_t hash = checkedSharedFilesHash(sets[i]);
        if (hash != shared_hash)
            throw InputError(sets[i].manifest_path, "/partial/slot_independent_hash",
                             "the shared files hash to " + hex(hash) + ", " + first.manifest_path + "'s to " +
                                 hex(shared_hash) + ": the partial bakes disagree on the building's charts, the "
                                 "ground grid or the occluder");
    }
    // Every file is read and checked as the loader would read the merged set (sizes, finite texels, irradiance
    // >= 0), so a truncated, empty, resized or NaN slot file is refused here, not by the first render after. One
    // set at a time: only the verdict is kept.
    for (const PartialSet& set : sets) loadPartialBakeSet(set.folder);
    // Each set's own slot must be what its bake wrote: the manifest entry (an edited sun irradiance) and its
    // three files, hashed together, against the hash the partial recorded.
    for (const PartialSet& set : sets) {
        const std::optional<uint64_t>& recorded = set.manifest.partial->slot_hash;
        if (!recorded)
            throw InputError(set.manifest_path, "/partial/slot_hash",
                             "missing: a partial set from an older gusuku-bake, whose slot cannot be checked; bake "
                             "its slot again");
        const uint64_t actual = slotHash(set.folder, set.manifest.slots.front());
        if (actual != *recorded)
            throw InputError(set.manifest_path, "/partial/slot_hash",
                             "the slot \"" + set.manifest.partial->slot + "\" (its manifest entry and files) hashes to " +
                                 hex(actual) + ", not the recorded " + hex(*recorded) + ": it changed after the bake");
    }
    std::map<std::string, size_t> set_of_slot;
    for (size_t i = 0; i < sets.size(); ++i) {
        const std::string& slot = sets[i].manifest.partial->slot;
        const auto [entry, inserted] = set_of_slot.emplace(slot, i);
        if (!inserted)
            throw InputError(sets[i].manifest_path, "/partial/slot",
                             "slot \"" + slot + "\" is also the slot of " + sets[entry->second].manifest_path +
                                 ": give each slot's partial set once");
    }
    for (const std::string& slot : first.manifest.partial->site_slots)
        if (!set_of_slot.count(slot))
            throw InputError(first.manifest_path, "/partial/site_slots",
                             "the site's slot \"" + slot + "\" is in none of the " + std::to_string(sets.size()) +
                                 " partial sets given: bake it with --slot " + slot);
    std::vector<std::pair<std::string, std::string>> copies;  // from, to-name
    const BakeSetManifest& shared = first.manifest;
    copies.push_back({requiredFile(first, "/building/mesh", shared.building.mesh), shared.building.mesh});
    copies.push_back(
        {requiredFile(first, "/ground_grid/geometry", shared.ground_grid.geometry), shared.ground_grid.geometry});
    if (shared.occluder)
        copies.push_back({requiredFile(first, "/occluder/mesh", shared.occluder->mesh), shared.occluder->mesh});
    if (!shared.ground_grid.albedo.empty())
        copies.push_back(
            {requiredFile(first, "/ground_grid/albedo", shared.ground_grid.albedo), shared.ground_grid.albedo});
    if (!shared.building.sun_horizon.empty())
        copies.push_back(
            {requiredFile(first, "/building/sun_horizon", shared.building.sun_horizon), shared.building.sun_horizon});
    for (const std::string& name : shared.partial->site_slots) {
        const PartialSet& set = sets[set_of_slot.at(name)];
        const BakeSetSlot& slot = set.manifest.slots.front();
        for (const auto& [field, file] : {std::pair{"building_irradiance", &slot.building_irradiance},
                                          {"ground_irradiance_with_building", &slot.ground_irradiance_with_building},
                                          {"ground_irradiance_without_building",
                                           &slot.ground_irradiance_without_building}})
            copies.push_back({requiredFile(set, std::string("/slots/0/") + field, *file), *file});
    }
    std::vector<std::string> inputs;
    for (const BakeSetInput& input : shared.inputs)
        inputs.push_back(resolveBakeSetInputPath(first.folder, shared, input.path));
    for (const PartialSet& set : sets)
        if (sameFolder(set.folder, output_dir))
            throw InputError(output_dir, "-o", "is the partial set " + set.folder + "; merge into another folder");
    OutputRequest output_request;
    output_request.output = output_dir;
    output_request.command = "merge";
    output_request.kind = OutputKind::kBakeSet;
    output_request.inputs = inputs;
    for (const PartialSet& set : sets) output_request.read_sets.push_back(set.folder);
    for (size_t i = 0; i < shared.inputs.size(); ++i)
        if (shared.inputs[i].role == "site") output_request.site_json = inputs[i];
    refuseUnsafeOutput(output_request);

    // ---- Write, as a bake does: the old manifest first out, every file renamed into place, the manifest last.
    const BakeFolderLock lock(output_dir);
    MergeReport report;
    report.manifest_path = output_dir + "/manifest.json";
    fs::remove(report.manifest_path);
    for (const auto& [from, name] : copies) copyAtomically(from, output_dir + "/" + name);

    BakeSetManifest merged = shared;
    merged.partial.reset();
    merged.input_paths_relative_to_folder = true;
    for (size_t i = 0; i < merged.inputs.size(); ++i)
        merged.inputs[i].path = bakeSetRelativeInputPath(output_dir, inputs[i]);
    merged.slots.clear();
    merged.statistics = {};
    for (const std::string& name : shared.partial->site_slots) {
        const PartialSet& set = sets[set_of_slot.at(name)];
        BakeSetSlot slot = set.manifest.slots.front();
        slot.sky_map = mergedSkyMapPath(set, slot.sky_map, merged.inputs, output_dir);
        merged.slots.push_back(slot);
        merged.statistics.rays_traced += set.manifest.statistics.rays_traced;
        merged.statistics.trace_seconds += set.manifest.statistics.trace_seconds;
        merged.statistics.wall_seconds = std::max(merged.statistics.wall_seconds, set.manifest.statistics.wall_seconds);
    }
    if (merged.statistics.trace_seconds > 0.0)
        merged.statistics.rays_per_second = double(merged.statistics.rays_traced) / merged.statistics.trace_seconds;
    writeBakeSetManifest(report.manifest_path, merged);
    report.slots = merged.slots.size();
    report.statistics = merged.statistics;
    return report;
}

}  // namespace gusuku::bake

#pragma once
// The runtime pack reader (docs/bakeset.md, "The runtime pack"): BAKESET/pack/ into gusuku::BakeSetData with the
// C++ standard library alone (library gusuku_pack_loader, CMake gusuku::pack_loader, which a phone app links
// beside gusuku::runtime; also built with GUSUKU_RUNTIME_ONLY). The C API's entry is gusuku_bakeset_load_pack
// (gusuku/pack_loader/gusuku_pack_loader.h).

#include <string>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

/// Reads the pack in `folder` (a pack folder, or a bake set folder holding pack/): manifest.json, pack.bin, every
/// texture_<n>.ktx2, and per slot the lightmap (E5B9G9R9 times pack.bin's lightmap_scale, alpha from its
/// _valid.ktx2, and its blocks in each format the format table gives a pack file (ASTC 4x4 HDR from _astc.ktx2,
/// each other from the file its row names) into building_blocks when the pack has them: a pack from before them has none,
/// and then every slot has none), and the ground images (float32), each at the manifest's sizes; then
/// findBakeSetProblem (which refuses a format's blocks in some slots only). Each
/// file is at most 1 GiB (the manifest 16 MiB) and a regular file. InputError "FILE: FIELD: PROBLEM" naming the first bad file and
/// field (a missing file, a truncated or malformed KTX2, another format, sizes that disagree with the manifest,
/// a validity texel neither 0 nor 255, the manifest's own problems); nothing half-loaded is returned.
BakeSetData loadRuntimePack(const std::string& folder);

}  // namespace gusuku

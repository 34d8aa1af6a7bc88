#pragma once
// The runtime pack's manifest.json (the bake set's, copied) read into gusuku::BakeSetManifest with the C++
// standard library alone: every field the runtime draws from (site, building, ground grid, occluder, slots with
// their suns and colour statistics) must be there with its type; the fields that only say how the set was made
// (inputs, settings, statistics, warnings) are read when present and otherwise left empty, since the tools' reader
// (gusuku/assets/bakeset_manifest_json.h) is the one that checks them. Private to gusuku_pack_loader.

#include <string>

#include "gusuku/formats/bakeset_manifest.h"

namespace gusuku::pack_detail {

/// InputError(file, "/json/pointer", problem) for a field missing or of the wrong type, a format other than
/// gusuku-bakeset/1, a partial set, a sky that is neither sunny nor overcast, a count out of range.
BakeSetManifest readPackManifest(const std::string& text, const std::string& file);

}  // namespace gusuku::pack_detail

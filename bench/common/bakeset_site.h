#pragma once
// What the tools read from a loaded bake set's manifest beyond the runtime's data: the site.json it was baked
// from, and its bake date's noon on the site's clock (the default instant of a frame).

#include <optional>
#include <string>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::bench_common {

/// site.json of the bake: `explicit_site` when given; else the manifest's site input, resolved against the bake
/// set's folder (resolveBakeSetInputPath; an older manifest's as the bake named it, or relative to the folder). InputError naming
/// FOLDER/manifest.json when it names none or the file is gone.
std::string siteJsonOf(const std::string& bake_set_folder, const BakeSetManifest& manifest,
                       const std::optional<std::string>& explicit_site = std::nullopt);

/// UTC seconds of 00:00 on the bake date, site clock (from the first sunny slot's time). InputError naming
/// `option` when the bake set has no sunny slot.
double bakeDateMidnightUtc(const std::string& bake_set_folder, const BakeSetManifest& manifest,
                           const std::string& option);

}  // namespace gusuku::bench_common

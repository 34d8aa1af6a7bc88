// The tools' reading of a bake set's manifest (see bakeset_site.h).

#include "bakeset_site.h"

#include <filesystem>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"

namespace gusuku::bench_common {

std::string siteJsonOf(const std::string& bake_set_folder, const BakeSetManifest& manifest,
                       const std::optional<std::string>& explicit_site) {
    if (explicit_site) return *explicit_site;
    for (const BakeSetInput& input : manifest.inputs)
        if (input.role == "site") {
            // Relative to the bake set (or, in an older manifest, to where the bake ran).
            const std::string resolved = resolveBakeSetInputPath(bake_set_folder, manifest, input.path);
            if (std::filesystem::exists(resolved)) return resolved;
            const std::filesystem::path beside = std::filesystem::path(bake_set_folder) / input.path;
            if (std::filesystem::exists(beside)) return beside.string();
            throw InputError(bake_set_folder + "/manifest.json", "/inputs",
                             "its site " + input.path + " is not found; give --site SITE.json");
        }
    throw InputError(bake_set_folder + "/manifest.json", "/inputs", "names no site; give --site SITE.json");
}

double bakeDateMidnightUtc(const std::string& bake_set_folder, const BakeSetManifest& manifest,
                           const std::string& option) {
    for (const BakeSetSlot& slot : manifest.slots)
        if (!slot.utc.empty()) {
            const std::string local = formatIso8601(parseIso8601Utc(slot.utc), manifest.site.utc_offset_minutes);
            return parseDateAtOffset(local.substr(0, 10), manifest.site.utc_offset_minutes);
        }
    throw InputError(bake_set_folder, option, "the bake set has no sunny slot to take the date from; give " + option);
}

}  // namespace gusuku::bench_common

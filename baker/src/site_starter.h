#pragma once
// What `gusuku-bake init` writes (issue 42 item 5): a starter site.json whose comments say what each field is and
// how to measure it on site, and a checklist of what to bring back from the site. The place and the day are the
// command's options, never placeholders that would bake silently wrong light.

#include <string>

namespace gusuku::bake_cli {

struct SiteStarterPlace {
    std::string name = "my site";
    double latitude_deg = 0.0;
    double longitude_deg = 0.0;
    double height_m = 0.0;      ///< above the WGS84 ellipsoid
    std::string utc_offset;     ///< "+hh:mm" / "-hh:mm"
    std::string date;           ///< "YYYY-MM-DD"
};

/// site.json with // comments (the site reader accepts JSON with comments), naming building.glb, site.glb,
/// sky_sunny.hdr and sky_overcast.hdr beside it: the files `gusuku-bake sample` writes, so a starter beside the
/// sample's files passes `check`.
std::string siteStarterJson(const SiteStarterPlace& place);

/// CHECKLIST.md: what to measure and photograph on site, and the commands from survey to phone pack.
std::string siteChecklist(const SiteStarterPlace& place);

}  // namespace gusuku::bake_cli

// The texts `gusuku-bake init` writes (site_starter.h).

#include "site_starter.h"

#include <cstdio>

namespace gusuku::bake_cli {
namespace {

std::string number(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.7g", value);
    return text;
}

// A JSON string literal: the name is the user's text.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;  // no control characters in a name
        out += c;
    }
    return out + "\"";
}

}  // namespace

std::string siteStarterJson(const SiteStarterPlace& place) {
    return R"(// site.json for gusuku-bake (docs/site-json.md describes every field). Written by `gusuku-bake init`.
// Replace the four files it names (building.glb, site.glb, sky_sunny.hdr, sky_overcast.hdr) with yours, then run
// `gusuku-bake check site.json`: it names the first thing that is wrong and says what to change.
{
  "format": "gusuku-site/1",
  "site": {
    "name": )" + quoted(place.name) + R"(,
    // The reference point: the origin of the site's east-north-up metres. A GNSS fix on the ground near the
    // building; height above the WGS84 ellipsoid (what GNSS gives), not above sea level.
    "latitude_deg": )" + number(place.latitude_deg) + R"(,
    "longitude_deg": )" + number(place.longitude_deg) + R"(,
    "height_m": )" + number(place.height_m) + R"(,
    // The site's clock on the baked day (slot times are on it), with daylight saving if it applies that day.
    "utc_offset": ")" + place.utc_offset + R"("
  },
  // The photogrammetry mesh of the real site (glTF, PLY or OBJ): what the building's light bounces off and its
  // shadow falls on. Its own axes and units are mapped into east-north-up metres by a similarity:
  // `gusuku-bake georef GCPS.csv --site site.json` fits scale, rotation and translation from ground control
  // points and prints these three fields. Leave the whole block out to bake on a flat ground plane.
  "sfm_mesh": {
    "path": "site.glb",
    "scale": 1.0,
    "rotation_wxyz": [1.0, 0.0, 0.0, 0.0],
    "translation_enu_m": [0.0, 0.0, 0.0]
  },
  // The lost building: a glTF in metres, its origin at the base. enu_offset_m places that origin in east, north
  // and up metres from the reference point; heading_deg turns the model's -z (its "north") to that compass bearing.
  "building": {
    "path": "building.glb",
    "enu_offset_m": [0.0, 0.0, 0.0],
    "heading_deg": 0.0,
    "scale": 1.0
  },
  // The sky: a 360-degree HDR (or an exposure bracket of 8-bit photos) taken on site, level, from the building's
  // place. north_azimuth_in_image_deg: where north is in the picture (0-360 across its width). With a sunny photo,
  // add its time, "taken_at": "YYYY-MM-DDThh:mm+hh:mm" (EXIF DateTimeOriginal and the camera's UTC offset), and
  // north_azimuth_in_image_deg can be "auto": the north from the sun. `check` compares a number with the sun.
  "skies": {
    "sunny": {"path": "sky_sunny.hdr", "north_azimuth_in_image_deg": 0.0},
    "overcast": {"path": "sky_overcast.hdr", "north_azimuth_in_image_deg": 0.0}
  },
  // The day baked, on the site clock. Without "slots" it bakes sunny 09:00, 12:00, 15:00 and overcast.
  "bake": {
    "date": ")" + place.date + R"(",
    "texels_per_metre": 8,
    "samples_per_texel": 256
  }
}
)";
}

std::string siteChecklist(const SiteStarterPlace& place) {
    return "# " + place.name + R"(: what to bring back from the site

Written by `gusuku-bake init` beside site.json. Tick each line; `gusuku-bake check site.json` checks the files.

## Measure
- [ ] The reference point: latitude, longitude and **ellipsoid** height from a GNSS receiver (RTK if you have
      one), on the ground near where the building stood. site.json's `site` block.
- [ ] At least three ground control points, spread around the site and not in a line: marks that will show in
      the photogrammetry (painted crosses, survey nails), each with its GNSS position. Write them as
      `name,mesh_x,mesh_y,mesh_z,latitude,longitude,height` once you can read their mesh coordinates; then
      `gusuku-bake georef GCPS.csv --site site.json` gives site.json's `sfm_mesh` fields and each point's error.
- [ ] The building's origin: where its base sits, as an east-north-up offset from the reference point, and the
      compass bearing of its front.

## Photograph
- [ ] The site for photogrammetry (overlapping photos all round), to build the site mesh (glTF, PLY or OBJ).
- [ ] A 360-degree sky from the building's place, level, in sun: an HDR, or a bracket of 8-bit photos with EXIF.
      Note the time to the minute and where north is in the picture.
- [ ] The same under overcast, if you can: it gives the overcast slot its own sky.

## Then
1. `gusuku-bake check site.json`: fix what it names.
2. `gusuku-bake bake site.json -o bakeset`: the lightmaps (Ctrl-C stops; the same command resumes).
3. `bakeset/pack/` is the phone's pack; `gusuku-bake export bakeset -o building.glb` writes a glTF with the
   light for other engines.
)";
}

}  // namespace gusuku::bake_cli

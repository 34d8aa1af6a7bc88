#pragma once
// An 8-bit equirectangular photo (a consumer 360 camera's JPEG or PNG), or an exposure bracket of one view, as
// a sky radiance map in the bake's units (docs/site-json.md, "8-bit sky photos").
//
// Calibration. The bake's radiance unit for a sky photo is Radiance's W sr^-1 m^-2 per linear Rec.709 channel,
// so that one unit of luminance Y is kRadianceWhiteEfficacy = 179 cd m^-2 (gusuku/maths/exposure.h): a bake set
// lit by a photo has luminance_per_unit 179, as one lit by a Radiance-calibrated HDR map. The camera model is the
// runtime's own (exposure.h, ISO 12232 saturation-based speed, lens factor q = 0.65):
//
//     EV100   = log2(N^2 / t) - log2(S / 100)           (EXIF FNumber N, ExposureTime t in s, ISO speed S)
//     L_white = 78 / (q 100) x 2^EV100 = 1.2 x 2^EV100   cd m^-2, the luminance that just saturates the sensor
//     radiance_channel = srgbDecode(code / 255) x L_white / 179
//
// A reflected-light meter (K = 12.5 cd m^-2 s, L_meter = K x 2^EV100 / 100 = 0.125 x 2^EV100) puts the scene's
// mean at display-linear 0.125 / 1.2 = 0.104 of that: the same statement from the meter's side. So a runtime
// camera at the photo's EV100 shows the sky as the photo did (exposureFromEv100(ev100, 179) x radiance =
// srgbDecode(code / 255)). The camera's tone curve is taken to be the sRGB transfer function (what a JPEG
// declares); a camera's own shoulder near white is not modelled, one reason the top codes count as clipped.
//
// Clipped texels are unknown: a texel with any channel at or above kSkyPhotoClippedCode holds at least the
// saturation white, not its radiance. In a single photo its clipped channels become that white, L_white / 179 (a
// lower bound whose flat top the sun-disc extraction recognises as a clipped sun, so E_sun comes from the
// clear-sky model calibrated on the unclipped diffuse light: gusuku_bake/sky_light.h, slot_lighting.cpp); where
// only some channels clip, the others keep their value (the least radiance the codes allow).
// In a bracket each texel is the weighted mean of radiance_i = srgbDecode(code_i / 255) x L_white_i / 179 over
// the members that hold it unclipped, by a hat in the encoded value m (the brightest channel's code): the inverse
// square of the relative radiance step of one code at m (1/m in the sRGB curve's linear foot, about 2.4 / (m + 14)
// above), so a member counts by how precisely its 8 bits hold the texel, falling linearly to 0 over the 32 codes
// below the clip (a camera's shoulder, JPEG ringing; and no seam where a member starts to clip), plus 1e-6 so that
// a texel dark in every member still gets their mean. A texel clipped in every member takes the darkest
// member's lower bound, as a single photo. A bracket whose darkest member holds the sun unclipped gives a
// measured E_sun, not a modelled one. Memory: each member is held as 8-bit codes in 1/256ths (6 bytes a texel)
// while merging.
//
// Errors (InputError naming the file and the field, one line): not PNG or JPEG data, not 8 bits a channel, not
// 2:1 (equirectangular), bracket members of different sizes, no exposure (neither ev100 nor the EXIF fields
// ExposureTime, FNumber and Exif:PhotographicSensitivity), an EXIF value that is zero, negative or not finite,
// an EV100 (from EXIF or given) outside kSkyPhotoEv100Range, site.json's range for ev100 (a corrupt EXIF: an
// FNumber of 2.1e9 is EV100 72), a damaged file (a truncated JPEG: gusuku/assets/image.h).
// Photos larger than kMaxImageSide on a side are box-downsampled in their encoded values while read (as
// readImage does): near a clip edge such a texel mixes clipped and unclipped texels (a known limit).

#include <optional>
#include <string>
#include <vector>

#include "gusuku/assets/site.h"
#include "gusuku/maths/image_rgba.h"

namespace gusuku {

/// The lowest 8-bit code counted as clipped: JPEG's ringing leaves the texels beside a clipped region a few
/// codes under 255, and cameras compress their last codes.
inline constexpr int kSkyPhotoClippedCode = 250;

/// The extensions an 8-bit sky photo may have (lower case).
bool isSkyPhotoExtension(const std::string& lower_case_extension);

/// The photo's exposure: `ev100` when given, else from its EXIF ExposureTime, FNumber and ISO speed
/// (Exif:PhotographicSensitivity, or the older Exif:ISOSpeedRatings). InputError(path, field, ...) when absent
/// or invalid, or when the EV100 is outside kSkyPhotoEv100Range (field "EXIF exposure", naming the EXIF fields
/// and their values; "ev100" for a given one).
double skyPhotoEv100(const std::string& path, const std::optional<double>& ev100);

/// Bake units (Radiance W sr^-1 m^-2) of a linear value 1 in a photo taken at ev100: 1.2 x 2^EV100 / 179.
double skyPhotoRadianceScale(double ev100);

/// What readSkyPhotos found, for the check command's and the bake's report.
struct SkyPhotoSummary {
    std::vector<double> ev100;          ///< per photo, in the order given
    size_t clipped_texel_count = 0;     ///< texels clipped in every photo (now the saturation white)
    size_t texel_count = 0;
};

/// One photo (photos.size() == 1) or a bracket, as a linear radiance map (alpha 1). See the header comment.
ImageRGBA readSkyPhotos(const std::vector<SkyPhotoConfig>& photos, SkyPhotoSummary* summary = nullptr);

/// The sky's radiance map whatever it is: readSkyPhotos for 8-bit photos (sky.photos, or a sky.path ending in
/// .jpg/.jpeg/.png with the exposure from EXIF), readRadianceMap (gusuku/assets/image.h) for an HDR map.
ImageRGBA readSkyRadiance(const SkyConfig& sky, SkyPhotoSummary* summary = nullptr);

}  // namespace gusuku

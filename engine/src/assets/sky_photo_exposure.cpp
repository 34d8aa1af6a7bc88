// A sky photo's exposure: site.json's ev100, else the EXIF fields OpenImageIO reads from the photo
// (gusuku/assets/sky_photo.h has the calibration).
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include <OpenImageIO/imageio.h>

#include "gusuku/assets/image.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/maths/exposure.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {

namespace {

std::string formatValue(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

// EV100 to a tenth of a stop, as cameras state it.
std::string formatEv100(double ev100) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", ev100);
    return text;
}

/// A required EXIF number, with the name it was found under.
struct ExifNumber {
    std::string name;
    double value = 0.0;
};

/// A required EXIF number that must be positive and finite; `unit` is appended to the value in messages.
ExifNumber positiveExifNumber(const std::string& path, const OIIO::ImageSpec& spec,
                              std::initializer_list<const char*> names, const char* unit) {
    const OIIO::ParamValue* found = nullptr;
    for (const char* name : names)
        if (!found) found = spec.find_attribute(name);
    const std::string field = *names.begin();
    if (!found)
        throw InputError(path, field,
                         "absent from the photo's EXIF; give the sky's exposure as \"ev100\" in site.json instead");
    const double value = found->get_float();
    if (!std::isfinite(value) || value <= 0.0)
        throw InputError(path, field, formatValue(value) + unit + " is not a positive, finite exposure value");
    return {found->name().string(), value};
}

/// Whether site.json's range for ev100 holds `ev100`.
bool inEv100Range(double ev100) {
    return ev100 >= kSkyPhotoEv100Range.minimum && ev100 <= kSkyPhotoEv100Range.maximum;
}

std::string ev100RangeText() {
    return "[" + formatValue(kSkyPhotoEv100Range.minimum) + ", " + formatValue(kSkyPhotoEv100Range.maximum) + "]";
}

/// EV100 from the EXIF fields OpenImageIO read, held to site.json's range.
double ev100FromExif(const std::string& path, const OIIO::ImageSpec& spec) {
    // Without the exposure time there is no exposure at all: name the field a user looks for first.
    const ExifNumber exposure_time_s = positiveExifNumber(path, spec, {"ExposureTime", "Exif:ExposureTime"}, " s");
    const ExifNumber f_number = positiveExifNumber(path, spec, {"FNumber", "Exif:FNumber"}, "");
    // OpenImageIO names EXIF tag 0x8827 Exif:PhotographicSensitivity (EXIF 2.3); older files and tools say
    // ISOSpeedRatings.
    const ExifNumber iso_speed =
        positiveExifNumber(path, spec, {"Exif:PhotographicSensitivity", "Exif:ISOSpeedRatings"}, "");
    const double ev100 = ev100FromCamera(f_number.value, exposure_time_s.value, iso_speed.value);
    // Each field alone may look plausible; only their EV100 shows the EXIF is corrupt (an FNumber of 2.1e9 gave
    // 72, a bake's worth of lightmaps of 3e19 and a manifest that could not be written). Refused here, so that
    // `check` and the bake's setup refuse it before a slot is traced.
    if (!std::isfinite(ev100) || !inEv100Range(ev100))
        throw InputError(path, "EXIF exposure",
                         exposure_time_s.name + " " + formatValue(exposure_time_s.value) + " s, " + f_number.name +
                             " " + formatValue(f_number.value) + ", " + iso_speed.name + " " +
                             formatValue(iso_speed.value) + " give EV100 " + formatEv100(ev100) + ", outside " +
                             ev100RangeText() + " (site.json's ev100 range): the EXIF is corrupt; give the "
                             "sky's exposure as \"ev100\" in site.json instead");
    return ev100;
}

}  // namespace

bool isSkyPhotoExtension(const std::string& lower_case_extension) {
    return lower_case_extension == ".jpg" || lower_case_extension == ".jpeg" || lower_case_extension == ".png";
}

double skyPhotoEv100(const std::string& path, const std::optional<double>& ev100) {
    if (ev100) {
        if (!std::isfinite(*ev100)) throw InputError(path, "ev100", "is not finite");
        if (!inEv100Range(*ev100))
            throw InputError(path, "ev100", formatValue(*ev100) + " is outside " + ev100RangeText());
        return *ev100;
    }
    readImageSize(path);  // the reader's checks (a regular file, an image, a sane header) before opening it here
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
    return ev100FromExif(path, input->spec());
}

double skyPhotoRadianceScale(double ev100) {
    return whiteLuminanceFromEv100(ev100, CameraSpeedModel::kSaturation) / kRadianceWhiteEfficacy;
}

}  // namespace gusuku

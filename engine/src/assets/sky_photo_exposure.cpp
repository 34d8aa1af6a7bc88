// A sky photo's exposure: site.json's ev100, else the EXIF fields OpenImageIO reads from the photo
// (gusuku/assets/sky_photo.h has the calibration).
#include <cmath>
#include <memory>
#include <sstream>

#include <OpenImageIO/imageio.h>

#include "gusuku/assets/image.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/maths/exposure.h"
#include "gusuku/maths/input_error.h"

namespace gusuku {

namespace {

std::string formatValue(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

/// A required EXIF number that must be positive and finite; `unit` is appended to the value in messages.
double positiveExifNumber(const std::string& path, const OIIO::ImageSpec& spec,
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
    return value;
}

}  // namespace

bool isSkyPhotoExtension(const std::string& lower_case_extension) {
    return lower_case_extension == ".jpg" || lower_case_extension == ".jpeg" || lower_case_extension == ".png";
}

double skyPhotoEv100(const std::string& path, const std::optional<double>& ev100) {
    if (ev100) {
        if (!std::isfinite(*ev100)) throw InputError(path, "ev100", "is not finite");
        return *ev100;
    }
    readImageSize(path);  // the reader's checks (a regular file, an image, a sane header) before opening it here
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    // Without the exposure time there is no exposure at all: name the field a user looks for first.
    const double exposure_time_s = positiveExifNumber(path, spec, {"ExposureTime", "Exif:ExposureTime"}, " s");
    const double f_number = positiveExifNumber(path, spec, {"FNumber", "Exif:FNumber"}, "");
    // OpenImageIO names EXIF tag 0x8827 Exif:PhotographicSensitivity (EXIF 2.3); older files and tools say
    // ISOSpeedRatings.
    const double iso_speed =
        positiveExifNumber(path, spec, {"Exif:PhotographicSensitivity", "Exif:ISOSpeedRatings"}, "");
    return ev100FromCamera(f_number, exposure_time_s, iso_speed);
}

double skyPhotoRadianceScale(double ev100) {
    return whiteLuminanceFromEv100(ev100, CameraSpeedModel::kSaturation) / kRadianceWhiteEfficacy;
}

}  // namespace gusuku

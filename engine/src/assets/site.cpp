// site.json: reading and validating the format documented in docs/site-json.md, and the model -> ENU
// placement transforms of the building and the SfM mesh.
#include "gusuku/assets/site.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "gusuku/assets/sky_photo.h"
#include "gusuku/assets/sky_sun.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "regular_file.h"
#include "site_json_reader.h"

namespace gusuku {

namespace {

using json_reader::NumberRange;
using json_reader::ObjectReader;
namespace fs = std::filesystem;

constexpr const char* kFormatName = "gusuku-site/1";

// Ranges, shared with docs/site-json.md (keep them in step).
constexpr NumberRange kLatitude{kSiteLatitudeRangeDeg.minimum, kSiteLatitudeRangeDeg.maximum};
constexpr NumberRange kLongitude{kSiteLongitudeRangeDeg.minimum, kSiteLongitudeRangeDeg.maximum};
constexpr NumberRange kHeight{kSiteHeightRangeM.minimum, kSiteHeightRangeM.maximum};
constexpr NumberRange kPressure{kSitePressureRangeMbar.minimum, kSitePressureRangeMbar.maximum};
constexpr NumberRange kTemperature{kSiteTemperatureRangeC.minimum, kSiteTemperatureRangeC.maximum};
constexpr NumberRange kEnuMetres{-100000.0, 100000.0};
// Metres per model unit: from a micrometre (a model in anything finer is a mistake, and scales near 0 collapse
// every vertex onto one point, which the glTF transform check then blames on the node) to 1000 km.
constexpr NumberRange kScale{1e-6, 1e6};
constexpr NumberRange kQuaternionComponent{-1.01, 1.01};
constexpr NumberRange kHeading{-360.0, 360.0};
constexpr NumberRange kNorthAzimuth{0.0, 360.0, false, true};
// EV100 of a sky photo: the range the EXIF reader holds the photo's own exposure to as well.
constexpr NumberRange kEv100{kSkyPhotoEv100Range.minimum, kSkyPhotoEv100Range.maximum};
// A bracket of one view: cameras shoot 3 to 9; beyond 16 it is more likely a folder of different photos.
constexpr size_t kMaxBracketPhotos = 16;
// Global horizontal illuminance under the sky: the clearest high-altitude noon stays under about 150 klux.
constexpr NumberRange kGlobalHorizontalLux{0.0, 200000.0, true, false};
constexpr NumberRange kTexelsPerMetre{0.0, 1000.0, true, false};
constexpr NumberRange kGroundCell{0.0, 100.0, true, false};
constexpr int kMaxUtcOffsetMinutes = 14 * 60;
constexpr double kQuaternionUnitTolerance = 1e-3;
constexpr uintmax_t kMaxSiteJsonBytes = 1 << 20;

bool isDigits(const std::string& text, size_t first, size_t count) {
    if (first + count > text.size()) return false;
    for (size_t i = first; i < first + count; ++i)
        if (!std::isdigit(static_cast<unsigned char>(text[i]))) return false;
    return true;
}

std::string inQuotes(const std::string& text) { return "\"" + text + "\""; }

/// "+09:00" -> 540. Only the explicit form: a bare "9" or "Z" would be easy to misread.
int parseUtcOffset(const ObjectReader& reader, const std::string& name) {
    const std::string text = reader.string(name);
    const bool shape_ok = text.size() == 6 && (text[0] == '+' || text[0] == '-') && isDigits(text, 1, 2) &&
                          text[3] == ':' && isDigits(text, 4, 2);
    if (!shape_ok) reader.fail(name, inQuotes(text) + " is not an offset of the form +hh:mm or -hh:mm");
    const int hours = std::stoi(text.substr(1, 2));
    const int minutes = std::stoi(text.substr(4, 2));
    if (minutes >= 60) reader.fail(name, inQuotes(text) + " has minutes outside [0, 59]");
    const int offset = (text[0] == '-' ? -1 : 1) * (hours * 60 + minutes);
    if (std::abs(offset) > kMaxUtcOffsetMinutes) reader.fail(name, inQuotes(text) + " is outside [-14:00, +14:00]");
    return offset;
}

/// "hh:mm" on a 24-hour clock -> minutes after midnight.
int parseLocalTime(const ObjectReader& reader, const std::string& name) {
    const std::string text = reader.string(name);
    const bool shape_ok = text.size() == 5 && isDigits(text, 0, 2) && text[2] == ':' && isDigits(text, 3, 2);
    if (!shape_ok) reader.fail(name, inQuotes(text) + " is not a time of the form hh:mm");
    const int hours = std::stoi(text.substr(0, 2));
    const int minutes = std::stoi(text.substr(3, 2));
    if (hours > 23 || minutes > 59) reader.fail(name, inQuotes(text) + " is not a time of day (00:00 to 23:59)");
    return hours * 60 + minutes;
}

bool isLeapYear(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

/// Checks "YYYY-MM-DD" is a real calendar day (so the message is precise whatever the time parser says).
void checkDate(const ObjectReader& reader, const std::string& name, const std::string& text) {
    const bool shape_ok = text.size() == 10 && isDigits(text, 0, 4) && text[4] == '-' && isDigits(text, 5, 2) &&
                          text[7] == '-' && isDigits(text, 8, 2);
    if (!shape_ok) reader.fail(name, inQuotes(text) + " is not a date of the form YYYY-MM-DD");
    const int year = std::stoi(text.substr(0, 4));
    const int month = std::stoi(text.substr(5, 2));
    const int day = std::stoi(text.substr(8, 2));
    if (month < 1 || month > 12) reader.fail(name, inQuotes(text) + " has a month outside [1, 12]");
    static constexpr int kDaysInMonth[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const int days = kDaysInMonth[month - 1] + (month == 2 && isLeapYear(year) ? 1 : 0);
    if (day < 1 || day > days)
        reader.fail(name, inQuotes(text) + " has a day outside [1, " + std::to_string(days) + "] for its month");
}

std::string lowercaseExtension(const fs::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

/// A referenced file: relative to site.json's folder, returned absolute; it must exist and have one of the
/// allowed extensions (the loaders choose their format by it).
std::string readFilePath(const ObjectReader& reader, const std::string& name, const fs::path& base_directory,
                         std::initializer_list<const char*> extensions) {
    const std::string text = reader.string(name);
    if (text.empty()) reader.fail(name, "is empty; expected a file path");
    const fs::path resolved = fs::absolute(base_directory / fs::path(text)).lexically_normal();
    const std::string extension = lowercaseExtension(resolved);
    bool extension_ok = false;
    std::string allowed;
    for (const char* candidate : extensions) {
        extension_ok = extension_ok || extension == candidate;
        allowed += std::string(allowed.empty() ? "" : " or ") + candidate;
    }
    if (!extension_ok) reader.fail(name, inQuotes(text) + " does not end in " + allowed);
    // A FIFO would block the loader that opens it; a device or a directory is no model or map.
    if (const std::string problem = regularFileProblem(resolved.string()); !problem.empty())
        reader.fail(name, problem == "file not found" ? "file not found: " + resolved.string()
                                                      : resolved.string() + " " + problem);
    return resolved.string();
}

void readGeodeticFields(const ObjectReader& reader, GeodeticPoint& point) {
    point.latitude_deg = reader.number("latitude_deg", kLatitude);
    point.longitude_deg = reader.number("longitude_deg", kLongitude);
    point.height_m = reader.number("height_m", kHeight);
}

glm::dvec3 toVec3(const std::vector<double>& numbers) { return {numbers[0], numbers[1], numbers[2]}; }

SiteLocation readSite(const ObjectReader& root) {
    const ObjectReader reader = root.object(
        "site", {"name", "latitude_deg", "longitude_deg", "height_m", "utc_offset", "pressure_mbar", "temperature_c"});
    SiteLocation site;
    site.name = reader.string("name");
    if (site.name.empty()) reader.fail("name", "is empty");
    readGeodeticFields(reader, site.reference);
    site.utc_offset_minutes = parseUtcOffset(reader, "utc_offset");
    site.pressure_mbar = reader.number("pressure_mbar", kPressure, site.pressure_mbar);
    site.temperature_c = reader.number("temperature_c", kTemperature, site.temperature_c);
    return site;
}

std::optional<SfmMeshConfig> readSfmMesh(const ObjectReader& root, const fs::path& base_directory) {
    const auto reader = root.optionalObject("sfm_mesh", {"path", "scale", "rotation_wxyz", "translation_enu_m"});
    if (!reader) return std::nullopt;
    SfmMeshConfig mesh;
    mesh.path = readFilePath(*reader, "path", base_directory, {".gltf", ".glb", ".ply", ".obj"});
    mesh.scale = reader->number("scale", kScale);
    const std::vector<double> quaternion = reader->numberArray("rotation_wxyz", 4, kQuaternionComponent);
    const double norm = std::sqrt(quaternion[0] * quaternion[0] + quaternion[1] * quaternion[1] +
                                  quaternion[2] * quaternion[2] + quaternion[3] * quaternion[3]);
    // A hand-typed quaternion is rarely exactly unit; beyond 1e-3 it is more likely a wrong number than rounding.
    if (std::abs(norm - 1.0) > kQuaternionUnitTolerance)
        reader->fail("rotation_wxyz", "is not a unit quaternion: its length is " + json_reader::formatNumber(norm) +
                                          " (allowed 1 +- 0.001)");
    for (size_t i = 0; i < 4; ++i) mesh.rotation_wxyz[i] = quaternion[i] / norm;
    mesh.translation_enu_m = toVec3(reader->numberArray("translation_enu_m", 3, kEnuMetres));
    return mesh;
}

BuildingConfig readBuilding(const ObjectReader& root, const fs::path& base_directory) {
    const ObjectReader reader =
        root.object("building", {"path", "position", "enu_offset_m", "heading_deg", "scale"});
    BuildingConfig building;
    building.path = readFilePath(reader, "path", base_directory, {".gltf", ".glb"});
    const bool has_position = reader.has("position");
    const bool has_offset = reader.has("enu_offset_m");
    if (has_position && has_offset)
        reader.fail("enu_offset_m", "give either position or enu_offset_m, not both");
    if (!has_position && !has_offset)
        reader.fail("position", "required field is missing (give position or enu_offset_m)");
    if (has_position) {
        const ObjectReader position = reader.object("position", {"latitude_deg", "longitude_deg", "height_m"});
        GeodeticPoint point;
        readGeodeticFields(position, point);
        building.position = point;
    } else {
        building.enu_offset_m = toVec3(reader.numberArray("enu_offset_m", 3, kEnuMetres));
    }
    building.heading_deg = reader.number("heading_deg", kHeading, building.heading_deg);
    building.scale = reader.number("scale", kScale, building.scale);
    return building;
}

/// One photo's file and optional EV100 (the same two fields at the sky's level and in a bracket entry).
SkyPhotoConfig readSkyPhoto(const ObjectReader& reader, const fs::path& base_directory) {
    SkyPhotoConfig photo;
    photo.path = readFilePath(reader, "path", base_directory, {".jpg", ".jpeg", ".png"});
    photo.ev100 = reader.optionalNumber("ev100", kEv100);
    return photo;
}

// "auto" north: the photo's sun may stand this far in elevation from the computed sun at taken_at before the time
// (or the photo's levelling) is called wrong; a 360 camera held by hand tilts a degree or two.
constexpr double kAutoNorthElevationToleranceDeg = 5.0;

double readTakenAt(const ObjectReader& reader) {
    const std::string text = reader.string("taken_at");
    try {
        return parseIso8601Utc(text);
    } catch (const std::invalid_argument& error) {
        reader.fail("taken_at", inQuotes(text) + " is not a time of the form YYYY-MM-DDThh:mm+hh:mm (the photo's "
                                                 "clock with its UTC offset): " + error.what());
    }
    return 0.0;
}

/// taken_at, also within the years the sun position covers (check compares the sky's sun with it).
double readSunTakenAt(const ObjectReader& reader) {
    const double taken_at = readTakenAt(reader);
    try {
        computeSunPosition(SunObserver{}, taken_at);  // the range depends on the instant alone
    } catch (const std::invalid_argument&) {
        reader.fail("taken_at", "is outside the UTC years -2000 to 6000 that the sun position (NREL SPA) covers");
    }
    return taken_at;
}

/// `"north_azimuth_in_image_deg": "auto"`: the column the sun stands in, less the sun's computed azimuth at taken_at.
double northFromSkySun(const ObjectReader& reader, const SkyConfig& sky, const SiteLocation& site) {
    if (!reader.has("taken_at"))
        reader.fail("north_azimuth_in_image_deg", "\"auto\" needs taken_at, the time the sky was photographed "
                                                  "(e.g. \"2026-06-21T10:30+09:00\"), to compute the sun's azimuth");
    const double taken_at = readSunTakenAt(reader);
    const SunPosition sun = computeSunPosition(site.sunObserver(), taken_at);  // in range: readSunTakenAt
    if (!sun.above_horizon)
        reader.fail("taken_at", "the sun is below the horizon then (elevation " +
                                    json_reader::formatNumber(std::round(sun.apparent_elevation_deg * 10) / 10) +
                                    " deg): check the date and the UTC offset");
    const SkySunSighting seen = findSkySun(readSkyRadiance(sky));
    if (!seen.found)
        reader.fail("north_azimuth_in_image_deg", "\"auto\" found no sun in the sky (no bright spot under " +
                                                      json_reader::formatNumber(kSkySunMaxCoreRadiusDeg) +
                                                      " deg across): give the north as a number of degrees");
    if (std::abs(seen.elevation_deg - sun.apparent_elevation_deg) > kAutoNorthElevationToleranceDeg)
        reader.fail("taken_at", "the sun in the sky stands at elevation " +
                                    json_reader::formatNumber(std::round(seen.elevation_deg * 10) / 10) +
                                    " deg, the computed sun then at " +
                                    json_reader::formatNumber(std::round(sun.apparent_elevation_deg * 10) / 10) +
                                    " deg: the time (or its UTC offset) is wrong, or the photo is not level; "
                                    "\"auto\" north would be wrong");
    return northAzimuthInImageFromSun(seen.image_azimuth_deg, sun.azimuth_deg);
}

/// An HDR map or one 8-bit photo in `path`, or an exposure bracket of 8-bit photos in `bracket`.
SkyConfig readSky(const ObjectReader& skies, const std::string& name, const fs::path& base_directory,
                  const SiteLocation& site) {
    const ObjectReader reader = skies.object(
        name, {"path", "ev100", "bracket", "north_azimuth_in_image_deg", "global_horizontal_lux", "taken_at"});
    SkyConfig sky;
    const bool has_path = reader.has("path");
    if (has_path == reader.has("bracket"))
        reader.fail("path", has_path ? "give either path or bracket, not both"
                                     : "required field is missing (give path or bracket)");
    if (has_path) {
        const std::string text = reader.string("path");
        const std::string extension = lowercaseExtension(fs::path(text));
        if (extension == ".jpg" || extension == ".jpeg" || extension == ".png") {
            sky.photos.push_back(readSkyPhoto(reader, base_directory));
            sky.path = sky.photos.front().path;
        } else {
            sky.path = readFilePath(reader, "path", base_directory, {".hdr", ".exr", ".jpg", ".jpeg", ".png"});
            for (const char* field : {"ev100", "global_horizontal_lux"})
                if (reader.has(field))
                    reader.fail(field, "applies to an 8-bit photo (.jpg, .jpeg, .png), whose exposure makes its "
                                       "radiance absolute; an HDR map holds radiance in its own units");
        }
    } else {
        if (reader.has("ev100"))
            reader.fail("ev100", "give each bracket member its own ev100 (or none: from its EXIF)");
        const nlohmann::json& bracket = reader.array("bracket");
        if (bracket.empty() || bracket.size() > kMaxBracketPhotos)
            reader.fail("bracket", "holds " + std::to_string(bracket.size()) + " photos; expected 1 to " +
                                       std::to_string(kMaxBracketPhotos));
        for (size_t i = 0; i < bracket.size(); ++i) {
            const ObjectReader member(reader.file(), bracket[i],
                                      reader.fieldPointer("bracket") + "/" + std::to_string(i), {"path", "ev100"});
            sky.photos.push_back(readSkyPhoto(member, base_directory));
        }
        sky.path = sky.photos.front().path;
    }
    sky.global_horizontal_lux = reader.optionalNumber("global_horizontal_lux", kGlobalHorizontalLux);
    if (reader.has("north_azimuth_in_image_deg") && reader.required("north_azimuth_in_image_deg").is_string()) {
        const std::string text = reader.string("north_azimuth_in_image_deg");
        if (text != "auto")
            reader.fail("north_azimuth_in_image_deg",
                        inQuotes(text) + " is not a number of degrees in [0, 360) nor \"auto\" (north from the sun)");
        sky.north_azimuth_in_image_deg = northFromSkySun(reader, sky, site);
    } else {
        sky.north_azimuth_in_image_deg =
            reader.number("north_azimuth_in_image_deg", kNorthAzimuth, sky.north_azimuth_in_image_deg);
        if (reader.has("taken_at")) readSunTakenAt(reader);
    }
    return sky;
}

bool isSlotName(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    for (const char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

BakeSlot sunnySlot(const std::string& name, const std::string& local_time) {
    BakeSlot slot;
    slot.name = name;
    slot.sky = SlotSky::Sunny;
    slot.local_time = local_time;
    return slot;
}

/// docs/design.md 3: by default sunny 09:00, 12:00 and 15:00 site time, and overcast when there is an overcast sky.
std::vector<BakeSlot> defaultSlots(bool has_overcast_sky) {
    std::vector<BakeSlot> slots = {sunnySlot("sunny_0900", "09:00"), sunnySlot("sunny_1200", "12:00"),
                                   sunnySlot("sunny_1500", "15:00")};
    if (has_overcast_sky) {
        BakeSlot overcast;
        overcast.name = "overcast";
        overcast.sky = SlotSky::Overcast;
        slots.push_back(overcast);
    }
    return slots;
}

std::vector<BakeSlot> readSlots(const ObjectReader& bake, bool has_overcast_sky, const std::string& file) {
    const nlohmann::json& array = bake.array("slots");
    if (array.empty()) bake.fail("slots", "is empty; give at least one slot or leave slots out for the defaults");
    std::vector<BakeSlot> slots;
    std::map<std::string, size_t> first_index_of_name;
    for (size_t i = 0; i < array.size(); ++i) {
        const ObjectReader reader(file, array[i], bake.fieldPointer("slots") + "/" + std::to_string(i),
                                  {"name", "sky", "local_time"});
        BakeSlot slot;
        slot.name = reader.string("name");
        if (!isSlotName(slot.name))
            reader.fail("name", inQuotes(slot.name) + " is not a slot name: 1 to 64 of a-z, 0-9 and _");
        const auto [existing, inserted] = first_index_of_name.emplace(slot.name, i);
        if (!inserted)
            reader.fail("name", "duplicate slot name " + inQuotes(slot.name) + " (also at " +
                                    bake.fieldPointer("slots") + "/" + std::to_string(existing->second) + "/name)");
        const std::string sky = reader.string("sky");
        if (sky == "sunny") {
            slot.sky = SlotSky::Sunny;
            parseLocalTime(reader, "local_time");
            slot.local_time = reader.string("local_time");
        } else if (sky == "overcast") {
            slot.sky = SlotSky::Overcast;
            if (!has_overcast_sky) reader.fail("sky", "an overcast slot needs skies.overcast, which is absent");
            // An overcast slot has no sun, so a clock time would mean nothing; refuse it rather than ignore it.
            if (reader.has("local_time"))
                reader.fail("local_time", "is not allowed for an overcast slot (it has no sun)");
        } else {
            reader.fail("sky", inQuotes(sky) + " is not a sky; expected \"sunny\" or \"overcast\"");
        }
        slots.push_back(slot);
    }
    return slots;
}

/// The sun code (NREL SPA) refuses instants outside the years it was fitted for (-2000..6000); a slot's instant
/// is checked here, by the sun code itself, so the date is reported at load rather than half-way into a bake.
void checkSunCanBeComputed(const ObjectReader& bake, const SiteLocation& site, const BakeSlot& slot) {
    const SunObserver observer = site.sunObserver();
    try {
        computeSunPosition(observer, slot.utc_seconds);
    } catch (const std::invalid_argument&) {
        // The site's own ranges are narrower than SPA's, so the instant is what it refused.
        bake.fail("date", "slot " + inQuotes(slot.name) + " at " +
                              formatIso8601(slot.utc_seconds, site.utc_offset_minutes) +
                              " is outside the UTC years -2000 to 6000 that the sun position (NREL SPA) covers");
    }
}

BakeSettings readBake(const ObjectReader& root, const SiteLocation& site, bool has_overcast_sky,
                      const std::string& file) {
    const ObjectReader reader = root.object(
        "bake", {"date", "slots", "texels_per_metre", "samples_per_texel", "max_bounces", "seed", "ground_cell_m"});
    BakeSettings bake;
    bake.date = reader.string("date");
    checkDate(reader, "date", bake.date);
    double midnight_utc_seconds = 0.0;
    try {
        midnight_utc_seconds = parseDateAtOffset(bake.date, site.utc_offset_minutes);
    } catch (const std::exception& error) {
        reader.fail("date", inQuotes(bake.date) + ": " + error.what());
    }
    bake.slots = reader.has("slots") ? readSlots(reader, has_overcast_sky, file) : defaultSlots(has_overcast_sky);
    for (BakeSlot& slot : bake.slots) {
        if (slot.sky != SlotSky::Sunny) continue;
        const int hours = std::stoi(slot.local_time.substr(0, 2));
        const int minutes = std::stoi(slot.local_time.substr(3, 2));
        slot.utc_seconds = midnight_utc_seconds + 3600.0 * hours + 60.0 * minutes;
        checkSunCanBeComputed(reader, site, slot);
    }
    bake.texels_per_metre = reader.number("texels_per_metre", kTexelsPerMetre, bake.texels_per_metre);
    bake.samples_per_texel = int(reader.integer("samples_per_texel", 1, 1000000, bake.samples_per_texel));
    bake.max_bounces = int(reader.integer("max_bounces", 0, 64, bake.max_bounces));
    bake.seed = uint32_t(reader.integer("seed", 0, 4294967295LL, bake.seed));
    bake.ground_cell_m = reader.number("ground_cell_m", kGroundCell, bake.ground_cell_m);
    return bake;
}

std::string readWholeFile(const std::string& path) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) throw InputError(path, "", problem);
    // A site.json is a few kilobytes; its parsed tree takes many times its size, so a huge file is refused unread.
    std::error_code size_error;
    const uintmax_t size = fs::file_size(path, size_error);
    if (!size_error && size > kMaxSiteJsonBytes)
        throw InputError(path, "", "is " + std::to_string(size) + " bytes, more than the " +
                                       std::to_string(kMaxSiteJsonBytes) + " a site.json may have");
    std::ifstream stream(path, std::ios::binary);
    if (!stream.is_open()) throw InputError(path, "", "cannot be opened for reading");
    std::ostringstream text;
    text << stream.rdbuf();
    if (stream.bad()) throw InputError(path, "", "cannot be read");
    return text.str();
}

/// Rotation about +z (up) by angle_rad, counter-clockwise seen from above (east towards north).
glm::dmat4 rotationAboutUp(double angle_rad) {
    const double c = std::cos(angle_rad);
    const double s = std::sin(angle_rad);
    glm::dmat4 rotation(1.0);
    rotation[0] = {c, s, 0.0, 0.0};   // image of east
    rotation[1] = {-s, c, 0.0, 0.0};  // image of north
    return rotation;
}

glm::dmat4 translation(const glm::dvec3& offset) {
    glm::dmat4 matrix(1.0);
    matrix[3] = glm::dvec4(offset, 1.0);
    return matrix;
}

glm::dmat4 uniformScale(double scale) {
    glm::dmat4 matrix(scale);
    matrix[3][3] = 1.0;
    return matrix;
}

}  // namespace

glm::dmat4 SfmMeshConfig::enuFromModel() const {
    // Rotation matrix of the unit quaternion (w, x, y, z), written out so the component order is unambiguous.
    const double w = rotation_wxyz[0], x = rotation_wxyz[1], y = rotation_wxyz[2], z = rotation_wxyz[3];
    glm::dmat4 rotation(1.0);  // glm is column-major: rotation[column] = image of that axis
    rotation[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y), 0};
    rotation[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x), 0};
    rotation[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y), 0};
    return translation(translation_enu_m) * rotation * uniformScale(scale);
}

glm::dmat4 BuildingConfig::enuFromModel(const GeodeticPoint& site_reference) const {
    // The same fixed axis change as enuFromGltfYUp() (gltf_loader.h), written here so the site model does
    // not depend on the glTF loader: glTF (x, y, z) -> ENU (x, -z, y).
    glm::dmat4 enu_from_gltf(0.0);
    enu_from_gltf[0] = {1, 0, 0, 0};   // glTF +x -> east
    enu_from_gltf[1] = {0, 0, 1, 0};   // glTF +y -> up
    enu_from_gltf[2] = {0, -1, 0, 0};  // glTF +z -> south (the model's north, -z, faces north)
    enu_from_gltf[3] = {0, 0, 0, 1};
    const glm::dvec3 origin_enu =
        position ? geodeticToEnu(site_reference, *position) : enu_offset_m.value_or(glm::dvec3(0.0));
    // A compass heading turns clockwise seen from above, the opposite of a positive rotation about up.
    const double turn_rad = -heading_deg * std::numbers::pi / 180.0;
    return translation(origin_enu) * rotationAboutUp(turn_rad) * uniformScale(scale) * enu_from_gltf;
}

SiteConfig loadSiteConfig(const std::string& path) {
    const nlohmann::json document = json_reader::parseDocument(path, readWholeFile(path));
    const ObjectReader root(path, document, "", {"format", "site", "sfm_mesh", "building", "skies", "bake"});
    const std::string format = root.string("format");
    if (format != kFormatName)
        root.fail("format", inQuotes(format) + " is not a format this version reads; expected " +
                                inQuotes(kFormatName));

    fs::path base_directory = fs::path(path).parent_path();
    if (base_directory.empty()) base_directory = ".";

    SiteConfig config;
    config.file = path;
    config.site = readSite(root);
    config.sfm_mesh = readSfmMesh(root, base_directory);
    config.building = readBuilding(root, base_directory);
    const ObjectReader skies = root.object("skies", {"sunny", "overcast"});
    config.sunny_sky = readSky(skies, "sunny", base_directory, config.site);
    if (skies.has("overcast")) config.overcast_sky = readSky(skies, "overcast", base_directory, config.site);
    config.bake = readBake(root, config.site, config.overcast_sky.has_value(), path);
    return config;
}

SkyCaptureTime readSkyCaptureTime(const std::string& site_json_path, const std::string& sky_name) {
    SkyCaptureTime capture;
    const nlohmann::json document = json_reader::parseDocument(site_json_path, readWholeFile(site_json_path));
    const nlohmann::json::json_pointer pointer("/skies/" + sky_name);
    if (!document.contains(pointer) || !document.at(pointer).is_object()) return capture;
    const nlohmann::json& sky = document.at(pointer);
    if (const auto taken_at = sky.find("taken_at"); taken_at != sky.end() && taken_at->is_string()) {
        capture.taken_at_text = taken_at->get<std::string>();
        try {
            capture.taken_at_utc_seconds = parseIso8601Utc(capture.taken_at_text);
        } catch (const std::invalid_argument&) {
        }
    }
    if (const auto north = sky.find("north_azimuth_in_image_deg"); north != sky.end())
        capture.north_auto = north->is_string() && north->get<std::string>() == "auto";
    return capture;
}

}  // namespace gusuku

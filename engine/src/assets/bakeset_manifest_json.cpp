// manifest.json <-> BakeSetManifest (gusuku/assets/bakeset_manifest_json.h). The writer's JSON is built member by
// member with the value types the baker always wrote (unsigned counts, int sizes, doubles), so the bytes of a
// bake set's manifest did not change when the baker moved onto this writer; the reader is strict (unknown
// fields are errors), so what it accepts round-trips through the struct without loss.

#include "gusuku/assets/bakeset_manifest_json.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/sun_horizon.h"
#include "site_json_reader.h"

namespace gusuku {

namespace {

using nlohmann::json;
using json_reader::NumberRange;
using json_reader::ObjectReader;

// The format's fixed texts: written into every manifest and required, word for word, by the reader (a
// different text would mean a different convention, which needs a new format version).
constexpr const char* kMeshFrame = "site ENU metres in glTF Y-up axes: glTF (x, y, z) = ENU (x, z, -y)";
constexpr const char* kLightmapUv = "TEXCOORD_1";
constexpr const char* kIrradianceUnits = "the sky maps' linear radiance units times steradians";
constexpr const char* kGeometryChannels = "RGB: unit normal (ENU), A: height (ENU z, metres)";
constexpr const char* kRow0 = "north edge";
constexpr const char* kIrradianceAlpha = "1 where the ground exists under the cell";
constexpr const char* kGroundAlbedoChannels = "RGB: linear base colour of the ground at the cell, A: 1 where ground";
constexpr const char* kColourSpace = "CIE Lab (D65) of linear radiance rho/pi*(E_ind + V E_sun cos)";
// Present since input paths are written relative to the bake set (so a set moves with its inputs); a manifest
// without it is older, and its relative paths were relative to where its bake ran.
constexpr const char* kInputPaths = "relative to this manifest's folder";

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------------------------------------
// Writing
// ------------------------------------------------------------------------------------------------------------

json vec3Json(const glm::dvec3& value) { return {value.x, value.y, value.z}; }

std::string hex64(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

/// JSON has no NaN or infinity (nlohmann would write null, which no reader accepts as a number).
void requireFiniteNumbers(const json& value, const std::string& pointer) {
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
        throw std::invalid_argument("bake set manifest: " + pointer + " is not finite");
    if (value.is_object())
        for (const auto& member : value.items())
            requireFiniteNumbers(member.value(), pointer + "/" + json_reader::escapePointerToken(member.key()));
    if (value.is_array())
        for (size_t i = 0; i < value.size(); ++i) requireFiniteNumbers(value[i], pointer + "/" + std::to_string(i));
}

json slotJson(const BakeSetSlot& slot, size_t index) {
    const std::string pointer = "/slots/" + std::to_string(index);
    const bool sunny = slot.sky == BakeSetSky::Sunny;
    if (sunny != slot.sun.position.has_value())
        throw std::invalid_argument("bake set manifest: " + pointer + "/sun: a sunny slot has a sun position, an "
                                    "overcast one none");
    if (slot.sun.present && !sunny)
        throw std::invalid_argument("bake set manifest: " + pointer + "/sun/present: an overcast slot has no sun");
    if (!sunny && (!slot.local_time.empty() || !slot.utc.empty()))
        throw std::invalid_argument("bake set manifest: " + pointer + ": an overcast slot has no local_time or utc");
    json sun = {{"present", slot.sun.present}, {"irradiance_source", slot.sun.irradiance_source}};
    if (slot.sun.position) {
        sun["azimuth_deg"] = slot.sun.position->azimuth_deg;
        sun["apparent_elevation_deg"] = slot.sun.position->apparent_elevation_deg;
        sun["direction_enu"] = vec3Json(slot.sun.position->direction_enu);
    }
    if (slot.sun.present) {
        sun["irradiance_rgb"] = vec3Json(slot.sun.irradiance_rgb);
        sun["angular_radius_deg"] = slot.sun.angular_radius_deg;
    }
    json entry = {
        {"name", slot.name},
        {"sky", sunny ? "sunny" : "overcast"},
        {"sky_map", slot.sky_map},
        {"sky_sampling",
         {{"method", slot.sky_sampling_method}, {"cosine_relative_variance", slot.cosine_relative_variance}}},
        {"sun", sun},
        {"building_irradiance", slot.building_irradiance},
        {"ground_irradiance_with_building", slot.ground_irradiance_with_building},
        {"ground_irradiance_without_building", slot.ground_irradiance_without_building},
        {"invalid_texels", slot.invalid_texels},
    };
    if (slot.colour_statistics) {
        const BakeSetColourStatistics& statistics = *slot.colour_statistics;
        entry["colour_statistics"] = {{"space", kColourSpace},
                                      {"lab_mean", vec3Json(statistics.lab_mean)},
                                      {"lab_sigma", vec3Json(statistics.lab_sigma)},
                                      {"texels", statistics.texels}};
    }
    if (sunny) {
        entry["local_time"] = slot.local_time;
        entry["utc"] = slot.utc;
    }
    return entry;
}

// ------------------------------------------------------------------------------------------------------------
// Reading
// ------------------------------------------------------------------------------------------------------------

const NumberRange kAnyFinite{-kInfinity, kInfinity};
const NumberRange kNonNegative{0.0, kInfinity};

NumberRange rangeOf(const BakeSetRange& range) { return {range.minimum, range.maximum}; }

/// Each input role names a file of its kind (a tool that follows the manifest to site.json must not be led to
/// read /etc/passwd as one): site .json, building .glb or .gltf, sfm_mesh .glb, .gltf, .ply or .obj, skies .hdr or
/// .exr maps or .jpg, .jpeg or .png photos (gusuku/assets/sky_photo.h; each photo of a bracket under its sky's role). Roles this
/// reader does not know are kept as they are.
void requireInputKind(const ObjectReader& reader, const BakeSetInput& input) {
    const auto ends_with = [&](const char* extension) {
        std::string lower = input.path;
        for (char& c : lower) c = char(std::tolower((unsigned char)c));
        const std::string suffix = extension;
        return lower.size() > suffix.size() && lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    const char* expected = nullptr;
    bool matches = true;
    if (input.role == "site") {
        expected = "a .json file";
        matches = ends_with(".json");
    } else if (input.role == "building") {
        expected = "a .glb or .gltf file";
        matches = ends_with(".glb") || ends_with(".gltf");
    } else if (input.role == "sfm_mesh") {
        expected = "a .glb, .gltf, .ply or .obj file";
        matches = ends_with(".glb") || ends_with(".gltf") || ends_with(".ply") || ends_with(".obj");
    } else if (input.role == "sunny_sky" || input.role == "overcast_sky") {
        expected = "a .hdr or .exr map or a .jpg, .jpeg or .png photo";
        matches = ends_with(".hdr") || ends_with(".exr") || ends_with(".jpg") || ends_with(".jpeg") ||
                  ends_with(".png");
    }
    if (!matches) reader.fail("path", "\"" + input.path + "\" is not " + expected + ", as the " + input.role + " input is");
}

/// "HH:MM", the slot's time on the site's clock, 00:00 to 23:59.
void requireClockTime(const ObjectReader& reader, const std::string& name, const std::string& text) {
    // An ISO 8601 time with its offset names the same instant on the site's clock (older writers used it).
    if (text.size() > 5) {
        try {
            parseIso8601Utc(text);
            return;
        } catch (const std::invalid_argument& error) {
            reader.fail(name, "\"" + text + "\" is neither a time of day HH:MM nor an ISO 8601 time: " + error.what());
        }
    }
    const bool shaped = text.size() == 5 && text[2] == ':' && std::isdigit((unsigned char)text[0]) &&
                        std::isdigit((unsigned char)text[1]) && std::isdigit((unsigned char)text[3]) &&
                        std::isdigit((unsigned char)text[4]);
    if (!shaped || std::stoi(text.substr(0, 2)) > 23 || std::stoi(text.substr(3, 2)) > 59)
        reader.fail(name, "\"" + text + "\" is not a time of day HH:MM (00:00 to 23:59)");
}

/// A whole number within [min, max], stored as JSON integer (what the writer writes) or as a whole float.
/// Integers are taken as they are, so counts above 2^53 keep every digit.
uint64_t readUnsigned(const ObjectReader& reader, const std::string& name, uint64_t min, uint64_t max) {
    const json& value = reader.required(name);
    uint64_t number = 0;
    if (value.is_number_unsigned()) {
        number = value.get<uint64_t>();
    } else if (value.is_number_integer()) {
        reader.fail(name, std::to_string(value.get<int64_t>()) + " is negative");
    } else {
        const double real = json_reader::checkedNumber(reader.file(), reader.fieldPointer(name), value, kAnyFinite);
        if (real != std::floor(real)) reader.fail(name, json_reader::formatNumber(real) + " is not a whole number");
        if (real < 0.0) reader.fail(name, json_reader::formatNumber(real) + " is negative");
        if (real >= 18446744073709551616.0) reader.fail(name, json_reader::formatNumber(real) + " is too large");
        number = uint64_t(real);
    }
    if (number < min || number > max)
        reader.fail(name, std::to_string(number) + " is outside [" + std::to_string(min) + ", " +
                              std::to_string(max) + "]");
    return number;
}

int readInt(const ObjectReader& reader, const std::string& name, int min, int max) {
    const json& value = reader.required(name);
    const double number = json_reader::checkedNumber(reader.file(), reader.fieldPointer(name), value,
                                                     NumberRange{double(min), double(max)});
    if (number != std::floor(number)) reader.fail(name, json_reader::formatNumber(number) + " is not a whole number");
    return int(number);
}

/// A number within its row of gusuku/formats/bakeset_ranges.h (whole when the row says so), refused as the pack
/// reader refuses it.
double readRanged(const ObjectReader& reader, const std::string& name, const BakeSetRange& range) {
    const json& value = reader.required(name);
    if (!value.is_number()) reader.fail(name, "expected a number, found " + json_reader::describeJsonType(value));
    const double number = value.get<double>();
    if (const std::optional<std::string> problem = bakeSetValueProblem(range, number)) reader.fail(name, *problem);
    return number;
}

/// A count within its row: integers as they are (every digit of a count above 2^53), then the row's bounds.
uint64_t readCount(const ObjectReader& reader, const std::string& name, const BakeSetRange& range) {
    const json& value = reader.required(name);
    if (value.is_number_unsigned()) {
        const uint64_t count = value.get<uint64_t>();
        if (count < uint64_t(range.minimum) || count > uint64_t(range.maximum))
            reader.fail(name, std::to_string(count) + " is outside " + describeBakeSetRange(range) + " " + range.unit);
        return count;
    }
    return uint64_t(readRanged(reader, name, range));
}

bool readBool(const ObjectReader& reader, const std::string& name) {
    const json& value = reader.required(name);
    if (!value.is_boolean())
        reader.fail(name, "expected true or false, found " + json_reader::describeJsonType(value));
    return value.get<bool>();
}

std::string readNonEmptyString(const ObjectReader& reader, const std::string& name) {
    std::string text = reader.string(name);
    if (text.empty()) reader.fail(name, "is empty");
    return text;
}

void readFixedText(const ObjectReader& reader, const std::string& name, const char* expected) {
    if (reader.string(name) != expected)
        reader.fail(name, std::string("expected \"") + expected + "\" (fixed by " + kBakeSetFormat + ")");
}

/// `count` numbers, each within its row of gusuku/formats/bakeset_ranges.h, refused as the pack reader refuses them.
std::vector<double> readRangedArray(const ObjectReader& reader, const std::string& name, size_t count,
                                    const BakeSetRange& range) {
    const std::vector<double> values = reader.numberArray(name, count, kAnyFinite);
    for (size_t i = 0; i < values.size(); ++i)
        if (const std::optional<std::string> problem = bakeSetValueProblem(range, values[i]))
            throw InputError(reader.file(), reader.fieldPointer(name) + "/" + std::to_string(i), *problem);
    return values;
}

glm::dvec3 readVec3(const ObjectReader& reader, const std::string& name, const BakeSetRange& range) {
    const std::vector<double> values = readRangedArray(reader, name, 3, range);
    return {values[0], values[1], values[2]};
}

uint64_t parseHex64(const ObjectReader& reader, const std::string& name) {
    const std::string text = reader.string(name);
    uint64_t value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value, 16);
    bool lower_hex = text.size() == 16;
    for (const char c : text) lower_hex = lower_hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
    if (!lower_hex || result.ec != std::errc() || result.ptr != text.data() + text.size())
        reader.fail(name, "\"" + text + "\" is not 16 lower-case hex digits");
    return value;
}

ObjectReader elementObject(const ObjectReader& parent, const std::string& array_name, size_t index,
                           std::initializer_list<const char*> known_fields) {
    const json& array = parent.array(array_name);
    return ObjectReader(parent.file(), array[index], parent.fieldPointer(array_name) + "/" + std::to_string(index),
                        known_fields);
}

BakeSetSun readSun(const ObjectReader& slot, bool sunny) {
    const ObjectReader reader = slot.object("sun", {"present", "irradiance_source", "azimuth_deg",
                                                    "apparent_elevation_deg", "direction_enu", "irradiance_rgb",
                                                    "angular_radius_deg"});
    BakeSetSun sun;
    sun.present = readBool(reader, "present");
    sun.irradiance_source = reader.string("irradiance_source");
    if (sun.present && !sunny) reader.fail("present", "an overcast slot has no sun");
    if (sunny) {
        BakeSetSunPosition position;
        position.azimuth_deg = readRanged(reader, "azimuth_deg", kBakeSetSunAzimuthDeg);
        position.apparent_elevation_deg = readRanged(reader, "apparent_elevation_deg", kBakeSetSunElevationDeg);
        // Before the direction's agreement with the angles, as the pack reader (which has no such check) refuses it.
        if (sun.present && !rangeOf(kBakeSetPresentSunElevationDeg).contains(position.apparent_elevation_deg))
            reader.fail("apparent_elevation_deg",
                        json_reader::formatNumber(position.apparent_elevation_deg) +
                            " is below the horizon, yet present is true (a present sun is at " +
                            rangeOf(kBakeSetPresentSunElevationDeg).describe() + " degrees)");
        position.direction_enu = readVec3(reader, "direction_enu", kBakeSetSunDirectionEnu);
        const glm::dvec3& d = position.direction_enu;
        if (const std::optional<std::string> problem = bakeSetDirectionProblem(kBakeSetSunDirectionEnu, d.x, d.y, d.z))
            reader.fail("direction_enu", *problem);
        // The direction must be the one azimuth and elevation give (docs/design.md 2): the runtime lights by
        // the direction and picks slots by the angles, so two that disagree light one sun and choose another.
        const double degree = std::acos(-1.0) / 180.0;
        const double elevation = position.apparent_elevation_deg * degree, azimuth = position.azimuth_deg * degree;
        const glm::dvec3 from_angles(std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                                     std::sin(elevation));
        const double apart_deg =
            std::acos(std::clamp(d.x * from_angles.x + d.y * from_angles.y + d.z * from_angles.z, -1.0, 1.0)) / degree;
        if (apart_deg > kBakeSetSunDirectionToleranceDeg)
            reader.fail("direction_enu", "is " + json_reader::formatNumber(apart_deg) +
                                             " degrees from the direction azimuth_deg and apparent_elevation_deg give");
        sun.position = position;
    } else {
        for (const char* name : {"azimuth_deg", "apparent_elevation_deg", "direction_enu"})
            if (reader.has(name)) reader.fail(name, "only a sunny slot has a sun position");
    }
    if (sun.present) {
        sun.irradiance_rgb = readVec3(reader, "irradiance_rgb", kBakeSetSunIrradiance);
        sun.angular_radius_deg = readRanged(reader, "angular_radius_deg", kBakeSetSunAngularRadiusDeg);
    } else {
        for (const char* name : {"irradiance_rgb", "angular_radius_deg"})
            if (reader.has(name)) reader.fail(name, "only a present sun has an irradiance");
    }
    return sun;
}

BakeSetSlot readSlot(const ObjectReader& reader) {
    BakeSetSlot slot;
    slot.name = readNonEmptyString(reader, "name");
    const std::string sky = reader.string("sky");
    if (sky != "sunny" && sky != "overcast")
        reader.fail("sky", "\"" + sky + "\" is neither \"sunny\" nor \"overcast\"");
    slot.sky = sky == "sunny" ? BakeSetSky::Sunny : BakeSetSky::Overcast;
    const bool sunny = slot.sky == BakeSetSky::Sunny;
    slot.sky_map = readNonEmptyString(reader, "sky_map");
    if (sunny) {
        slot.local_time = readNonEmptyString(reader, "local_time");
        requireClockTime(reader, "local_time", slot.local_time);
        slot.utc = readNonEmptyString(reader, "utc");
        try {
            parseIso8601Utc(slot.utc);
        } catch (const std::invalid_argument& error) {
            reader.fail("utc", error.what());
        }
    } else {
        for (const char* name : {"local_time", "utc"})
            if (reader.has(name)) reader.fail(name, "only a sunny slot has a time");
    }
    slot.sun = readSun(reader, sunny);
    const ObjectReader sampling = reader.object("sky_sampling", {"method", "cosine_relative_variance"});
    slot.sky_sampling_method = readNonEmptyString(sampling, "method");
    // pi * integral(L^2 cos) / integral(L cos)^2 - 1 is >= 0 up to rounding (Cauchy-Schwarz); -1 is its floor.
    slot.cosine_relative_variance = readRanged(sampling, "cosine_relative_variance", kBakeSetCosineRelativeVariance);
    slot.building_irradiance = readNonEmptyString(reader, "building_irradiance");
    slot.ground_irradiance_with_building = readNonEmptyString(reader, "ground_irradiance_with_building");
    slot.ground_irradiance_without_building = readNonEmptyString(reader, "ground_irradiance_without_building");
    slot.invalid_texels = readCount(reader, "invalid_texels", kBakeSetInvalidTexels);
    if (const auto colour = reader.optionalObject("colour_statistics", {"space", "lab_mean", "lab_sigma", "texels"})) {
        readFixedText(*colour, "space", kColourSpace);
        BakeSetColourStatistics statistics;
        statistics.lab_mean = readVec3(*colour, "lab_mean", kBakeSetLabMean);
        statistics.lab_sigma = readVec3(*colour, "lab_sigma", kBakeSetLabSigma);
        statistics.texels = readCount(*colour, "texels", kBakeSetColourTexels);
        slot.colour_statistics = statistics;
    }
    return slot;
}

/// A partial set's marker: its slot is one of the site's slots, named once, and the one slot the manifest holds.
BakeSetPartial readPartial(const ObjectReader& reader, const BakeSetManifest& manifest) {
    BakeSetPartial partial;
    partial.slot = readNonEmptyString(reader, "slot");
    const json& names = reader.array("site_slots");
    for (size_t i = 0; i < names.size(); ++i) {
        const std::string pointer = reader.fieldPointer("site_slots") + "/" + std::to_string(i);
        partial.site_slots.push_back(json_reader::checkedString(reader.file(), pointer, names[i]));
        for (size_t j = 0; j < i; ++j)
            if (partial.site_slots[j] == partial.site_slots[i])
                throw InputError(reader.file(), pointer, "\"" + partial.site_slots[i] + "\" is named twice");
    }
    if (std::find(partial.site_slots.begin(), partial.site_slots.end(), partial.slot) == partial.site_slots.end())
        reader.fail("slot", "\"" + partial.slot + "\" is not one of site_slots");
    if (manifest.slots.size() != 1 || manifest.slots.front().name != partial.slot)
        reader.fail("slot", "a partial set holds exactly its own slot, \"" + partial.slot + "\", in /slots");
    partial.slot_independent_hash = parseHex64(reader, "slot_independent_hash");
    if (reader.has("slot_hash")) partial.slot_hash = parseHex64(reader, "slot_hash");
    return partial;
}

// /building: the mesh, its lightmap and, in bake sets since the sun horizons, their file.
BakeSetBuilding readBuilding(const ObjectReader& root) {
    BakeSetBuilding building_info;
    const ObjectReader building =
        root.object("building", {"mesh", "mesh_frame", "lightmap_uv", "lightmap_uv_source", "lightmap_resolution",
                                 "texels_per_metre", "texels", "irradiance_units", "sun_horizon",
                                 "sun_horizon_layout"});
    building_info.mesh = readNonEmptyString(building, "mesh");
    readFixedText(building, "mesh_frame", kMeshFrame);
    readFixedText(building, "lightmap_uv", kLightmapUv);
    building_info.lightmap_uv_source = building.string("lightmap_uv_source");
    building_info.lightmap_resolution = int(readRanged(building, "lightmap_resolution", kBakeSetLightmapResolution));
    building_info.texels_per_metre = readRanged(building, "texels_per_metre", kBakeSetTexelsPerMetre);
    building_info.texels = readCount(building, "texels", kBakeSetBuildingTexels);
    readFixedText(building, "irradiance_units", kIrradianceUnits);
    if (building.has("sun_horizon")) {  // optional: bake sets before them have none
        building_info.sun_horizon = readNonEmptyString(building, "sun_horizon");
        readFixedText(building, "sun_horizon_layout", kSunHorizonLayout);
    }
    return building_info;
}

BakeSetManifest readManifest(const ObjectReader& root) {
    BakeSetManifest manifest;
    root.string("format");  // its value was checked before anything else
    manifest.input_hash = parseHex64(root, "input_hash");

    const json& inputs = root.array("inputs");
    for (size_t i = 0; i < inputs.size(); ++i) {
        const ObjectReader input = elementObject(root, "inputs", i, {"role", "path", "fnv1a64"});
        BakeSetInput entry;
        entry.role = readNonEmptyString(input, "role");
        entry.path = readNonEmptyString(input, "path");
        requireInputKind(input, entry);
        parseHex64(input, "fnv1a64");
        entry.fnv1a64 = input.string("fnv1a64");
        manifest.inputs.push_back(entry);
    }

    const ObjectReader site =
        root.object("site", {"name", "latitude_deg", "longitude_deg", "height_m", "utc_offset_minutes"});
    manifest.site.name = site.string("name");
    manifest.site.latitude_deg = readRanged(site, "latitude_deg", kBakeSetLatitudeDeg);
    manifest.site.longitude_deg = readRanged(site, "longitude_deg", kBakeSetLongitudeDeg);
    manifest.site.height_m = readRanged(site, "height_m", kBakeSetHeightM);
    manifest.site.utc_offset_minutes = int(readRanged(site, "utc_offset_minutes", kBakeSetUtcOffsetMinutes));

    const ObjectReader settings = root.object("settings", {"samples_per_texel", "max_bounces", "seed", "denoised"});
    manifest.settings.samples_per_texel = uint32_t(readUnsigned(settings, "samples_per_texel", 1, UINT32_MAX));
    manifest.settings.max_bounces = readInt(settings, "max_bounces", 0, 1 << 16);
    manifest.settings.seed = uint32_t(readUnsigned(settings, "seed", 0, UINT32_MAX));
    manifest.settings.denoised = readBool(settings, "denoised");

    manifest.building = readBuilding(root);

    const ObjectReader ground =
        root.object("ground_grid", {"geometry", "geometry_channels", "origin_enu_m", "cell_m", "columns", "rows",
                                    "row_0", "ground_source", "irradiance_alpha", "albedo", "albedo_channels"});
    manifest.ground_grid.geometry = readNonEmptyString(ground, "geometry");
    readFixedText(ground, "geometry_channels", kGeometryChannels);
    const std::vector<double> origin = readRangedArray(ground, "origin_enu_m", 2, kBakeSetGroundOriginM);
    manifest.ground_grid.grid.origin_enu_m = {origin[0], origin[1]};
    manifest.ground_grid.grid.cell_m = readRanged(ground, "cell_m", kBakeSetGroundCellM);
    manifest.ground_grid.grid.columns = int(readRanged(ground, "columns", kBakeSetGroundColumns));
    manifest.ground_grid.grid.rows = int(readRanged(ground, "rows", kBakeSetGroundRows));
    readFixedText(ground, "row_0", kRow0);
    manifest.ground_grid.ground_source = readNonEmptyString(ground, "ground_source");
    readFixedText(ground, "irradiance_alpha", kIrradianceAlpha);
    if (ground.has("albedo")) {
        manifest.ground_grid.albedo = readNonEmptyString(ground, "albedo");
        readFixedText(ground, "albedo_channels", kGroundAlbedoChannels);
    }

    if (const auto occluder = root.optionalObject("occluder", {"mesh", "mesh_frame", "triangles", "source_triangles",
                                                               "target_error_m", "simplification_error_m"})) {
        BakeSetOccluderInfo info;
        info.mesh = readNonEmptyString(*occluder, "mesh");
        readFixedText(*occluder, "mesh_frame", kMeshFrame);
        info.source_triangles = readCount(*occluder, "source_triangles", kBakeSetOccluderSourceTriangles);
        info.triangles = readCount(*occluder, "triangles", kBakeSetOccluderTriangles);
        if (info.triangles > info.source_triangles)
            occluder->fail("triangles", std::to_string(info.triangles) + " is more than source_triangles " +
                                            std::to_string(info.source_triangles));
        info.target_error_m = readRanged(*occluder, "target_error_m", kBakeSetOccluderTargetErrorM);
        info.simplification_error_m = readRanged(*occluder, "simplification_error_m", kBakeSetOccluderSimplificationErrorM);
        manifest.occluder = info;
    }

    if (root.has("input_paths")) readFixedText(root, "input_paths", kInputPaths);
    manifest.input_paths_relative_to_folder = root.has("input_paths");

    const json& slots = root.array("slots");
    // The runtime draws from one slot at least: an empty list would open and then have no lightmap to sample.
    if (slots.empty()) root.fail("slots", "empty: a bake set holds at least one slot");
    for (size_t i = 0; i < slots.size(); ++i) {
        const ObjectReader slot =
            elementObject(root, "slots", i,
                          {"name", "sky", "sky_map", "local_time", "utc", "sun", "sky_sampling", "building_irradiance",
                           "ground_irradiance_with_building", "ground_irradiance_without_building", "invalid_texels",
                           "colour_statistics"});
        manifest.slots.push_back(readSlot(slot));
        const uint64_t lightmap_texels = uint64_t(manifest.building.lightmap_resolution) *
                                         uint64_t(manifest.building.lightmap_resolution);
        if (manifest.slots.back().invalid_texels > lightmap_texels)
            slot.fail("invalid_texels", std::to_string(manifest.slots.back().invalid_texels) +
                                            " is more than the lightmap's " + std::to_string(lightmap_texels) +
                                            " texels");
        for (size_t j = 0; j < i; ++j)
            if (manifest.slots[j].name == manifest.slots[i].name)
                slot.fail("name", "\"" + manifest.slots[i].name + "\" is already the name of /slots/" +
                                      std::to_string(j));
    }

    const ObjectReader statistics =
        root.object("statistics", {"rays_traced", "trace_seconds", "rays_per_second", "wall_seconds"});
    manifest.statistics.rays_traced = readUnsigned(statistics, "rays_traced", 0, UINT64_MAX);
    manifest.statistics.trace_seconds = statistics.number("trace_seconds", kNonNegative);
    manifest.statistics.rays_per_second = statistics.number("rays_per_second", kNonNegative);
    manifest.statistics.wall_seconds = statistics.number("wall_seconds", kNonNegative);

    const json& warnings = root.array("warnings");
    for (size_t i = 0; i < warnings.size(); ++i)
        manifest.warnings.push_back(json_reader::checkedString(
            root.file(), root.fieldPointer("warnings") + "/" + std::to_string(i), warnings[i]));

    if (const auto partial = root.optionalObject("partial", {"slot", "site_slots", "slot_independent_hash", "slot_hash"}))
        manifest.partial = readPartial(*partial, manifest);
    return manifest;
}

}  // namespace

std::string bakeSetSlotJson(const BakeSetSlot& slot) { return slotJson(slot, 0).dump(); }

std::string bakeSetManifestJson(const BakeSetManifest& manifest) {
    json inputs = json::array();
    for (const BakeSetInput& input : manifest.inputs)
        inputs.push_back({{"role", input.role}, {"path", input.path}, {"fnv1a64", input.fnv1a64}});
    json slots = json::array();
    for (size_t i = 0; i < manifest.slots.size(); ++i) slots.push_back(slotJson(manifest.slots[i], i));
    const BakeSetBuilding& building = manifest.building;
    const BakeSetGroundGrid& ground = manifest.ground_grid;
    const BakeSetStatistics& statistics = manifest.statistics;
    json document = {
        {"format", kBakeSetFormat},
        {"input_hash", hex64(manifest.input_hash)},
        {"inputs", inputs},
        {"site", {{"name", manifest.site.name},
                  {"latitude_deg", manifest.site.latitude_deg},
                  {"longitude_deg", manifest.site.longitude_deg},
                  {"height_m", manifest.site.height_m},
                  {"utc_offset_minutes", manifest.site.utc_offset_minutes}}},
        {"settings", {{"samples_per_texel", manifest.settings.samples_per_texel},
                      {"max_bounces", manifest.settings.max_bounces},
                      {"seed", manifest.settings.seed},
                      {"denoised", manifest.settings.denoised}}},
        {"building", {{"mesh", building.mesh},
                      {"mesh_frame", kMeshFrame},
                      {"lightmap_uv", kLightmapUv},
                      {"lightmap_uv_source", building.lightmap_uv_source},
                      {"lightmap_resolution", building.lightmap_resolution},
                      {"texels_per_metre", building.texels_per_metre},
                      {"texels", building.texels},
                      {"irradiance_units", kIrradianceUnits}}},
        {"ground_grid", {{"geometry", ground.geometry},
                         {"geometry_channels", kGeometryChannels},
                         {"origin_enu_m", {ground.grid.origin_enu_m.x, ground.grid.origin_enu_m.y}},
                         {"cell_m", ground.grid.cell_m},
                         {"columns", ground.grid.columns},
                         {"rows", ground.grid.rows},
                         {"row_0", kRow0},
                         {"ground_source", ground.ground_source},
                         {"irradiance_alpha", kIrradianceAlpha}}},
        {"slots", slots},
        {"statistics", {{"rays_traced", statistics.rays_traced},
                        {"trace_seconds", statistics.trace_seconds},
                        {"rays_per_second", statistics.rays_per_second},
                        {"wall_seconds", statistics.wall_seconds}}},
        {"warnings", manifest.warnings},
    };
    if (manifest.input_paths_relative_to_folder) document["input_paths"] = kInputPaths;
    if (manifest.partial)
        document["partial"] = {{"slot", manifest.partial->slot},
                               {"site_slots", manifest.partial->site_slots},
                               {"slot_independent_hash", hex64(manifest.partial->slot_independent_hash)}};
    if (manifest.partial && manifest.partial->slot_hash)
        document["partial"]["slot_hash"] = hex64(*manifest.partial->slot_hash);
    if (manifest.occluder)  // absent without an SfM mesh: such manifests keep their bytes
        document["occluder"] = {{"mesh", manifest.occluder->mesh},
                                {"mesh_frame", kMeshFrame},
                                {"triangles", manifest.occluder->triangles},
                                {"source_triangles", manifest.occluder->source_triangles},
                                {"target_error_m", manifest.occluder->target_error_m},
                                {"simplification_error_m", manifest.occluder->simplification_error_m}};
    if (!building.sun_horizon.empty()) {
        document["building"]["sun_horizon"] = building.sun_horizon;
        document["building"]["sun_horizon_layout"] = kSunHorizonLayout;
    }
    if (!ground.albedo.empty()) {
        document["ground_grid"]["albedo"] = ground.albedo;
        document["ground_grid"]["albedo_channels"] = kGroundAlbedoChannels;
    }
    requireFiniteNumbers(document, "");
    std::string text = document.dump(2) + "\n";
    // The writer refuses what the reader would refuse, by reading back what it wrote: one set of checks.
    try {
        parseBakeSetManifest("the manifest being written", text);
    } catch (const InputError& error) {
        throw std::invalid_argument(std::string("bake set manifest: ") + error.what());
    }
    return text;
}

void writeBakeSetManifest(const std::string& path, const BakeSetManifest& manifest) {
    const std::string text = bakeSetManifestJson(manifest);
    writeBytesAtomically(path, text.data(), text.size());
}

BakeSetManifest parseBakeSetManifest(const std::string& file, const std::string& text) {
    const json document = json_reader::parseDocument(file, text);
    // The version first: a manifest of another format is reported as such, not by its first unfamiliar field.
    if (document.is_object() && document.contains("format") && document["format"].is_string() &&
        document["format"].get<std::string>() != kBakeSetFormat)
        throw InputError(file, "/format",
                         "\"" + document["format"].get<std::string>() +
                             "\" is not a format this reader knows (expected \"" + kBakeSetFormat + "\")");
    const ObjectReader root(file, document, "",
                            {"format", "input_hash", "input_paths", "inputs", "site", "settings", "building",
                             "ground_grid", "occluder", "slots", "statistics", "warnings", "partial"});
    return readManifest(root);
}

BakeSetManifest readBakeSetManifest(const std::string& path) {
    // A manifest is a few kilobytes (tens with many warnings); its parsed tree takes many times its size, so a
    // larger file is refused unread.
    constexpr uint64_t kMaxManifestBytes = uint64_t(16) << 20;
    return parseBakeSetManifest(path, readWholeFile(path, kMaxManifestBytes));
}

}  // namespace gusuku

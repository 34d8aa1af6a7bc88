// The runtime pack's manifest reader (pack_manifest.h).

#include "pack_manifest.h"

#include <cmath>

#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/input_error.h"
#include "json_reader.h"

namespace gusuku::pack_detail {
namespace {

using json_detail::JsonValue;
using json_detail::parseJson;

using Type = JsonValue::Type;

// One JSON object and its pointer, for reading its members with errors that name them.
class Fields {
public:
    Fields(const JsonValue& value, std::string pointer, const std::string& file)
        : value_(value), pointer_(std::move(pointer)), file_(file) {
        if (value.type != Type::kObject) fail("", "is not an object");
    }
    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw InputError(file_, pointer_ + (key.empty() ? "" : "/" + key), problem);
    }
    bool has(const std::string& key) const { return value_.find(key) != nullptr; }
    const JsonValue& get(const std::string& key, Type type, const char* type_name) const {
        const JsonValue* member = value_.find(key);
        if (member == nullptr) fail(key, "is missing");
        if (member->type != type) fail(key, std::string("is not ") + type_name);
        return *member;
    }
    Fields object(const std::string& key) const { return Fields(get(key, Type::kObject, "an object"), pointer_ + "/" + key, file_); }
    const std::vector<JsonValue>& array(const std::string& key) const { return get(key, Type::kArray, "an array").items; }
    std::string text(const std::string& key) const { return get(key, Type::kString, "a string").text; }
    bool boolean(const std::string& key) const { return get(key, Type::kBool, "true or false").boolean; }
    double number(const std::string& key) const { return get(key, Type::kNumber, "a number").number; }
    /// A number within its row of gusuku/formats/bakeset_ranges.h, refused as the tools' reader refuses it.
    double ranged(const std::string& key, const BakeSetRange& range) const {
        const double value = number(key);
        if (const std::optional<std::string> problem = bakeSetValueProblem(range, value)) fail(key, *problem);
        return value;
    }
    /// Three numbers, each within the row, and of length 1 when the row is a direction.
    glm::dvec3 vector3(const std::string& key, const BakeSetRange& range) const {
        const std::vector<JsonValue>& items = array(key);
        if (items.size() != 3) fail(key, "does not have 3 numbers");
        glm::dvec3 out;
        for (int axis = 0; axis < 3; ++axis) {
            if (items[axis].type != Type::kNumber) fail(key + "/" + std::to_string(axis), "is not a number");
            out[axis] = items[axis].number;
            if (const std::optional<std::string> problem = bakeSetValueProblem(range, out[axis]))
                fail(key + "/" + std::to_string(axis), *problem);
        }
        if (const std::optional<std::string> problem = bakeSetDirectionProblem(range, out.x, out.y, out.z))
            fail(key, *problem);
        return out;
    }
    const std::string& pointer() const { return pointer_; }
    const std::string& file() const { return file_; }

private:
    const JsonValue& value_;
    std::string pointer_;
    const std::string& file_;
};

BakeSetSun readSun(const Fields& sun, bool sunny) {
    BakeSetSun out;
    out.present = sun.boolean("present");
    out.irradiance_source = sun.text("irradiance_source");
    if (sunny) {
        const double azimuth_deg = sun.ranged("azimuth_deg", kBakeSetSunAzimuthDeg);
        const double elevation_deg = sun.ranged("apparent_elevation_deg", kBakeSetSunElevationDeg);
        out.position = BakeSetSunPosition{azimuth_deg, elevation_deg,
                                          sun.vector3("direction_enu", kBakeSetSunDirectionEnu)};
    } else if (out.present) {
        sun.fail("present", "an overcast slot has no sun");
    }
    if (out.present) {
        if (const std::optional<std::string> problem =
                bakeSetValueProblem(kBakeSetPresentSunElevationDeg, out.position->apparent_elevation_deg))
            sun.fail("apparent_elevation_deg", *problem + ", yet present is true (a present sun is above the horizon)");
        out.irradiance_rgb = sun.vector3("irradiance_rgb", kBakeSetSunIrradiance);
        out.angular_radius_deg = sun.ranged("angular_radius_deg", kBakeSetSunAngularRadiusDeg);
    }
    return out;
}

BakeSetSlot readSlot(const Fields& slot) {
    BakeSetSlot out;
    out.name = slot.text("name");
    const std::string sky = slot.text("sky");
    if (sky != "sunny" && sky != "overcast") slot.fail("sky", "\"" + sky + "\" is neither \"sunny\" nor \"overcast\"");
    out.sky = sky == "sunny" ? BakeSetSky::Sunny : BakeSetSky::Overcast;
    if (slot.has("sky_map")) out.sky_map = slot.text("sky_map");
    if (out.sky == BakeSetSky::Sunny) {
        out.local_time = slot.text("local_time");
        out.utc = slot.text("utc");
    }
    out.sun = readSun(slot.object("sun"), out.sky == BakeSetSky::Sunny);
    if (slot.has("sky_sampling")) {
        const Fields sampling = slot.object("sky_sampling");
        out.sky_sampling_method = sampling.text("method");
        out.cosine_relative_variance = sampling.ranged("cosine_relative_variance", kBakeSetCosineRelativeVariance);
    }
    out.building_irradiance = slot.text("building_irradiance");
    out.ground_irradiance_with_building = slot.text("ground_irradiance_with_building");
    out.ground_irradiance_without_building = slot.text("ground_irradiance_without_building");
    out.invalid_texels = uint64_t(slot.ranged("invalid_texels", kBakeSetInvalidTexels));
    if (slot.has("colour_statistics")) {
        const Fields statistics = slot.object("colour_statistics");
        out.colour_statistics = BakeSetColourStatistics{statistics.vector3("lab_mean", kBakeSetLabMean),
                                                        statistics.vector3("lab_sigma", kBakeSetLabSigma),
                                                        uint64_t(statistics.ranged("texels", kBakeSetColourTexels))};
    }
    return out;
}

void readPlace(const Fields& root, BakeSetManifest& manifest) {
    const Fields site = root.object("site");
    manifest.site.name = site.text("name");
    manifest.site.latitude_deg = site.ranged("latitude_deg", kBakeSetLatitudeDeg);
    manifest.site.longitude_deg = site.ranged("longitude_deg", kBakeSetLongitudeDeg);
    manifest.site.height_m = site.ranged("height_m", kBakeSetHeightM);
    manifest.site.utc_offset_minutes = int(site.ranged("utc_offset_minutes", kBakeSetUtcOffsetMinutes));
    const Fields building = root.object("building");
    manifest.building.mesh = building.text("mesh");
    manifest.building.lightmap_uv_source = building.text("lightmap_uv_source");
    manifest.building.lightmap_resolution = int(building.ranged("lightmap_resolution", kBakeSetLightmapResolution));
    manifest.building.texels_per_metre = building.ranged("texels_per_metre", kBakeSetTexelsPerMetre);
    manifest.building.texels = uint64_t(building.ranged("texels", kBakeSetBuildingTexels));
    if (building.has("sun_horizon")) manifest.building.sun_horizon = building.text("sun_horizon");
    const Fields ground = root.object("ground_grid");
    manifest.ground_grid.geometry = ground.text("geometry");
    manifest.ground_grid.ground_source = ground.text("ground_source");
    if (ground.has("albedo")) manifest.ground_grid.albedo = ground.text("albedo");
    manifest.ground_grid.grid.cell_m = ground.ranged("cell_m", kBakeSetGroundCellM);
    manifest.ground_grid.grid.columns = int(ground.ranged("columns", kBakeSetGroundColumns));
    manifest.ground_grid.grid.rows = int(ground.ranged("rows", kBakeSetGroundRows));
    const std::vector<JsonValue>& origin = ground.array("origin_enu_m");
    if (origin.size() != 2 || origin[0].type != Type::kNumber || origin[1].type != Type::kNumber)
        ground.fail("origin_enu_m", "is not 2 numbers");
    for (int axis = 0; axis < 2; ++axis)
        if (const std::optional<std::string> problem = bakeSetValueProblem(kBakeSetGroundOriginM, origin[axis].number))
            ground.fail("origin_enu_m/" + std::to_string(axis), *problem);
    manifest.ground_grid.grid.origin_enu_m = {origin[0].number, origin[1].number};
    if (root.has("occluder")) {
        const Fields occluder = root.object("occluder");
        const std::string mesh = occluder.text("mesh");
        const uint64_t source_triangles = uint64_t(occluder.ranged("source_triangles", kBakeSetOccluderSourceTriangles));
        const uint64_t triangles = uint64_t(occluder.ranged("triangles", kBakeSetOccluderTriangles));
        if (triangles > source_triangles)
            occluder.fail("triangles", std::to_string(triangles) + " is more than source_triangles " +
                                           std::to_string(source_triangles));
        manifest.occluder = BakeSetOccluderInfo{mesh, triangles, source_triangles,
                                                occluder.ranged("target_error_m", kBakeSetOccluderTargetErrorM),
                                                occluder.ranged("simplification_error_m",
                                                                kBakeSetOccluderSimplificationErrorM)};
    }
}

}  // namespace

BakeSetManifest readPackManifest(const std::string& text, const std::string& file) {
    const JsonValue document = parseJson(text, file);
    const Fields root(document, "", file);
    if (root.text("format") != kBakeSetFormat)
        root.fail("format", "\"" + root.text("format") + "\" is not " + kBakeSetFormat);
    if (root.has("partial")) root.fail("partial", "a partial bake set (one slot of a split bake) has no runtime pack");
    BakeSetManifest manifest;
    readPlace(root, manifest);
    const std::vector<JsonValue>& slots = root.array("slots");
    if (slots.empty() || slots.size() > 64) root.fail("slots", "holds " + std::to_string(slots.size()) + " slots, not 1 to 64");
    for (size_t index = 0; index < slots.size(); ++index)
        manifest.slots.push_back(readSlot(Fields(slots[index], "/slots/" + std::to_string(index), file)));
    // How the set was made: informational here (the tools' reader checks them).
    if (root.has("warnings"))
        for (const JsonValue& warning : root.array("warnings"))
            if (warning.type == Type::kString) manifest.warnings.push_back(warning.text);
    return manifest;
}

}  // namespace gusuku::pack_detail

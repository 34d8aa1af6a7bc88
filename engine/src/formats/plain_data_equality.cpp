// Member-wise equality of the plain data in gusuku/formats/ground_grid.h and gusuku/formats/bakeset_manifest.h,
// written out because the installed headers are C++17 (a defaulted operator== is C++20). Each struct's members
// are named once, in a structured binding: a binding must name every data member, so a member added to a struct
// and not here fails to compile instead of being silently left out of the comparison.

#include <tuple>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/formats/ground_grid.h"

namespace gusuku {
namespace {
auto membersOf(const GroundGrid& value) {
    const auto& [origin_enu_m, cell_m, columns, rows] = value;
    return std::tie(origin_enu_m, cell_m, columns, rows);
}

auto membersOf(const GroundCellAddress& value) {
    const auto& [column, row] = value;
    return std::tie(column, row);
}

auto membersOf(const BakeSetInput& value) {
    const auto& [role, path, fnv1a64] = value;
    return std::tie(role, path, fnv1a64);
}

auto membersOf(const BakeSetSite& value) {
    const auto& [name, latitude_deg, longitude_deg, height_m, utc_offset_minutes] = value;
    return std::tie(name, latitude_deg, longitude_deg, height_m, utc_offset_minutes);
}

auto membersOf(const BakeSetSettings& value) {
    const auto& [samples_per_texel, max_bounces, seed, denoised] = value;
    return std::tie(samples_per_texel, max_bounces, seed, denoised);
}

auto membersOf(const BakeSetBuilding& value) {
    const auto& [mesh, lightmap_uv_source, lightmap_resolution, texels_per_metre, texels, sun_horizon] = value;
    return std::tie(mesh, lightmap_uv_source, lightmap_resolution, texels_per_metre, texels, sun_horizon);
}

auto membersOf(const BakeSetGroundGrid& value) {
    const auto& [geometry, grid, ground_source, albedo] = value;
    return std::tie(geometry, grid, ground_source, albedo);
}

auto membersOf(const BakeSetOccluderInfo& value) {
    const auto& [mesh, triangles, source_triangles, target_error_m, simplification_error_m] = value;
    return std::tie(mesh, triangles, source_triangles, target_error_m, simplification_error_m);
}

auto membersOf(const BakeSetSunPosition& value) {
    const auto& [azimuth_deg, apparent_elevation_deg, direction_enu] = value;
    return std::tie(azimuth_deg, apparent_elevation_deg, direction_enu);
}

auto membersOf(const BakeSetSun& value) {
    const auto& [present, irradiance_source, position, irradiance_rgb, angular_radius_deg] = value;
    return std::tie(present, irradiance_source, position, irradiance_rgb, angular_radius_deg);
}

auto membersOf(const BakeSetColourStatistics& value) {
    const auto& [lab_mean, lab_sigma, texels] = value;
    return std::tie(lab_mean, lab_sigma, texels);
}

auto membersOf(const BakeSetSlot& value) {
    const auto& [name, sky, sky_map, local_time, utc, sun, sky_sampling_method, cosine_relative_variance,
        building_irradiance, ground_irradiance_with_building, ground_irradiance_without_building, invalid_texels,
        colour_statistics] = value;
    return std::tie(name, sky, sky_map, local_time, utc, sun, sky_sampling_method, cosine_relative_variance,
        building_irradiance, ground_irradiance_with_building, ground_irradiance_without_building, invalid_texels,
        colour_statistics);
}

auto membersOf(const BakeSetStatistics& value) {
    const auto& [rays_traced, trace_seconds, rays_per_second, wall_seconds] = value;
    return std::tie(rays_traced, trace_seconds, rays_per_second, wall_seconds);
}

auto membersOf(const BakeSetPartial& value) {
    const auto& [slot, site_slots, slot_independent_hash, slot_hash] = value;
    return std::tie(slot, site_slots, slot_independent_hash, slot_hash);
}

auto membersOf(const BakeSetManifest& value) {
    const auto& [input_hash, input_paths_relative_to_folder, inputs, site, settings, building, ground_grid,
        occluder, slots, statistics, warnings, partial] = value;
    return std::tie(input_hash, input_paths_relative_to_folder, inputs, site, settings, building, ground_grid,
        occluder, slots, statistics, warnings, partial);
}
}  // namespace

bool GroundGrid::operator==(const GroundGrid& other) const {
    return membersOf(*this) == membersOf(other);
}
bool GroundCellAddress::operator==(const GroundCellAddress& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetInput::operator==(const BakeSetInput& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetSite::operator==(const BakeSetSite& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetSettings::operator==(const BakeSetSettings& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetBuilding::operator==(const BakeSetBuilding& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetGroundGrid::operator==(const BakeSetGroundGrid& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetOccluderInfo::operator==(const BakeSetOccluderInfo& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetSunPosition::operator==(const BakeSetSunPosition& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetSun::operator==(const BakeSetSun& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetColourStatistics::operator==(const BakeSetColourStatistics& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetSlot::operator==(const BakeSetSlot& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetStatistics::operator==(const BakeSetStatistics& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetPartial::operator==(const BakeSetPartial& other) const {
    return membersOf(*this) == membersOf(other);
}
bool BakeSetManifest::operator==(const BakeSetManifest& other) const {
    return membersOf(*this) == membersOf(other);
}

}  // namespace gusuku

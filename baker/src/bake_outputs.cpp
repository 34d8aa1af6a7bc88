#include "bake_outputs.h"

#include <cmath>
#include <cstdio>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "gusuku/atomic_file.h"
#include "gusuku/gltf_loader.h"
#include "gusuku/image.h"
#include "gusuku/time_utc.h"
#include "gusuku_bake/bake_statistics.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/lightmap_denoise.h"

namespace gusuku::bake {

namespace {

nlohmann::json vec3Json(const glm::dvec3& value) { return {value.x, value.y, value.z}; }

ImageRGBA imageFromTexels(const std::vector<glm::vec4>& texels, int width, int height) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.resize(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            const float value = texels[i][c];
            image.texels[i * 4 + size_t(c)] = std::isfinite(value) ? value : 0.0f;  // never NaN in an output
        }
    return image;
}

}  // namespace

ProcessedLightmap processBuildingLightmap(const BakeGeometry& geometry, const std::vector<glm::vec4>& sums,
                                          uint32_t samples, bool denoise) {
    const int resolution = geometry.lightmap_resolution;
    ProcessedLightmap result;
    result.image.assign(size_t(resolution) * size_t(resolution), glm::vec4(0.0f));
    std::vector<DenoiseGuide> guides(result.image.size());
    const float inverse_samples = 1.0f / float(std::max(samples, 1u));
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        const LightmapTexel& texel = geometry.texels[i];
        const size_t index = size_t(texel.y) * size_t(resolution) + size_t(texel.x);
        const bool valid = sums[i].w * inverse_samples <= kMaxBackfaceFraction;
        if (!valid) ++result.invalid_texels;
        result.image[index] = glm::vec4(glm::vec3(sums[i]) * inverse_samples, valid ? 1.0f : 0.0f);
        guides[index] = {texel.position, texel.shading_normal};
    }
    if (denoise) denoiseLightmap(result.image, guides, resolution, denoiseOptionsForSamples(samples));
    result.per_texel.resize(geometry.texels.size());
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        const LightmapTexel& texel = geometry.texels[i];
        result.per_texel[i] = result.image[size_t(texel.y) * size_t(resolution) + size_t(texel.x)];
    }
    // Invalid texels inside charts and the padding around them take their valid neighbours' values, so bilinear
    // filtering at chart edges never reads black; alpha then marks only the texels that were traced and valid.
    std::vector<bool> traced_valid(result.image.size());
    for (size_t i = 0; i < result.image.size(); ++i) traced_valid[i] = result.image[i].a > 0.0f;
    dilateLightmap(result.image, resolution, 8);
    for (size_t i = 0; i < result.image.size(); ++i) result.image[i].a = traced_valid[i] ? 1.0f : 0.0f;
    return result;
}

BakeOutputWriter::BakeOutputWriter(std::string output_dir, const BakeGeometry& geometry, uint32_t samples,
                                   bool denoise)
    : output_dir_(std::move(output_dir)), geometry_(geometry), samples_(samples), denoise_(denoise) {}

void BakeOutputWriter::writeGeometry() {
    // The building as baked: ENU positions expressed in glTF's Y-up axes, with TEXCOORD_1 = the lightmap UVs.
    writeGlb(output_dir_ + "/building.glb", geometry_.building, glm::inverse(enuFromGltfYUp()));
    const GroundRegion& region = geometry_.ground_region;
    std::vector<glm::vec4> texels(size_t(region.columns) * size_t(region.rows));
    for (size_t i = 0; i < texels.size(); ++i) {
        const GroundCell& cell = geometry_.ground_cells[i];
        texels[i] = glm::vec4(cell.normal, cell.height_m);
    }
    writeExr(output_dir_ + "/ground_geometry.exr", imageFromTexels(texels, region.columns, region.rows), true);
}

void BakeOutputWriter::writeGroundImage(const std::string& file, const std::vector<glm::vec4>& sums) {
    const GroundRegion& region = geometry_.ground_region;
    std::vector<glm::vec4> texels(size_t(region.columns) * size_t(region.rows), glm::vec4(0.0f));
    const float inverse_samples = 1.0f / float(std::max(samples_, 1u));
    size_t point = 0;
    for (size_t i = 0; i < texels.size(); ++i)
        if (geometry_.ground_cells[i].valid) texels[i] = glm::vec4(glm::vec3(sums[point++]) * inverse_samples, 1.0f);
    writeExr(output_dir_ + "/" + file, imageFromTexels(texels, region.columns, region.rows), true);
}

void BakeOutputWriter::writeSlot(const SlotLighting& lighting, const std::vector<glm::vec4>& building_sums,
                                 const std::vector<glm::vec4>& ground_with_sums,
                                 const std::vector<glm::vec4>& ground_without_sums) {
    const std::string& name = lighting.slot.name;
    const ProcessedLightmap lightmap = processBuildingLightmap(geometry_, building_sums, samples_, denoise_);
    const int resolution = geometry_.lightmap_resolution;
    const std::string building_file = "building_" + name + ".exr";
    writeExr(output_dir_ + "/" + building_file, imageFromTexels(lightmap.image, resolution, resolution), true);
    const std::string with_file = "ground_" + name + "_with.exr";
    const std::string without_file = "ground_" + name + "_without.exr";
    writeGroundImage(with_file, ground_with_sums);
    writeGroundImage(without_file, ground_without_sums);

    const LabStatistics statistics = bakedAppearanceStatistics(geometry_, lightmap.per_texel, lighting.sun);
    nlohmann::json sun = {{"present", lighting.sun.present},
                          {"irradiance_source", lighting.sun_irradiance_source}};
    if (lighting.slot.sky == SlotSky::Sunny) {
        sun["azimuth_deg"] = lighting.sun_position.azimuth_deg;
        sun["apparent_elevation_deg"] = lighting.sun_position.apparent_elevation_deg;
        sun["direction_enu"] = vec3Json(lighting.sun_position.direction_enu);
    }
    if (lighting.sun.present) {
        sun["irradiance_rgb"] = vec3Json(lighting.sun.irradiance_rgb);
        sun["angular_radius_deg"] = lighting.sun.angular_radius_deg;
    }
    nlohmann::json entry = {
        {"name", name},
        {"sky", lighting.slot.sky == SlotSky::Sunny ? "sunny" : "overcast"},
        {"sky_map", lighting.sky->path},
        {"sky_sampling",
         {{"method", skySamplingName(resolveSkySampling(SkySampling::Automatic, lighting.sky->tables))},
          {"cosine_relative_variance", lighting.sky->tables.cosine_relative_variance}}},
        {"sun", sun},
        {"building_irradiance", building_file},
        {"ground_irradiance_with_building", with_file},
        {"ground_irradiance_without_building", without_file},
        {"invalid_texels", lightmap.invalid_texels},
        {"colour_statistics", {{"space", "CIE Lab (D65) of linear radiance rho/pi*(E_ind + V E_sun cos)"},
                               {"lab_mean", {statistics.mean.x, statistics.mean.y, statistics.mean.z}},
                               {"lab_sigma", {statistics.sigma.x, statistics.sigma.y, statistics.sigma.z}},
                               {"texels", statistics.texel_count}}},
    };
    if (lighting.slot.sky == SlotSky::Sunny) {
        entry["local_time"] = lighting.slot.local_time;
        entry["utc"] = formatIso8601(lighting.slot.utc_seconds, 0);
    }
    slot_entries_.push_back(entry);
}

void BakeOutputWriter::writeManifest(const SiteConfig& site, uint64_t input_hash, const BakeReport& report) {
    char hash_text[17];
    std::snprintf(hash_text, sizeof hash_text, "%016llx", static_cast<unsigned long long>(input_hash));
    nlohmann::json inputs = nlohmann::json::array();
    const auto addInput = [&](const std::string& role, const std::string& path) {
        inputs.push_back({{"role", role}, {"path", path}, {"fnv1a64", hashFileHex(path)}});
    };
    addInput("site", site.file);
    addInput("building", site.building.path);
    if (site.sfm_mesh) addInput("sfm_mesh", site.sfm_mesh->path);
    addInput("sunny_sky", site.sunny_sky.path);
    if (site.overcast_sky) addInput("overcast_sky", site.overcast_sky->path);
    const GroundRegion& region = geometry_.ground_region;
    const nlohmann::json manifest = {
        {"format", kBakeSetFormat},
        {"input_hash", hash_text},
        {"inputs", inputs},
        {"site", {{"name", site.site.name},
                  {"latitude_deg", site.site.reference.latitude_deg},
                  {"longitude_deg", site.site.reference.longitude_deg},
                  {"height_m", site.site.reference.height_m},
                  {"utc_offset_minutes", site.site.utc_offset_minutes}}},
        {"settings", {{"samples_per_texel", samples_},
                      {"max_bounces", site.bake.max_bounces},
                      {"seed", site.bake.seed},
                      {"denoised", denoise_}}},
        {"building", {{"mesh", "building.glb"},
                      {"mesh_frame", "site ENU metres in glTF Y-up axes: glTF (x, y, z) = ENU (x, z, -y)"},
                      {"lightmap_uv", "TEXCOORD_1"},
                      {"lightmap_uv_source", geometry_.lightmap_uv_source},
                      {"lightmap_resolution", geometry_.lightmap_resolution},
                      {"texels_per_metre", geometry_.effective_texels_per_metre},
                      {"texels", geometry_.texels.size()},
                      {"irradiance_units", "the sky maps' linear radiance units times steradians"}}},
        {"ground_grid", {{"geometry", "ground_geometry.exr"},
                         {"geometry_channels", "RGB: unit normal (ENU), A: height (ENU z, metres)"},
                         {"origin_enu_m", {region.origin_enu_m.x, region.origin_enu_m.y}},
                         {"cell_m", region.cell_m},
                         {"columns", region.columns},
                         {"rows", region.rows},
                         {"row_0", "north edge"},
                         {"ground_source", geometry_.site_mesh_is_stand_in ? "flat plane at z = 0" : "sfm_mesh"},
                         {"irradiance_alpha", "1 where the ground exists under the cell"}}},
        {"slots", slot_entries_},
        {"statistics", {{"rays_traced", report.rays_traced},
                        {"trace_seconds", report.trace_seconds},
                        {"rays_per_second", report.trace_seconds > 0.0 ? double(report.rays_traced) / report.trace_seconds : 0.0},
                        {"wall_seconds", report.wall_seconds}}},
        {"warnings", report.warnings},
    };
    const std::string text = manifest.dump(2) + "\n";
    writeBytesAtomically(output_dir_ + "/manifest.json", text.data(), text.size());
}

}  // namespace gusuku::bake

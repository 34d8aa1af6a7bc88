#include "bake_outputs.h"
#include "ground_covered_cells.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "bake_statistics.h"
#include "sun_horizon_output.h"
#include "ground_albedo.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku_bake/lightmap_denoise.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku_bake/bake_merge.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/assets/glb_positions.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/occluder.h"

namespace gusuku::bake {

namespace {

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
                                          uint32_t samples, bool denoise,
                                          const std::vector<float>& texel_luminance_variance) {
    const int resolution = geometry.lightmap_resolution;
    ProcessedLightmap result;
    result.image.assign(size_t(resolution) * size_t(resolution), glm::vec4(0.0f));
    std::vector<DenoiseGuide> guides(result.image.size());
    if (sums.size() != geometry.texels.size() ||
        (!texel_luminance_variance.empty() && texel_luminance_variance.size() != sums.size()))
        throw std::invalid_argument("processBuildingLightmap: sums or variances do not match the texels");
    // One sample measures no variance: the filter then stops on relative irradiance alone.
    const bool with_variance = !texel_luminance_variance.empty() && samples >= 2;
    std::vector<float> variance_image(with_variance ? result.image.size() : 0, 0.0f);
    const float inverse_samples = 1.0f / float(std::max(samples, 1u));
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        const LightmapTexel& texel = geometry.texels[i];
        const size_t index = size_t(texel.y) * size_t(resolution) + size_t(texel.x);
        const bool valid = sums[i].w * inverse_samples <= kMaxBackfaceFraction;
        if (!valid) ++result.invalid_texels;
        result.image[index] = glm::vec4(glm::vec3(sums[i]) * inverse_samples, valid ? 1.0f : 0.0f);
        guides[index] = {texel.position, texel.shading_normal, geometry.texel_chart[i]};
        if (with_variance) variance_image[index] = texel_luminance_variance[i];
    }
    if (denoise)
        denoiseLightmap(result.image, guides, resolution, denoiseOptionsForSamples(samples, with_variance),
                        variance_image);
    result.per_texel.resize(geometry.texels.size());
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        const LightmapTexel& texel = geometry.texels[i];
        result.per_texel[i] = result.image[size_t(texel.y) * size_t(resolution) + size_t(texel.x)];
    }
    // Invalid texels inside charts and the gutter around them take their valid neighbours' values, so bilinear
    // filtering at chart edges never reads black, each from its own chart only (a chart's read texels may touch
    // another's); alpha then marks only the texels that were traced and valid.
    std::vector<bool> traced_valid(result.image.size());
    for (size_t i = 0; i < result.image.size(); ++i) traced_valid[i] = result.image[i].a > 0.0f;
    dilateLightmapWithinCharts(result.image, geometry.texel_reader_chart, resolution, 8);
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
    // The ground's base colour per cell, for the runtime's ground colour match (ground_albedo.h).
    writeExr(output_dir_ + "/" + kGroundAlbedoFile,
             imageFromTexels(sampleGroundAlbedo(geometry_), region.columns, region.rows), true);
    writeOccluder();
    writeSunHorizonFile(output_dir_, geometry_);
}

void BakeOutputWriter::writeOccluder() {
    const std::string path = output_dir_ + "/occluder.glb";
    // The site's triangles follow the building's in the trace scene; a flat stand-in ground occludes nothing
    // real, so it gets no occluder (and one left by an older bake of this folder goes).
    const TraceScene& scene = geometry_.scene;
    const std::vector<uint32_t> site_indices(scene.mesh.indices.begin() + long(3 * scene.building_triangle_count),
                                             scene.mesh.indices.end());
    if (geometry_.site_mesh_is_stand_in || site_indices.empty()) {
        std::filesystem::remove(path);
        return;
    }
    const OccluderMesh occluder = simplifyOccluder(scene.mesh.positions, site_indices, kOccluderTargetErrorM);
    writePositionsGlb(path, occluder.positions, occluder.indices, glm::inverse(enuFromGltfYUp()));
    occluder_ = BakeSetOccluderInfo{"occluder.glb", occluder.triangleCount(), occluder.source_triangles,
                                    kOccluderTargetErrorM, occluder.error_m};
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
                                 const std::vector<float>& building_luminance_variance,
                                 const std::vector<glm::vec4>& ground_with_sums,
                                 const std::vector<glm::vec4>& ground_without_sums) {
    const std::string& name = lighting.slot.name;
    const ProcessedLightmap lightmap = processBuildingLightmap(geometry_, building_sums, samples_, denoise_,
                                                               building_luminance_variance);
    const int resolution = geometry_.lightmap_resolution;
    const std::string building_file = "building_" + name + ".exr";
    writeExr(output_dir_ + "/" + building_file, imageFromTexels(lightmap.image, resolution, resolution), true);
    const std::string with_file = "ground_" + name + "_with.exr";
    const std::string without_file = "ground_" + name + "_without.exr";
    // The cells the building covers carry their open neighbours' ratio (ground_covered_cells.h).
    writeGroundImage(with_file, withCoveredCellsFilled(geometry_, coveredGroundCells(geometry_), ground_with_sums,
                                                       ground_without_sums));
    writeGroundImage(without_file, ground_without_sums);

    const LabStatistics statistics = bakedAppearanceStatistics(geometry_, lightmap.per_texel, lighting.sun);
    BakeSetSlot entry;
    entry.name = name;
    entry.sky = lighting.slot.sky == SlotSky::Sunny ? BakeSetSky::Sunny : BakeSetSky::Overcast;
    entry.sky_map = bakeSetRelativeInputPath(output_dir_, lighting.sky->path);
    entry.sky_sampling_method = skySamplingName(resolveSkySampling(SkySampling::Automatic, lighting.sky->tables));
    entry.cosine_relative_variance = lighting.sky->tables.cosine_relative_variance;
    entry.sun.present = lighting.sun.present;
    entry.sun.irradiance_source = lighting.sun_irradiance_source;
    if (lighting.slot.sky == SlotSky::Sunny) {
        entry.local_time = lighting.slot.local_time;
        entry.utc = formatIso8601(lighting.slot.utc_seconds, 0);
        entry.sun.position = BakeSetSunPosition{lighting.sun_position.azimuth_deg,
                                                lighting.sun_position.apparent_elevation_deg,
                                                lighting.sun_position.direction_enu};
    }
    if (lighting.sun.present) {
        entry.sun.irradiance_rgb = lighting.sun.irradiance_rgb;
        entry.sun.angular_radius_deg = lighting.sun.angular_radius_deg;
    }
    entry.building_irradiance = building_file;
    entry.ground_irradiance_with_building = with_file;
    entry.ground_irradiance_without_building = without_file;
    entry.invalid_texels = lightmap.invalid_texels;
    entry.colour_statistics =
        BakeSetColourStatistics{glm::dvec3(statistics.mean), glm::dvec3(statistics.sigma), statistics.texel_count};
    slots_.push_back(entry);
}

uint64_t BakeOutputWriter::slotIndependentHash() const {
    BakeSetManifest names;
    if (occluder_) names.occluder = occluder_;
    names.ground_grid.albedo = kGroundAlbedoFile;
    names.building.sun_horizon = kSunHorizonFile;  // writeGeometry wrote it, as writeManifest records
    return slotIndependentFilesHash(output_dir_, names);
}

void BakeOutputWriter::writeManifest(const SiteConfig& site, uint64_t input_hash, const BakeReport& report,
                                     const std::optional<BakeSetPartial>& partial) {
    BakeSetManifest manifest;
    manifest.input_hash = input_hash;
    manifest.input_paths_relative_to_folder = true;
    const auto addInput = [&](const std::string& role, const std::string& path) {
        manifest.inputs.push_back({role, bakeSetRelativeInputPath(output_dir_, path), hashFileHex(path)});
    };
    addInput("site", site.file);
    addInput("building", site.building.path);
    if (site.sfm_mesh) addInput("sfm_mesh", site.sfm_mesh->path);
    // A sky's every photo (a bracket) is an input under its role; the first is the sky's path.
    const auto addSky = [&](const std::string& role, const SkyConfig& sky) {
        addInput(role, sky.path);
        for (size_t i = 1; i < sky.photos.size(); ++i) addInput(role, sky.photos[i].path);
    };
    addSky("sunny_sky", site.sunny_sky);
    if (site.overcast_sky) addSky("overcast_sky", *site.overcast_sky);
    manifest.site = {site.site.name, site.site.reference.latitude_deg, site.site.reference.longitude_deg,
                     site.site.reference.height_m, site.site.utc_offset_minutes};
    manifest.settings = {samples_, site.bake.max_bounces, site.bake.seed, denoise_};
    manifest.building.lightmap_uv_source = geometry_.lightmap_uv_source;
    manifest.building.lightmap_resolution = geometry_.lightmap_resolution;
    manifest.building.texels_per_metre = geometry_.effective_texels_per_metre;
    manifest.building.texels = geometry_.texels.size();
    manifest.building.sun_horizon = kSunHorizonFile;  // writeGeometry wrote it
    manifest.ground_grid.grid = geometry_.ground_region;
    manifest.ground_grid.ground_source = geometry_.site_mesh_is_stand_in ? "flat plane at z = 0" : "sfm_mesh";
    manifest.ground_grid.albedo = kGroundAlbedoFile;
    manifest.occluder = occluder_;
    manifest.slots = slots_;
    manifest.statistics = {report.rays_traced, report.trace_seconds,
                           report.trace_seconds > 0.0 ? double(report.rays_traced) / report.trace_seconds : 0.0,
                           report.wall_seconds};
    manifest.warnings = report.warnings;
    manifest.partial = partial;
    // A partial set holds one slot, written by now: its hash lets merge refuse an edited entry or file.
    if (manifest.partial && manifest.slots.size() == 1)
        manifest.partial->slot_hash = slotHash(output_dir_, manifest.slots.front());
    writeBakeSetManifest(output_dir_ + "/manifest.json", manifest);
}

}  // namespace gusuku::bake

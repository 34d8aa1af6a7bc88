#include "bake_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <memory>

#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

namespace {

constexpr int kMaxLightmapResolution = 4096;
// A building larger than this is a unit or scale mistake (a glTF in millimetres, building.scale 1e6): a lost
// building is tens of metres across, a whole castle a few hundred.
constexpr double kMaxBuildingExtentM = 10000.0;
// The lightmap texels a site may ask for before the charts are made: the density is lowered to fit the largest
// lightmap, but charts are first cut and packed at the requested density, whose cost grows with the texel count;
// past 16 times the largest lightmap (a fourfold density cut) the request is a mistake, refused before that work.
constexpr double kMaxRequestedLightmapTexels = 16.0 * double(kMaxLightmapResolution) * kMaxLightmapResolution;

// The least share of the lightmap's texels a bake covers: charts are packed at kLightmapPackingOverhead = 2 (half
// the square), glTF layouts fill as much or more; the sample house at 1000 texels/m covered 76 % of 4096^2.
constexpr double kLeastCoveredFraction = 0.5;

std::string formatNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

// The fewest lightmap texels the bake will trace for `building` at texels_per_metre (requested_texels = its area
// x the density squared): generated charts cover about the requested count, or at least kLeastCoveredFraction of
// the largest lightmap the density is lowered to fit; the glTF's own lightmap UVs (TEXCOORD_1, kept when they
// pass the check) cover their share of the unit square at the resolution chosen for them.
double leastLightmapTexels(const TriangleMesh& building, double texels_per_metre, double requested_texels) {
    const double largest_lightmap_texels = double(kMaxLightmapResolution) * kMaxLightmapResolution;
    double least = kLeastCoveredFraction * std::min(requested_texels, largest_lightmap_texels);
    if (building.has_uv1 && building.uv1.size() == building.positions.size()) {
        double uv_area = 0.0;
        for (size_t i = 0; i + 2 < building.indices.size(); i += 3) {
            const glm::dvec2 a = building.uv1[building.indices[i]];
            const glm::dvec2 b = building.uv1[building.indices[i + 1]];
            const glm::dvec2 c = building.uv1[building.indices[i + 2]];
            uv_area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        }
        const double resolution = chooseLightmapResolution(building, texels_per_metre);
        least = std::min(least, std::min(uv_area, 1.0) * resolution * resolution);
    }
    return least;
}

// Refuses, before any chart is cut, a building whose size or requested texel count no bake can hold, naming the
// site.json field to change. storage_buffer_limit_bytes (0: none) is the device's: the building's lightmap texels
// are traced from one storage buffer of query points.
void requireBakeableBuilding(const SiteConfig& site, const TriangleMesh& building,
                             uint64_t storage_buffer_limit_bytes) {
    const Bounds3 bounds = meshBounds(building);
    const glm::dvec3 extent = glm::dvec3(bounds.max) - glm::dvec3(bounds.min);
    const double largest_extent = std::max({extent.x, extent.y, extent.z});
    if (!std::isfinite(largest_extent) || largest_extent > kMaxBuildingExtentM)
        throw InputError(site.file, "/building/scale",
                         "the building spans " + formatNumber(largest_extent) + " m once placed (scale " +
                             formatNumber(site.building.scale) + "), more than " + formatNumber(kMaxBuildingExtentM) +
                             " m: check building.scale and the glTF's units (metres)");
    const double area_m2 = meshSurfaceAreaM2(building);
    const double texels_per_metre = site.bake.texels_per_metre;
    const double requested_texels = area_m2 * texels_per_metre * texels_per_metre;
    if (requested_texels > kMaxRequestedLightmapTexels)
        throw InputError(site.file, "/bake/texels_per_metre",
                         formatNumber(texels_per_metre) + " texels/m on the building's " + formatNumber(area_m2) +
                             " m^2 of surface asks for " + formatNumber(requested_texels) +
                             " lightmap texels, more than the limit " + formatNumber(kMaxRequestedLightmapTexels) +
                             " (16 x " + std::to_string(kMaxLightmapResolution) + "^2): at most " +
                             formatNumber(std::sqrt(kMaxRequestedLightmapTexels / area_m2)) +
                             " texels/m for this building");
    if (storage_buffer_limit_bytes == 0) return;
    // Query points for the texels the lightmap will hold at least, past the device's buffer limit: refused here, in
    // a moment, where the bake's own check after charting and rasterising (deviceLimitProblems) took minutes and
    // a gigabyte at 1000 texels/m to say the same.
    const double least_texels = leastLightmapTexels(building, texels_per_metre, requested_texels);
    const double least_bytes = least_texels * double(sizeof(QueryPointGpu));
    if (least_bytes > double(storage_buffer_limit_bytes)) {
        const double device_texels = double(storage_buffer_limit_bytes) / double(sizeof(QueryPointGpu));
        throw InputError(site.file, "/bake/texels_per_metre",
                         formatNumber(texels_per_metre) + " texels/m on the building's " + formatNumber(area_m2) +
                             " m^2 of surface make at least " + formatNumber(least_texels) +
                             " lightmap texels, whose query points need at least " +
                             formatNumber(least_bytes / double(1 << 20)) +
                             " MiB in one storage buffer, over the device's maxStorageBufferRange of " +
                             formatNumber(double(storage_buffer_limit_bytes) / double(1 << 20)) +
                             " MiB (refused before charting); lower bake.texels_per_metre to about " +
                             formatNumber(std::sqrt(device_texels / area_m2)) + " or less");
    }
}

// Lightmap UVs: the glTF's own when they pass the check at the chosen resolution, else our charts.
void chooseLightmapUvs(BakeGeometry& geometry, const TriangleMesh& loaded, double texels_per_metre) {
    const int resolution = chooseLightmapResolution(loaded, texels_per_metre);
    geometry.lightmap_resolution = resolution;
    if (loaded.has_uv1) {
        const UvCheckReport report = checkLightmapUvs(loaded, resolution);
        if (report.ok) {
            geometry.building = loaded;
            geometry.lightmap_uv_source = "TEXCOORD_1 from the glTF";
            geometry.effective_texels_per_metre = texels_per_metre;
            return;
        }
        geometry.warnings.push_back("building TEXCOORD_1 not usable as a lightmap (" + report.message +
                                    "); generating charts instead");
    }
    // Our charts get the smallest lightmap that holds them at the requested density (lower only past the cap).
    LightmapCharts charts = generateLightmapChartsInSmallestLightmap(loaded, texels_per_metre, kMaxLightmapResolution);
    geometry.lightmap_resolution = charts.resolution;
    geometry.building = std::move(charts.mesh);
    geometry.effective_texels_per_metre = charts.texels_per_metre;
    geometry.lightmap_uv_source = "generated charts (" + std::to_string(charts.chart_count) + " charts)";
    if (charts.texels_per_metre < texels_per_metre * 0.999)
        geometry.warnings.push_back("lightmap density lowered from " + std::to_string(texels_per_metre) + " to " +
                                    std::to_string(charts.texels_per_metre) + " texels/m to fit " +
                                    std::to_string(geometry.lightmap_resolution) + "^2");
}

}  // namespace

TriangleMesh loadSiteMeshOrStandIn(const SiteConfig& site, const Bounds3& building_bounds, int max_texture_size,
                                   std::vector<std::string>& warnings, bool& is_stand_in) {
    is_stand_in = !site.sfm_mesh;
    if (site.sfm_mesh) {
        GltfLoadOptions site_options;
        site_options.enu_from_model = site.sfm_mesh->enuFromModel();
        site_options.max_texture_size = max_texture_size;
        return loadSiteMesh(site.sfm_mesh->path, site_options, &warnings);
    }
    const glm::vec3 extent = building_bounds.max - building_bounds.min;
    const double half_size = 4.0 * std::max({double(extent.x), double(extent.y), double(extent.z), 10.0});
    warnings.push_back("site.json has no sfm_mesh: the ground is a flat grey plane at z = 0");
    return makeFlatGround(half_size);
}

BakeGeometry prepareBakeGeometry(const SiteConfig& site, double lowest_sun_elevation_deg, int max_texture_size,
                                 int building_texture_size, uint64_t storage_buffer_limit_bytes) {
    BakeGeometry geometry;
    GltfLoadOptions building_options;
    building_options.enu_from_model = site.building.enuFromModel(site.site.reference);
    building_options.max_texture_size = building_texture_size;
    const TriangleMesh building = loadGltf(site.building.path, building_options, &geometry.warnings);
    requireBakeableBuilding(site, building, storage_buffer_limit_bytes);
    chooseLightmapUvs(geometry, building, site.bake.texels_per_metre);
    geometry.texels = rasterizeLightmapTexels(geometry.building, geometry.lightmap_resolution);
    const std::vector<uint32_t> triangle_chart = lightmapUvCharts(geometry.building);
    for (const LightmapTexel& texel : geometry.texels) geometry.texel_chart.push_back(triangle_chart[texel.triangle]);
    geometry.texel_reader_chart = lightmapTexelReaderCharts(geometry.building, triangle_chart, geometry.lightmap_resolution);

    const Bounds3 building_bounds = meshBounds(geometry.building);
    const TriangleMesh site_mesh = loadSiteMeshOrStandIn(site, building_bounds, max_texture_size, geometry.warnings,
                                                         geometry.site_mesh_is_stand_in);
    geometry.scene = makeTraceScene(geometry.building, &site_mesh);
    geometry.scene.bvh = std::make_shared<const Bvh>(buildBvh(geometry.scene.mesh, geometry.scene.triangle_flags));
    if (geometry.cpuBvh().dropped_triangle_count > 0)
        geometry.warnings.push_back(std::to_string(geometry.cpuBvh().dropped_triangle_count) +
                                    " degenerate or non-finite triangles were left out of the trace");

    geometry.ground_region =
        chooseSiteGroundRegion(building_bounds, site_mesh, lowest_sun_elevation_deg, site.bake.ground_cell_m);
    const Bounds3 scene_bounds = meshBounds(geometry.scene.mesh);
    geometry.ground_cells = sampleGround(geometry.ground_region, geometry.cpuBvh(), geometry.scene.mesh,
                                         kTriangleFlagBuilding, scene_bounds.max.z + 1.0f);
    return geometry;
}

}  // namespace gusuku::bake

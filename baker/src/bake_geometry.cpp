#include "bake_geometry.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "gusuku/assets/gltf_loader.h"
#include "gusuku/maths/input_error.h"

namespace gusuku::bake {

namespace {

constexpr int kMaxLightmapResolution = 4096;

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
        return loadGltf(site.sfm_mesh->path, site_options, &warnings);
    }
    const glm::vec3 extent = building_bounds.max - building_bounds.min;
    const double half_size = 4.0 * std::max({double(extent.x), double(extent.y), double(extent.z), 10.0});
    warnings.push_back("site.json has no sfm_mesh: the ground is a flat grey plane at z = 0");
    return makeFlatGround(half_size);
}

BakeGeometry prepareBakeGeometry(const SiteConfig& site, double lowest_sun_elevation_deg, int max_texture_size) {
    BakeGeometry geometry;
    GltfLoadOptions building_options;
    building_options.enu_from_model = site.building.enuFromModel(site.site.reference);
    building_options.max_texture_size = max_texture_size;
    const TriangleMesh building = loadGltf(site.building.path, building_options, &geometry.warnings);
    chooseLightmapUvs(geometry, building, site.bake.texels_per_metre);
    geometry.texels = rasterizeLightmapTexels(geometry.building, geometry.lightmap_resolution);
    const std::vector<uint32_t> triangle_chart = lightmapUvCharts(geometry.building);
    for (const LightmapTexel& texel : geometry.texels) geometry.texel_chart.push_back(triangle_chart[texel.triangle]);

    const Bounds3 building_bounds = meshBounds(geometry.building);
    const TriangleMesh site_mesh = loadSiteMeshOrStandIn(site, building_bounds, max_texture_size, geometry.warnings,
                                                         geometry.site_mesh_is_stand_in);
    geometry.scene = makeTraceScene(geometry.building, &site_mesh);
    geometry.scene.bvh = std::make_shared<const Bvh>(buildBvh(geometry.scene.mesh, geometry.scene.triangle_flags));
    if (geometry.cpuBvh().dropped_triangle_count > 0)
        geometry.warnings.push_back(std::to_string(geometry.cpuBvh().dropped_triangle_count) +
                                    " degenerate or non-finite triangles were left out of the trace");

    geometry.ground_region = chooseGroundRegion(building_bounds, lowest_sun_elevation_deg, site.bake.ground_cell_m);
    const Bounds3 scene_bounds = meshBounds(geometry.scene.mesh);
    geometry.ground_cells = sampleGround(geometry.ground_region, geometry.cpuBvh(), geometry.scene.mesh,
                                         kTriangleFlagBuilding, scene_bounds.max.z + 1.0f);
    return geometry;
}

}  // namespace gusuku::bake

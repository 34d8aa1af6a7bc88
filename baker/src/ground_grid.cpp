#include "gusuku_bake/ground_grid.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace gusuku::bake {

GroundRegion chooseGroundRegion(const Bounds3& building_bounds, double lowest_sun_elevation_deg, double cell_m,
                                int max_cells_per_side) {
    const double height = std::max(0.0, double(building_bounds.max.z - building_bounds.min.z));
    double shadow_reach = 0.0;
    if (lowest_sun_elevation_deg >= 0.0) {
        const double elevation = std::max(lowest_sun_elevation_deg, 10.0) * std::numbers::pi / 180.0;
        shadow_reach = height / std::tan(elevation);
    }
    const double margin = shadow_reach + std::max(1.0, 0.5 * height);
    GroundRegion region;
    region.origin_enu_m = {double(building_bounds.min.x) - margin, double(building_bounds.min.y) - margin};
    const double width = double(building_bounds.max.x - building_bounds.min.x) + 2.0 * margin;
    const double depth = double(building_bounds.max.y - building_bounds.min.y) + 2.0 * margin;
    region.cell_m = std::max(cell_m, std::max(width, depth) / double(max_cells_per_side));
    region.columns = std::max(1, int(std::ceil(width / region.cell_m)));
    region.rows = std::max(1, int(std::ceil(depth / region.cell_m)));
    return region;
}

Bounds3 siteReliefBounds(const TriangleMesh& site_mesh, const Bounds3& building_bounds, double search_m) {
    Bounds3 relief;
    if (building_bounds.empty()) return relief;
    const float reach = float(search_m);
    for (size_t t = 0; t + 2 < site_mesh.indices.size(); t += 3) {
        const glm::vec3 p0 = site_mesh.positions[site_mesh.indices[t]];
        const glm::vec3 p1 = site_mesh.positions[site_mesh.indices[t + 1]];
        const glm::vec3 p2 = site_mesh.positions[site_mesh.indices[t + 2]];
        const glm::vec3 normal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        if (!std::isfinite(normal.z) || std::abs(normal.z) >= 0.5f) continue;  // not steep, or degenerate
        const float low = std::min({p0.z, p1.z, p2.z}), high = std::max({p0.z, p1.z, p2.z});
        if (double(high - low) < kSiteReliefMinHeightM) continue;  // a ripple's shadow is no boundary
        const glm::vec3 centre = (p0 + p1 + p2) / 3.0f;
        if (centre.x < building_bounds.min.x - reach || centre.x > building_bounds.max.x + reach ||
            centre.y < building_bounds.min.y - reach || centre.y > building_bounds.max.y + reach)
            continue;
        for (const glm::vec3& p : {p0, p1, p2}) relief.extend(p);
    }
    return relief;
}

GroundRegion chooseSiteGroundRegion(const Bounds3& building_bounds, const TriangleMesh& site_mesh,
                                    double lowest_sun_elevation_deg, double cell_m, int max_cells_per_side) {
    const GroundRegion building =
        chooseGroundRegion(building_bounds, lowest_sun_elevation_deg, cell_m, max_cells_per_side);
    const Bounds3 relief_bounds = siteReliefBounds(site_mesh, building_bounds, kSiteReliefSearchM);
    if (relief_bounds.empty()) return building;
    // Each caster with its own reach: the relief's shadows are as long as the relief is tall, and the grid's
    // extent also sets the runtime's shadow map's (docs/bakeset.md), so the building's height does not grow it.
    const GroundRegion relief = chooseGroundRegion(relief_bounds, lowest_sun_elevation_deg, cell_m, max_cells_per_side);
    auto farCorner = [](const GroundRegion& region) {
        return region.origin_enu_m + glm::dvec2(region.columns, region.rows) * region.cell_m;
    };
    const glm::dvec2 low = glm::min(building.origin_enu_m, relief.origin_enu_m);
    const glm::dvec2 high = glm::max(farCorner(building), farCorner(relief));
    GroundRegion region;
    region.origin_enu_m = low;
    region.cell_m = std::max(cell_m, std::max(high.x - low.x, high.y - low.y) / double(max_cells_per_side));
    region.columns = std::max(1, int(std::ceil((high.x - low.x) / region.cell_m - 1e-9)));
    region.rows = std::max(1, int(std::ceil((high.y - low.y) / region.cell_m - 1e-9)));
    return region;
}

std::vector<GroundCell> sampleGround(const GroundRegion& region, const Bvh& bvh, const TriangleMesh& mesh,
                                     uint32_t skip_flags, float top_z) {
    std::vector<GroundCell> cells(region.cellCount());
    const glm::vec3 down(0.0f, 0.0f, -1.0f);
    for (int row = 0; row < region.rows; ++row)
        for (int column = 0; column < region.columns; ++column) {
            const glm::dvec2 centre = groundCellCentre(region, column, row);
            const glm::vec3 origin(float(centre.x), float(centre.y), top_z);
            const auto hit = traceClosestCpu(bvh, origin, down, 1e30f, skip_flags);
            GroundCell& cell = cells[groundCellIndex(region, {column, row})];
            if (!hit) continue;
            const uint32_t t = hit->triangle_index;
            const glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]];
            const glm::vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
            const glm::vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
            glm::vec3 normal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
            if (normal.z < 0.0f) normal = -normal;  // the ground faces the sky whichever way it was wound
            cell.valid = std::isfinite(normal.x);
            cell.height_m = top_z - hit->t;
            cell.normal = cell.valid ? normal : glm::vec3(0.0f, 0.0f, 1.0f);
        }
    return cells;
}

TriangleMesh makeFlatGround(double half_size_m, const glm::vec3& albedo) {
    TriangleMesh ground;
    const float h = float(half_size_m);
    ground.positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
    ground.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
    ground.uv0.assign(4, glm::vec2(0.0f));
    ground.indices = {0, 1, 2, 0, 2, 3};
    ground.triangle_material = {0, 0};
    Material material;
    material.name = "flat ground stand-in";
    material.base_color_factor = glm::vec4(albedo, 1.0f);
    ground.materials.push_back(material);
    return ground;
}

}  // namespace gusuku::bake

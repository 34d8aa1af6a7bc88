// Ground grid addressing and the shadow-catcher ratio (gusuku/formats/ground_grid.h). The GLSL twin in
// shaders/include/ground_ratio.glsl mirrors each function line for line; change both together.

#include "gusuku/formats/ground_grid.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace gusuku {

glm::dvec2 groundCellCentreEnu(const GroundGrid& grid, GroundCellAddress cell) {
    return {grid.origin_enu_m.x + (cell.column + 0.5) * grid.cell_m,
            grid.origin_enu_m.y + (grid.rows - cell.row - 0.5) * grid.cell_m};
}

bool groundCellInside(const GroundGrid& grid, GroundCellAddress cell) {
    return cell.column >= 0 && cell.column < grid.columns && cell.row >= 0 && cell.row < grid.rows;
}

std::optional<GroundCellAddress> groundCellAt(const GroundGrid& grid, const glm::dvec2& enu_xy) {
    if (!(grid.cell_m > 0.0)) return std::nullopt;
    // Both floors stay in double until they are known to be inside the grid: a far point must not overflow int.
    const double column = std::floor((enu_xy.x - grid.origin_enu_m.x) / grid.cell_m);
    const double cells_north_of_origin = std::floor((enu_xy.y - grid.origin_enu_m.y) / grid.cell_m);
    if (!(column >= 0.0 && column < double(grid.columns))) return std::nullopt;  // also false for NaN
    if (!(cells_north_of_origin >= 0.0 && cells_north_of_origin < double(grid.rows))) return std::nullopt;
    return GroundCellAddress{int(column), grid.rows - 1 - int(cells_north_of_origin)};
}

size_t groundCellIndex(const GroundGrid& grid, GroundCellAddress cell) {
    return size_t(cell.row) * size_t(grid.columns) + size_t(cell.column);
}

GroundCellAddress groundCellFromIndex(const GroundGrid& grid, size_t index) {
    const size_t columns = size_t(std::max(grid.columns, 1));
    return {int(index % columns), int(index / columns)};
}

glm::dvec2 groundGridUv(const GroundGrid& grid, const glm::dvec2& enu_xy) {
    return {(enu_xy.x - grid.origin_enu_m.x) / (grid.columns * grid.cell_m),
            (grid.origin_enu_m.y + grid.rows * grid.cell_m - enu_xy.y) / (grid.rows * grid.cell_m)};
}

glm::vec3 groundSunIrradiance(const glm::vec3& sun_irradiance_rgb, const glm::vec3& normal_enu,
                              const glm::vec3& sun_direction_enu, float scene_visibility) {
    const float cosine = std::max(0.0f, glm::dot(normal_enu, sun_direction_enu));
    return sun_irradiance_rgb * (scene_visibility * cosine);
}

glm::vec3 groundShadowRatio(const glm::vec3& e_with, const glm::vec3& e_without, const glm::vec3& e_sun,
                            float building_visibility) {
    glm::vec3 ratio(1.0f);
    for (int c = 0; c < 3; ++c) {
        const float denominator = e_without[c] + e_sun[c];
        if (denominator > 0.0f) ratio[c] = (e_with[c] + building_visibility * e_sun[c]) / denominator;
    }
    return ratio;
}

}  // namespace gusuku

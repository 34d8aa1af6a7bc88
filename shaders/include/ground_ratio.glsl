// Ground grid addressing and the shadow-catcher ratio: the GLSL twin of engine/include/gusuku/formats/ground_grid.h,
// same names, same expressions in the same order, float32. The contracts (frame, units, image convention, the
// guards) are documented there; tests/test_ground_ratio.cpp holds this file to the C++ through
// shaders/tests/ground_ratio_probe.comp.
//
// Grid: column 0 west, row 0 NORTH; cell (column, row) has its centre at
//   x = origin_x + (column + 0.5) cell_m,   y = origin_y + (rows - row - 0.5) cell_m   (ENU metres);
// texel index = row * columns + column.
// Ratio: (E_with + V_bld E_sun) / (E_without + E_sun) per channel, E_sun = V_scene I_sun max(0, n . s); a channel
// whose denominator is not > 0 gets 1.
#ifndef GUSUKU_GROUND_RATIO_GLSL
#define GUSUKU_GROUND_RATIO_GLSL

struct GroundGrid {
    vec2 origin_enu_m;  // south-west corner of the grid
    float cell_m;       // > 0
    int columns;        // west to east
    int rows;           // north to south
};

vec2 groundCellCentreEnu(GroundGrid grid, ivec2 cell) {  // cell = (column, row)
    return vec2(grid.origin_enu_m.x + (float(cell.x) + 0.5) * grid.cell_m,
                grid.origin_enu_m.y + (float(grid.rows - cell.y) - 0.5) * grid.cell_m);
}

bool groundCellInside(GroundGrid grid, ivec2 cell) {
    return cell.x >= 0 && cell.x < grid.columns && cell.y >= 0 && cell.y < grid.rows;
}

// The cell holding ENU (x, y); false (and cell = (-1, -1)) outside the grid or for a non-finite point.
bool groundCellAt(GroundGrid grid, vec2 enu_xy, out ivec2 cell) {
    cell = ivec2(-1);
    if (!(grid.cell_m > 0.0)) return false;
    float column = floor((enu_xy.x - grid.origin_enu_m.x) / grid.cell_m);
    float cells_north_of_origin = floor((enu_xy.y - grid.origin_enu_m.y) / grid.cell_m);
    if (!(column >= 0.0 && column < float(grid.columns))) return false;
    if (!(cells_north_of_origin >= 0.0 && cells_north_of_origin < float(grid.rows))) return false;
    cell = ivec2(int(column), grid.rows - 1 - int(cells_north_of_origin));
    return true;
}

int groundCellIndex(GroundGrid grid, ivec2 cell) { return cell.y * grid.columns + cell.x; }

ivec2 groundCellFromIndex(GroundGrid grid, int index) {
    int columns = max(grid.columns, 1);
    return ivec2(index % columns, index / columns);
}

// Texture coordinates in the ground images (Vulkan: texel centres at (i + 0.5) / size).
vec2 groundGridUv(GroundGrid grid, vec2 enu_xy) {
    return vec2((enu_xy.x - grid.origin_enu_m.x) / (float(grid.columns) * grid.cell_m),
                (grid.origin_enu_m.y + float(grid.rows) * grid.cell_m - enu_xy.y) / (float(grid.rows) * grid.cell_m));
}

vec3 groundSunIrradiance(vec3 sun_irradiance_rgb, vec3 normal_enu, vec3 sun_direction_enu, float scene_visibility) {
    float cosine = max(0.0, dot(normal_enu, sun_direction_enu));
    return sun_irradiance_rgb * (scene_visibility * cosine);
}

vec3 groundShadowRatio(vec3 e_with, vec3 e_without, vec3 e_sun, float building_visibility) {
    vec3 ratio = vec3(1.0);
    for (int c = 0; c < 3; ++c) {
        float denominator = e_without[c] + e_sun[c];
        if (denominator > 0.0) ratio[c] = (e_with[c] + building_visibility * e_sun[c]) / denominator;
    }
    return ratio;
}

#endif  // GUSUKU_GROUND_RATIO_GLSL

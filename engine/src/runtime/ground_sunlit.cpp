// Cells whose ratio stays at exactly 1 in this frame's light (see ground_sunlit.h).

#include "ground_sunlit.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

namespace gusuku::runtime_detail {
namespace {

constexpr float kNoHeight = -1e30f;
// The shader computes the ratio in float from half floats times a scale, interpolated: the CPU's check uses a
// threshold this much smaller (relative) than the shader's, far more than float's rounding of a few operations.
constexpr double kThresholdMargin = 2e-3;
// A sun closer to the zenith than this horizontal part is treated as straight overhead (no march direction).
constexpr double kOverheadHorizontal = 1e-9;

// The cell's column and row bounds [low, high] an interval of x (or y) overlaps, clamped to the grid.
void cellRange(double low_m, double high_m, double origin_m, double cell_m, int count, int& first, int& last) {
    first = std::max(0, int(std::floor((low_m - origin_m) / cell_m)));
    last = std::min(count - 1, int(std::floor((high_m - origin_m) / cell_m)));
}

// Float rounding of the tiles' heights (metres): a tile is stored this much higher.
constexpr float kTileRounding = 1e-4f;

// Whether some point Q of a tile's column (no higher than rise_m above the ground point P, P's horizontal offset
// to Q along u in [along_low, along_high] and across it at least `across`) can shade P: within the tap's reach
// of P's ray and nearer the sun by more than the bias. In the vertical plane of u, Q - P = t s + beta w with
// w = (-sun_z u + horizontal z) (unit, across the ray): beta = rise h - along sun_z, t = along h + rise sun_z.
// |beta| within the reach left after `across` bounds the rise from above, (beta >= -reach) the along from
// above; t grows with both, so its largest value is at the largest feasible along and rise.
bool tileMayShade(double along_low, double along_high, double across, double rise_m, double horizontal,
                  double sun_z, double tap_reach_m, double bias_m) {
    const double reach = std::sqrt(std::max(0.0, tap_reach_m * tap_reach_m - across * across));
    // beta >= -reach: along sun_z <= rise h + reach.
    const double along_limit = (rise_m * horizontal + reach) / sun_z;
    const double along = std::min(along_high, along_limit);
    if (along < along_low) return false;
    // beta <= reach: rise <= (reach + along sun_z) / h.
    const double rise = horizontal > kOverheadHorizontal ? std::min(rise_m, (reach + along * sun_z) / horizontal)
                                                         : rise_m;
    return along * horizontal + rise * sun_z > bias_m;
}

// runtime_shadow_coordinates.glsl's clamp of the cosine and cap of the tangent.
constexpr double kShadowMinCosine = 0.05;
constexpr double kShadowMaxBiasTangent = 10.0;

}  // namespace

SiteHeightTiles siteHeightTiles(const GroundGrid& grid, std::span<const glm::vec3> positions,
                                std::span<const uint32_t> indices) {
    SiteHeightTiles tiles;
    tiles.columns = std::max(grid.columns, 0) * kSiteTilesPerCell;
    tiles.rows = std::max(grid.rows, 0) * kSiteTilesPerCell;
    tiles.tile_m = grid.cell_m / kSiteTilesPerCell;
    tiles.max_z.assign(size_t(tiles.columns) * size_t(tiles.rows), kNoHeight);
    const double west = grid.origin_enu_m.x, south = grid.origin_enu_m.y, tile_m = tiles.tile_m;
    const double east_end = west + tiles.columns * tile_m, north_end = south + tiles.rows * tile_m;
    for (size_t first = 0; first + 2 < indices.size(); first += 3) {
        if (indices[first] >= positions.size() || indices[first + 1] >= positions.size() ||
            indices[first + 2] >= positions.size())
            continue;
        const glm::dvec3 a(positions[indices[first]]), b(positions[indices[first + 1]]), c(positions[indices[first + 2]]);
        const glm::dvec3 low = glm::min(a, glm::min(b, c)), high = glm::max(a, glm::max(b, c));
        if (!std::isfinite(low.x + low.y + low.z + high.x + high.y + high.z)) continue;
        const float top = float(high.z);
        tiles.top_z = std::max(tiles.top_z, top);
        // Any part beyond the grid counts towards outside_max_z (a ray leaving the grid must clear it).
        if (low.x < west || high.x > east_end || low.y < south || high.y > north_end)
            tiles.outside_max_z = std::max(tiles.outside_max_z, top);
        // The triangle's plane z = z0 + gx (x - a.x) + gy (y - a.y), where it is not vertical: its highest point over a
        // square is at one of the square's corners (and never above the triangle's top).
        const glm::dvec3 normal = glm::cross(b - a, c - a);
        const bool planar = std::abs(normal.z) > 1e-9 * glm::length(normal);
        const double gx = planar ? -normal.x / normal.z : 0.0, gy = planar ? -normal.y / normal.z : 0.0;
        int column_low, column_high, row_low, row_high;
        cellRange(low.x, high.x, west, tile_m, tiles.columns, column_low, column_high);
        cellRange(low.y, high.y, south, tile_m, tiles.rows, row_low, row_high);
        for (int tile_row = row_low; tile_row <= row_high; ++tile_row)
            for (int column = column_low; column <= column_high; ++column) {
                double z = high.z;
                if (planar) {
                    const double x0 = west + column * tile_m - a.x, y0 = south + tile_row * tile_m - a.y;
                    const double corner_max = a.z + std::max(gx * x0, gx * (x0 + tile_m)) +
                                              std::max(gy * y0, gy * (y0 + tile_m));
                    z = std::min(z, corner_max);
                }
                float& tile = tiles.max_z[size_t(tile_row) * size_t(tiles.columns) + size_t(column)];
                tile = std::max(tile, float(z) + kTileRounding);
            }
    }
    return tiles;
}

double siteShadowBiasM(const SiteShadowTest& test, const glm::dvec3& normal, const glm::dvec3& shadow_sun) {
    const double cosine = std::clamp(glm::dot(normal, shadow_sun), kShadowMinCosine, 1.0);
    const double tangent = std::sqrt(std::max(0.0, 1.0 - cosine * cosine)) / cosine;
    return kSiteBiasFraction * test.bias_texels * test.texel_m * (1.0 + std::min(tangent, kShadowMaxBiasTangent));
}

bool groundCellSurelySunlit(const GroundCells& cells, const SiteHeightTiles& tiles, size_t column, size_t row,
                            const glm::dvec3& shadow_sun, const SiteShadowTest& test) {
    const GroundGrid& grid = cells.grid;
    const int columns = grid.columns, rows = grid.rows;
    if (!(shadow_sun.z > 0.0) || tiles.max_z.size() != size_t(tiles.columns) * size_t(tiles.rows) ||
        tiles.columns != columns * kSiteTilesPerCell || tiles.rows != rows * kSiteTilesPerCell)
        return false;
    // The lowest ground of the cell's quads, and the smallest bias of their corners (a fragment's depth and bias
    // are interpolated between its quad's corners, all among the cell and its neighbours).
    const size_t own = row * size_t(columns) + column;
    double base_z = cells.height[own];
    const bool normals = cells.normal.size() == cells.state.size();
    double bias_m = normals ? siteShadowBiasM(test, glm::dvec3(cells.normal[own]), shadow_sun) : 0.0;
    for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
            const int r = int(row) + dr, c = int(column) + dc;
            if (r < 0 || c < 0 || r >= rows || c >= columns) continue;
            const size_t neighbour = size_t(r) * size_t(columns) + size_t(c);
            if (cells.state[neighbour] == kCellNoGround) continue;
            base_z = std::min(base_z, double(cells.height[neighbour]));
            if (normals)
                bias_m = std::min(bias_m, siteShadowBiasM(test, glm::dvec3(cells.normal[neighbour]), shadow_sun));
        }
    const double tap_reach_m = kSiteTapReachTexels * test.texel_m;
    const double top_z = std::max(double(tiles.top_z), double(tiles.outside_max_z));
    if (top_z + tap_reach_m <= base_z) return true;  // nothing of the site rises above the ground here
    const double horizontal = std::hypot(shadow_sun.x, shadow_sun.y);
    const double sun_z = shadow_sun.z;
    const double east = horizontal > kOverheadHorizontal ? shadow_sun.x / horizontal : 1.0;
    const double north = horizontal > kOverheadHorizontal ? shadow_sun.y / horizontal : 0.0;
    const glm::dvec3 centre = groundCellCentre(grid, column, row, base_z);
    const double tile_m = tiles.tile_m;
    // Half extents, along the ray's horizontal direction u and across it, of the fragments' square (one cell) and
    // of a tile's square.
    const double spread = std::abs(east) + std::abs(north);
    const double fragment_half = 0.5 * grid.cell_m * spread, tile_half = 0.5 * tile_m * spread;
    const double slack = fragment_half + tile_half;
    // Beyond this along u no point of the tube around the ray is below the site's top.
    const double rise = horizontal > kOverheadHorizontal ? sun_z / horizontal : 1e30;
    const double march_end_m = std::min((top_z - base_z) / rise + tap_reach_m / sun_z + slack, 1e6);
    const int across_tiles = int(std::ceil((tap_reach_m + slack) / tile_m)) + 1;
    const double grid_west = grid.origin_enu_m.x, grid_south = grid.origin_enu_m.y;
    for (double along_m = -slack; along_m <= march_end_m + tile_m; along_m += tile_m) {
        const double x = centre.x + east * along_m, y = centre.y + north * along_m;
        const int at_column = int(std::floor((x - grid_west) / tile_m));
        const int at_row = int(std::floor((y - grid_south) / tile_m));
        if (at_column < -across_tiles || at_row < -across_tiles || at_column >= tiles.columns + across_tiles ||
            at_row >= tiles.rows + across_tiles) {
            // Left the grid: what stands beyond it is known only by its top, which the ray must clear.
            return double(tiles.outside_max_z) + tap_reach_m / horizontal <
                   base_z + std::max(0.0, along_m - slack) * rise;
        }
        for (int tile_row = at_row - across_tiles; tile_row <= at_row + across_tiles; ++tile_row)
            for (int c = at_column - across_tiles; c <= at_column + across_tiles; ++c) {
                if (tile_row < 0 || c < 0 || tile_row >= tiles.rows || c >= tiles.columns) continue;
                const float tile_z = tiles.max_z[size_t(tile_row) * size_t(tiles.columns) + size_t(c)];
                if (tile_z == kNoHeight) continue;
                const double dx = grid_west + (c + 0.5) * tile_m - centre.x;
                const double dy = grid_south + (tile_row + 0.5) * tile_m - centre.y;
                const double across = std::max(0.0, std::abs(dx * north - dy * east) - slack);
                if (across > tap_reach_m) continue;
                const double along_centre = dx * east + dy * north;
                const double along_low = along_centre - slack, along_high = along_centre + slack;
                if (tileMayShade(along_low, along_high, across, double(tile_z) - base_z, horizontal, sun_z, tap_reach_m, bias_m))
                    return false;
            }
    }
    return true;
}

std::vector<float> groundSlotLight(std::span<const std::span<const float>> with_rgba,
                                   std::span<const std::span<const float>> without_rgba, float inverse_scale) {
    const size_t slots = std::min(with_rgba.size(), without_rgba.size());
    const size_t cells = slots > 0 ? with_rgba[0].size() / 4 : 0;
    std::vector<float> light(slots * cells * 6, 0.0f);
    const float scale = 1.0f / inverse_scale;
    // As the GPU reads it: the half float the runtime stores, times the scale (runtime_scene.cpp's toHalf).
    auto asRead = [&](float value) { return glm::unpackHalf1x16(glm::packHalf1x16(value * inverse_scale)) * scale; };
    for (size_t slot = 0; slot < slots; ++slot)
        for (size_t cell = 0; cell < cells && cell * 4 + 3 < without_rgba[slot].size(); ++cell)
            for (int channel = 0; channel < 3; ++channel) {
                float* out = &light[(slot * cells + cell) * 6];
                out[channel] = asRead(with_rgba[slot][cell * 4 + size_t(channel)]);
                out[3 + channel] = asRead(without_rgba[slot][cell * 4 + size_t(channel)]);
            }
    return light;
}

void markPassThroughCells(const GroundCells& cells, std::span<const float> slot_light, const SiteHeightTiles& tiles,
                          const PassThroughLight& light, std::span<uint8_t> pass_through) {
    std::fill(pass_through.begin(), pass_through.end(), uint8_t(0));
    const size_t columns = size_t(std::max(cells.grid.columns, 0)), rows = size_t(std::max(cells.grid.rows, 0));
    const size_t cell_count = columns * rows;
    if (cell_count == 0 || pass_through.size() != cell_count || cells.state.size() != cell_count) return;
    const size_t slot_count = slot_light.size() / (cell_count * 6);
    float weight_sum = 0.0f;
    for (int blend = 0; blend < 3; ++blend) {
        if (light.slots[blend] < 0 || !(light.weights[blend] > 0.0f)) continue;
        if (size_t(light.slots[blend]) >= slot_count || !(light.weights[blend] >= 0.0f)) return;
        weight_sum += light.weights[blend];
    }
    // The blend of the slots' checks holds only for weights that sum to at most 1 (E_sun is not weighted).
    if (!(weight_sum <= 1.0f + 1e-6f)) return;
    const double threshold = double(light.pass_through_threshold) * (1.0 - kThresholdMargin);
    const bool sun = light.sun_shines && light.shadow_sun.z > 0.0;
    for (size_t row = 0; row < rows; ++row)
        for (size_t column = 0; column < columns; ++column) {
            const size_t cell = row * columns + column;
            if (cells.state[cell] != kCellGroundChangedByBuilding) continue;
            glm::dvec3 sun_floor(0.0);
            // The sun counts only where the site surely leaves it unshadowed; its cosine from the cell's normal is
            // the GPU's, less the slack between the rounded sun and the frame's.
            if (sun && !cells.normal.empty()) {
                const double cosine = glm::dot(glm::dvec3(cells.normal[cell]), light.shadow_sun) - light.cosine_slack;
                if (cosine > 0.0 &&
                    groundCellSurelySunlit(cells, tiles, column, row, light.shadow_sun, light.site_shadow))
                    sun_floor = light.sun_irradiance_floor * cosine;
            }
            bool holds = true;
            for (int blend = 0; blend < 3 && holds; ++blend) {
                if (light.slots[blend] < 0 || !(light.weights[blend] > 0.0f)) continue;
                const float* values = &slot_light[(size_t(light.slots[blend]) * cell_count + cell) * 6];
                for (int channel = 0; channel < 3 && holds; ++channel) {
                    const double with = values[channel], without = values[3 + channel];
                    holds = std::abs(with - without) < threshold * (without + sun_floor[channel]);
                }
            }
            pass_through[cell] = holds ? 1 : 0;
        }
}

}  // namespace gusuku::runtime_detail

// Choosing the ground quads a frame draws (see ground_quads.h).

#include "ground_quads.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gusuku::runtime_detail {
namespace {

// A direction component smaller than this counts as parallel to that axis's slabs (no division by it).
constexpr double kParallelComponent = 1e-12;
// The ray's far end before any slab clips it: beyond any scene.
constexpr double kUnboundedRayT = 1e30;

// Marks the cells (see selectGroundQuads) and returns nothing: marked and shadow_candidate are filled.
void markCells(const GroundCells& cells, const glm::dvec3& low, const glm::dvec3& high, bool include_baked_changes,
               bool sun_shines, const glm::dvec3& sun_direction, std::span<uint8_t> marked,
               std::span<float> shadow_candidate, std::span<const uint8_t> pass_through) {
    const size_t columns = size_t(std::max(cells.grid.columns, 0)), rows = size_t(std::max(cells.grid.rows, 0));
    for (size_t row = 0; row < rows; ++row)
        for (size_t column = 0; column < columns; ++column) {
            const size_t cell = row * columns + column;
            const uint8_t state = cells.state[cell];
            const bool baked_change = include_baked_changes && state == kCellGroundChangedByBuilding &&
                                      !(pass_through.size() == cells.state.size() && pass_through[cell] != 0);
            bool candidate = false;
            if (state != kCellNoGround && sun_shines) {
                const glm::dvec3 origin = groundCellCentre(cells.grid, column, row, double(cells.height[cell]));
                candidate = rayMeetsBox(origin, sun_direction, low, high);
            }
            marked[cell] = (baked_change || candidate) ? 1 : 0;
            shadow_candidate[cell] = candidate ? 1.0f : 0.0f;
        }
}

}  // namespace

double groundShadowMarginM(double cell_m) { return kShadowReachMarginCells * cell_m + kShadowReachMarginM; }

glm::dvec3 groundCellCentre(const GroundGrid& grid, size_t column, size_t row, double height_m) {
    const size_t rows = size_t(std::max(grid.rows, 0));
    return glm::dvec3(grid.origin_enu_m.x + (double(column) + 0.5) * grid.cell_m,
                      grid.origin_enu_m.y + (double(rows - row) - 0.5) * grid.cell_m, height_m);
}

bool rayMeetsBox(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& low,
                 const glm::dvec3& high) {
    double near_t = 0.0, far_t = kUnboundedRayT;
    for (int axis = 0; axis < 3 && near_t <= far_t; ++axis) {
        if (std::abs(direction[axis]) < kParallelComponent) {
            if (origin[axis] < low[axis] || origin[axis] > high[axis]) far_t = -1.0;
            continue;
        }
        double t0 = (low[axis] - origin[axis]) / direction[axis];
        double t1 = (high[axis] - origin[axis]) / direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        near_t = std::max(near_t, t0);
        far_t = std::min(far_t, t1);
    }
    return near_t <= far_t;
}

GroundQuadSelection selectGroundQuads(const GroundCells& cells, const glm::dvec3& building_min,
                                      const glm::dvec3& building_max, bool include_baked_changes, bool sun_shines,
                                      const glm::dvec3& sun_direction, std::span<uint8_t> marked,
                                      std::span<float> shadow_candidate, std::span<uint32_t> quad_indices,
                                      std::span<const uint8_t> pass_through) {
    const GroundGrid& grid = cells.grid;
    const size_t columns = size_t(std::max(grid.columns, 0)), rows = size_t(std::max(grid.rows, 0));
    if (quad_indices.empty() || cells.state.size() != columns * rows) return {};
    const double margin = groundShadowMarginM(grid.cell_m);
    markCells(cells, building_min - margin, building_max + margin, include_baked_changes, sun_shines, sun_direction,
              marked, shadow_candidate, pass_through);
    // Quads the shadow may reach first (drawn with the shadow-reading shader), then the rest. Of a quad, only the
    // triangles with a marked corner: a triangle whose three corners are all unmarked interpolates only values the
    // frame leaves alone (no shadow candidate, no baked change or one proved within the skip threshold), as an
    // undrawn quad does, so it is left to the camera too. The triangles drawn are the quad's own (a c b, b c d),
    // so what they write does not change.
    GroundQuadSelection selection;
    uint32_t written = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t row = 0; row + 1 < rows; ++row)
            for (size_t column = 0; column + 1 < columns; ++column) {
                const uint32_t a = uint32_t(row * columns + column), b = a + 1, c = a + uint32_t(columns), d = c + 1;
                const bool first = marked[a] | marked[c] | marked[b], second = marked[b] | marked[c] | marked[d];
                if (!first && !second) continue;
                const bool shadow =
                    shadow_candidate[a] + shadow_candidate[b] + shadow_candidate[c] + shadow_candidate[d] > 0.0f;
                if (shadow != (pass == 0)) continue;
                uint32_t* triangle = &quad_indices[written];
                if (first) triangle[0] = a, triangle[1] = c, triangle[2] = b, triangle += 3, written += 3;
                if (second) triangle[0] = b, triangle[1] = c, triangle[2] = d, written += 3;
                ++selection.quads;
            }
        if (pass == 0) selection.shadow_index_count = written;
    }
    selection.index_count = written;
    return selection;
}

}  // namespace gusuku::runtime_detail

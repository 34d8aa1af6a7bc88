#include "ground_covered_cells.h"

#include <cmath>

#include "gusuku_bake/bvh.h"
#include "gusuku_bake/ground_grid.h"

namespace gusuku::bake {

namespace {

constexpr float kRayOffsetM = 1e-3f;  // as the tracer's (TracePass::ray_offset_m)

}  // namespace

std::vector<uint8_t> coveredGroundCells(const BakeGeometry& geometry) {
    const GroundRegion& region = geometry.ground_region;
    std::vector<uint8_t> covered(geometry.ground_cells.size(), 0);
    const glm::vec3 up(0.0f, 0.0f, 1.0f);
    for (int row = 0; row < region.rows; ++row)
        for (int column = 0; column < region.columns; ++column) {
            const size_t index = size_t(row) * size_t(region.columns) + size_t(column);
            const GroundCell& cell = geometry.ground_cells[index];
            if (!cell.valid) continue;
            const glm::dvec2 centre = groundCellCentre(region, column, row);
            const glm::vec3 origin(float(centre.x), float(centre.y), cell.height_m + kRayOffsetM);
            const auto hit = traceClosestCpu(geometry.cpuBvh(), origin, up, kCoveredGapM);
            covered[index] = hit && hit->triangle_index < geometry.scene.building_triangle_count;
        }
    return covered;
}

std::vector<glm::vec4> withCoveredCellsFilled(const BakeGeometry& geometry, const std::vector<uint8_t>& covered,
                                              const std::vector<glm::vec4>& with_sums,
                                              const std::vector<glm::vec4>& without_sums) {
    const GroundRegion& region = geometry.ground_region;
    const size_t cells = geometry.ground_cells.size();
    // The traced point of each cell with ground (-1: none).
    std::vector<long> point_of(cells, -1);
    long points = 0;
    for (size_t i = 0; i < cells; ++i)
        if (geometry.ground_cells[i].valid) point_of[i] = points++;
    std::vector<glm::vec4> filled = with_sums;
    if (size_t(points) != with_sums.size() || with_sums.size() != without_sums.size()) return filled;
    // Per cell, the ratio it offers its covered neighbours; known once the cell is open or filled.
    std::vector<glm::dvec3> ratio(cells, glm::dvec3(1.0));
    std::vector<uint8_t> known(cells, 0);
    auto ratioOf = [](const glm::vec4& with, const glm::vec4& without) {
        glm::dvec3 r(1.0);
        for (int c = 0; c < 3; ++c) r[c] = without[c] > 0.0f ? double(with[c]) / double(without[c]) : 1.0;
        return r;
    };
    for (size_t i = 0; i < cells; ++i)
        if (point_of[i] >= 0 && !covered[i]) {
            ratio[i] = ratioOf(with_sums[size_t(point_of[i])], without_sums[size_t(point_of[i])]);
            known[i] = 1;
        }
    // Ring by ring: a covered cell takes the mean ratio of its known 8 neighbours from the rings before its own.
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<uint8_t> next_known = known;
        for (int row = 0; row < region.rows; ++row)
            for (int column = 0; column < region.columns; ++column) {
                const size_t i = size_t(row) * size_t(region.columns) + size_t(column);
                if (known[i] || point_of[i] < 0) continue;
                glm::dvec3 sum(0.0);
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int r = row + dy, c = column + dx;
                        if ((dx == 0 && dy == 0) || r < 0 || c < 0 || r >= region.rows || c >= region.columns) continue;
                        const size_t n = size_t(r) * size_t(region.columns) + size_t(c);
                        if (!known[n]) continue;
                        sum += ratio[n];
                        ++count;
                    }
                if (count == 0) continue;
                ratio[i] = sum / double(count);
                next_known[i] = 1;
                const size_t p = size_t(point_of[i]);
                for (int ch = 0; ch < 3; ++ch) filled[p][ch] = float(double(without_sums[p][ch]) * ratio[i][ch]);
                changed = true;
            }
        known.swap(next_known);
    }
    return filled;
}

}  // namespace gusuku::bake

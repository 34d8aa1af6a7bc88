// Packing lightmap charts into the square lightmap, and choosing the lightmap's size from the surface area.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_pack.h"

namespace gusuku::bake {
namespace detail {
namespace {

struct ShelfResult {
    int total_height = 0;  // texels the shelves would need (may exceed the resolution)
    bool fits = false;
    std::vector<ChartPlacement> placements;
};

ShelfResult shelfPack(const std::vector<glm::dvec2>& extents_m, double texels_per_metre, int resolution,
                      int padding) {
    ShelfResult result;
    result.placements.resize(extents_m.size());
    for (size_t chart = 0; chart < extents_m.size(); ++chart) {
        glm::ivec2 inner = innerTexelSize(extents_m[chart], texels_per_metre);
        ChartPlacement& placement = result.placements[chart];
        placement.rotated = inner.y > inner.x;
        if (placement.rotated) std::swap(inner.x, inner.y);
        placement.inner_width = inner.x;
        placement.inner_height = inner.y;
    }
    std::vector<size_t> order(extents_m.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const ChartPlacement& pa = result.placements[a];
        const ChartPlacement& pb = result.placements[b];
        if (pa.inner_height != pb.inner_height) return pa.inner_height > pb.inner_height;
        if (pa.inner_width != pb.inner_width) return pa.inner_width > pb.inner_width;
        return a < b;
    });
    result.fits = true;
    int shelf_y = 0, shelf_height = 0, cursor_x = 0;
    for (size_t chart : order) {
        ChartPlacement& placement = result.placements[chart];
        const int outer_width = placement.inner_width + 2 * padding;
        const int outer_height = placement.inner_height + 2 * padding;
        if (outer_width > resolution) result.fits = false;
        if (cursor_x + outer_width > resolution && cursor_x > 0) {
            shelf_y += shelf_height;
            shelf_height = 0;
            cursor_x = 0;
        }
        placement.x = cursor_x + padding;
        placement.y = shelf_y + padding;
        cursor_x += outer_width;
        shelf_height = std::max(shelf_height, outer_height);
    }
    result.total_height = shelf_y + shelf_height;
    if (result.total_height > resolution) result.fits = false;
    return result;
}

}  // namespace

glm::ivec2 innerTexelSize(const glm::dvec2& extent_m, double texels_per_metre) {
    return glm::ivec2(int(std::floor(extent_m.x * texels_per_metre)) + 1,
                      int(std::floor(extent_m.y * texels_per_metre)) + 1);
}

ChartPacking packChartRectangles(const std::vector<glm::dvec2>& extents_m, double texels_per_metre, int resolution,
                                 int padding) {
    ChartPacking packing;
    ShelfResult attempt = shelfPack(extents_m, texels_per_metre, resolution, padding);
    if (attempt.fits) {
        packing.texels_per_metre = texels_per_metre;
        packing.placements = std::move(attempt.placements);
        return packing;
    }
    if (!shelfPack(extents_m, 0.0, resolution, padding).fits)
        throw InputError("lightmap", "resolution",
                         std::to_string(extents_m.size()) + " charts with " + std::to_string(padding) +
                             " texels of padding do not fit in " + std::to_string(resolution) + "^2 texels even at " +
                             "one texel each; raise the lightmap resolution");

    // Bracket the largest density that fits, then bisect it.
    double failing_density = texels_per_metre;
    double fitting_density = texels_per_metre;
    ShelfResult fitting;
    for (;;) {
        const double shrink = std::clamp(std::sqrt(double(resolution) / double(attempt.total_height)), 0.3, 0.95);
        fitting_density *= shrink;
        attempt = shelfPack(extents_m, fitting_density, resolution, padding);
        if (attempt.fits) break;
        failing_density = fitting_density;
    }
    fitting = std::move(attempt);
    for (int step = 0; step < 12; ++step) {
        const double middle = 0.5 * (fitting_density + failing_density);
        ShelfResult trial = shelfPack(extents_m, middle, resolution, padding);
        if (trial.fits) {
            fitting_density = middle;
            fitting = std::move(trial);
        } else {
            failing_density = middle;
        }
    }
    packing.texels_per_metre = fitting_density;
    packing.placements = std::move(fitting.placements);
    return packing;
}

}  // namespace detail

int chooseLightmapResolution(const TriangleMesh& mesh, double texels_per_metre, int max_resolution) {
    if (!(texels_per_metre > 0.0) || !std::isfinite(texels_per_metre))
        throw InputError("lightmap", "texels_per_metre",
                         "must be finite and positive, got " + std::to_string(texels_per_metre));
    if (max_resolution < 4)
        throw InputError("lightmap", "max_resolution", "must be at least 4, got " + std::to_string(max_resolution));
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
    double area_m2 = 0.0;
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        const glm::dvec3 p0(mesh.positions[mesh.indices[triangle * 3 + 0]]);
        const glm::dvec3 p1(mesh.positions[mesh.indices[triangle * 3 + 1]]);
        const glm::dvec3 p2(mesh.positions[mesh.indices[triangle * 3 + 2]]);
        const double double_area = glm::length(glm::cross(p1 - p0, p2 - p0));
        if (std::isfinite(double_area)) area_m2 += 0.5 * double_area;
    }
    const double side = std::ceil(std::sqrt(area_m2 * texels_per_metre * texels_per_metre * kLightmapPackingOverhead));
    const int capped_maximum = max_resolution / 4 * 4;
    if (!(side < double(capped_maximum))) return capped_maximum;
    const int rounded_up = (int(side) + 3) / 4 * 4;
    return std::clamp(rounded_up, 4, capped_maximum);
}

}  // namespace gusuku::bake

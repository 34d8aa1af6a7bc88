#pragma once
// Private to the lightmap code: packing charts into the square lightmap by the shape of the texels they touch.

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>

namespace gusuku::bake::detail {

/// A chart as the packer sees it: a rectangle of texels, and which of them the chart needs for itself. The
/// charting code gives each chart's bilinear read set (lightmap_chart_frames.cpp, phase 7): the packer keeps these
/// sets, grown by the padding, apart.
struct ChartShape {
    glm::ivec2 inner{1, 1};         ///< texels, as charted (before any turn)
    std::vector<uint8_t> occupied;  ///< inner.x * inner.y, row-major: 1 where the chart needs the texel
};

/// Where one chart went. Its shape's rectangle is [x, x + inner_width] x [y, y + inner_height] (texels, after the
/// turn); `padding` texels no other chart occupies surround its occupied texels inside the lightmap.
struct ChartPlacement {
    int x = 0;
    int y = 0;
    int inner_width = 0;   ///< after the turn
    int inner_height = 0;  ///< after the turn
    int quarter_turns = 0;  ///< 0-3 counter-clockwise quarter turns (rotations, never mirrors) of the chart
};

/// Texel coordinates of a point at `local` (texels, in the unturned inner rectangle of size `inner`) once the
/// chart is placed.
glm::dvec2 placedTexel(const ChartPlacement& placement, const glm::ivec2& inner, const glm::dvec2& local);

struct ChartPacking {
    double texels_per_metre = 0.0;  ///< the density that fitted: the requested one, or the largest lower one found
    std::vector<ChartPlacement> placements;  ///< one per chart, in input order
};

/// The texels a chart of `extent_m` needs at `texels_per_metre`: floor(extent * density) + 1 per side, so the
/// chart's far edge never lands on a texel boundary and even a point-sized chart gets one texel.
glm::ivec2 innerTexelSize(const glm::dvec2& extent_m, double texels_per_metre);

/// The charts' shapes at a density (the charting code rasterises them).
using ChartShapesAt = std::function<std::vector<ChartShape>(double texels_per_metre)>;

/// Packs the charts at `texels_per_metre` (lightmap_pack.cpp: a skyline of column heights, each chart dropped
/// where it ends lowest, any of four turns, or a small chart into the lowest hole left under a bigger one, its
/// occupied texels grown by `padding` never meeting another's occupied texels grown by `padding`), lowering
/// the density (bisection, 12 steps after a bracket is found) until everything fits in resolution^2. Throws
/// InputError when even the smallest footprints (2 + 2 * padding texels square) do not fit.
ChartPacking packChartShapes(const ChartShapesAt& shapes_at, double texels_per_metre, int resolution, int padding);

/// A side (a multiple of 4, at most max_resolution rounded down to 4) within 1.6 % of the smallest whose square
/// holds `shapes` with packChartShapes' packer; max_resolution (rounded) when even that does not.
int smallestFittingResolution(const std::vector<ChartShape>& shapes, int max_resolution, int padding);

}  // namespace gusuku::bake::detail

#pragma once
// Private to the lightmap code: packing chart rectangles into the square lightmap.

#include <vector>

#include <glm/vec2.hpp>

namespace gusuku::bake::detail {

/// Where one chart went. Its triangles live in the inner rectangle [x, x + inner_width] x [y, y + inner_height]
/// (texels); `padding` empty texels surround it on every side, inside the lightmap.
struct ChartPlacement {
    int x = 0;
    int y = 0;
    int inner_width = 0;   ///< after rotation
    int inner_height = 0;  ///< after rotation
    bool rotated = false;  ///< turned 90 degrees so the rectangle lies wide (packs better on shelves)
};

struct ChartPacking {
    double texels_per_metre = 0.0;  ///< the density that fitted: the requested one, or the largest lower one found
    std::vector<ChartPlacement> placements;  ///< one per chart, in input order
};

/// The texels a chart of `extent_m` needs at `texels_per_metre`: floor(extent * density) + 1 per side, so the
/// chart's far edge never lands on a texel boundary and even a point-sized chart gets one texel.
glm::ivec2 innerTexelSize(const glm::dvec2& extent_m, double texels_per_metre);

/// Shelf-packs the charts (tallest first) at `texels_per_metre`, lowering it (bisection on the density, 12
/// steps after a bracket is found) until everything fits in resolution^2. Throws InputError when even the
/// smallest footprints (1 + 2 * padding texels square) do not fit.
ChartPacking packChartRectangles(const std::vector<glm::dvec2>& extents_m, double texels_per_metre, int resolution,
                                 int padding);

}  // namespace gusuku::bake::detail

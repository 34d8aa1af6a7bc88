// dilateLightmap: grows each chart's baked values into the empty texels around it, so that bilinear filtering
// at a chart's edge averages the chart with itself instead of with black.

#include <string>
#include <vector>

#include "gusuku/maths/input_error.h"
#include "gusuku_bake/lightmap_uv.h"

namespace gusuku::bake {

void dilateLightmap(std::vector<glm::vec4>& rgba_texels, int resolution, int iterations) {
    if (resolution < 1 || rgba_texels.size() != size_t(resolution) * size_t(resolution))
        throw InputError("lightmap", "texels",
                         "dilation needs resolution^2 texels (resolution " + std::to_string(resolution) + ", got " +
                             std::to_string(rgba_texels.size()) + ")");
    // Read from a copy of the previous iteration so that a texel filled now does not feed its neighbours until
    // the next ring: every ring is the average of the ring inside it, independent of scan order.
    std::vector<glm::vec4> previous;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        previous = rgba_texels;
        bool changed = false;
        for (int y = 0; y < resolution; ++y) {
            for (int x = 0; x < resolution; ++x) {
                const size_t index = size_t(y) * resolution + x;
                if (previous[index].w > 0.0f) continue;
                glm::vec4 sum{0.0f};
                int valid_neighbours = 0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= resolution || ny >= resolution)
                            continue;
                        const glm::vec4& neighbour = previous[size_t(ny) * resolution + nx];
                        if (!(neighbour.w > 0.0f)) continue;
                        sum += neighbour;
                        ++valid_neighbours;
                    }
                }
                if (valid_neighbours == 0) continue;
                rgba_texels[index] = sum / float(valid_neighbours);
                changed = true;
            }
        }
        if (!changed) break;
    }
}

}  // namespace gusuku::bake

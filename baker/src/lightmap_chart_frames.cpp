// Phase 7 of generateLightmapCharts (lightmap_charting.h): where each chart lies in its frame of texels at a
// density, chosen among a few placements per axis, and which texels of the frame its bilinear lookups read and its
// triangles claim (the texel rasterisation the packer's shapes and the charted mesh's uv1 share).

#include <algorithm>
#include <cmath>
#include <vector>

#include "lightmap_charting.h"
#include "lightmap_raster.h"

namespace gusuku::bake::detail {
namespace {

// Where a chart of `extent` texels may start inside its frame, and the frame's texels, along one axis. Bilinear
// lookups on the chart read the texels whose centre lies less than a texel from it: every centre it covers plus one
// beyond each end, wherever it lies (an open unit interval holds one centre). Placement decides how many centres it
// covers, n = floor(extent) or n + 1, and so reads n + 2 or n + 3 texels. Each placement keeps both chart edges and
// both ends of the read span at least kEdgeClearanceTexels clear of rows of centres, so float noise cannot flip
// which centres it covers or reads; the frame is exactly the texels it reads.
// - Fewer: the chart starts half of 1 - frac(extent) past a centre and covers n (a 1 m face at 8 texels/m covers 8
//   centres, reads 10); possible while frac <= 1 - 2 * clearance.
// - More: it starts frac / 2 before a centre and covers n + 1 (a 1.5 m face at 2 texels/m covers 4, reads 6);
//   possible while frac >= 2 * clearance.
// Which fills better depends on the chart (chooseChartFrame): n + 1 of n + 3 beats n of n + 2 on a rectangle, but a
// thin, finely cut strip claims a texel under each triangle that covers no centre (lightmap_uv.h's fallback), so
// covering no row of centres may claim as many texels for fewer reads.
constexpr double kEdgeClearanceTexels = 0.05;

// - Spanned: the chart is stretched along the axis (shrunk by kSpannedMaxShrink at most: a 1 m wall at 8 texels/m
//   spans 9 centres, not 10) so that its ends lie kSpannedInsetTexels inside the first and last of
//   m = ceil(extent (1 - kSpannedMaxShrink) + 2 inset) + 1 centres. It reads exactly those
//   m texels (the next centre out lies a texel and the inset away, beyond the read slack), and claims the two end
//   centres too, by lightmap_raster.h's near-claim rule (a centre within kNearClaimTexels of a triangle and in
//   none): every texel it reads is traced, so a rectangle's read ring costs nothing. A 4 cm baluster's faces
//   (2.56 texels at 16 texels/m) read 4 texels across instead of 5 and claim all 4 instead of 3.
constexpr double kSpannedInsetTexels = 0.01;
constexpr double kSpannedMaxShrink = 0.005;
static_assert(kSpannedInsetTexels > detail::kReadSlackTexels && 2.0 * kSpannedInsetTexels <= detail::kNearClaimTexels,
              "the spanned frame must read no texel beyond its end centres and claim both");

struct AxisFrame {
    int texels = 1;
    double margin = 0.0;
    double stretch = 1.0;  // texels of the frame per texel of the chart at the density
};

// The placements along one axis that keep the clearance: one or both, and the spanned one.
std::vector<AxisFrame> axisFrames(double extent) {
    const double whole = std::floor(extent), fraction = extent - whole;
    std::vector<AxisFrame> frames;
    if (0.5 * (1.0 - fraction) >= kEdgeClearanceTexels) frames.push_back({int(whole) + 2, 1.0 - 0.5 * fraction});
    if (0.5 * fraction >= kEdgeClearanceTexels) frames.push_back({int(whole) + 3, 1.5 - 0.5 * fraction});
    if (extent > 1e-6) {
        const double spans = std::max(1.0, std::ceil(extent * (1.0 - kSpannedMaxShrink) + 2.0 * kSpannedInsetTexels));
        frames.push_back({int(spans) + 1, 0.5 + kSpannedInsetTexels, (spans - 2.0 * kSpannedInsetTexels) / extent});
    }
    return frames;
}

// The texels of a chart's frame its bilinear lookups read (`read`, frame.inner.x * frame.inner.y, row-major: the
// texels whose centre lies less than a texel from one of its triangles on both axes, by kReadSlackTexels
// conservatively; a zero-area triangle reads every texel around its bounding box), and how many texels it claims by
// lightmap_uv.h's coverage rule (the centres its triangles cover, and the texel under the UV centroid of a triangle
// that covers none): the texels traced for it. The frame is then cut (or grown) to the read texels' bounding box:
// a read found only through the slack (a corner of an unfolded net that lands on a row of centres) may lie a texel
// outside axisFrames' frame, and must still be kept from other charts.
size_t rasteriseChartFrame(const Chart& chart, ChartFrame& frame, double scale, std::vector<uint8_t>& read,
                           std::vector<uint8_t>& claimed) {
    // A grid with one texel more on every side than the frame.
    const glm::ivec2 grid = frame.inner + 2;
    const glm::dvec2 grid_margin = frame.margin + 1.0;
    const size_t cells = size_t(grid.x) * size_t(grid.y);
    std::vector<uint8_t> grid_read(cells, 0);
    claimed.assign(cells, 0);
    size_t claimed_count = 0;
    auto claim = [&](int x, int y) {
        uint8_t& cell = claimed[size_t(y) * size_t(grid.x) + size_t(x)];
        claimed_count += cell ? 0 : 1;
        cell = 1;
    };
    const ChartFrame grid_frame{grid, grid_margin, frame.stretch};
    glm::ivec2 low_cell(grid), high_cell(-1);
    for (size_t slot = 0; slot < chart.triangles.size(); ++slot) {
        detail::UvTriangle local;
        for (int i = 0; i < 3; ++i) local[i] = localTexel(chart, grid_frame, scale, chart.corners[slot * 3 + size_t(i)]);
        const glm::dvec2 low = glm::min(local[0], glm::min(local[1], local[2]));
        const glm::dvec2 high = glm::max(local[0], glm::max(local[1], local[2]));
        // Texels whose centre lies within (low - 1, high + 1), with the slack; the grid holds them all.
        const int first_x = std::clamp(int(std::floor(low.x - 1.5 - detail::kReadSlackTexels)), 0, grid.x - 1);
        const int last_x = std::clamp(int(std::floor(high.x + 0.5 + detail::kReadSlackTexels)), 0, grid.x - 1);
        const int first_y = std::clamp(int(std::floor(low.y - 1.5 - detail::kReadSlackTexels)), 0, grid.y - 1);
        const int last_y = std::clamp(int(std::floor(high.y + 0.5 + detail::kReadSlackTexels)), 0, grid.y - 1);
        bool covers_a_centre = false;
        for (int y = first_y; y <= last_y; ++y)
            for (int x = first_x; x <= last_x; ++x) {
                if (!detail::bilinearReadsTexel(local, x, y)) continue;
                grid_read[size_t(y) * size_t(grid.x) + size_t(x)] = 1;
                low_cell = glm::min(low_cell, glm::ivec2(x, y));
                high_cell = glm::max(high_cell, glm::ivec2(x, y));
                if (detail::containsPoint(local, glm::dvec2(x + 0.5, y + 0.5))) {
                    claim(x, y);
                    covers_a_centre = true;
                } else if (detail::nearClaimsCentre(local, glm::dvec2(x + 0.5, y + 0.5))) {
                    claim(x, y);  // the bake claims it unless another triangle contains it (lightmap_texels.cpp)
                }
            }
        if (!covers_a_centre) {
            const glm::dvec2 centroid = (local[0] + local[1] + local[2]) / 3.0;
            claim(std::clamp(int(std::floor(centroid.x)), 0, grid.x - 1),
                  std::clamp(int(std::floor(centroid.y)), 0, grid.y - 1));
        }
    }
    if (high_cell.x < 0) low_cell = high_cell = glm::ivec2(1);  // reads nothing (cannot happen): keep one texel
    frame.inner = high_cell - low_cell + 1;
    frame.margin = grid_margin - glm::dvec2(low_cell);
    read.assign(size_t(frame.inner.x) * size_t(frame.inner.y), 0);
    for (int y = 0; y < frame.inner.y; ++y)
        for (int x = 0; x < frame.inner.x; ++x)
            read[size_t(y) * size_t(frame.inner.x) + size_t(x)] =
                grid_read[size_t(y + low_cell.y) * size_t(grid.x) + size_t(x + low_cell.x)];
    return claimed_count;
}

// The claimed texels per read texel the bake's charts reach: choosing each chart's frame to maximise claimed -
// kTargetClaimedPerRead * read maximises the lightmap's claimed share over all charts' reads when the target is that
// share (the packer then keeps the reads' share of the lightmap near 90 %).
constexpr double kTargetClaimedPerRead = 0.65;

}  // namespace

// A chart's vertex in texels of its unturned frame at `scale` texels per metre: flattened, moved to the
// rectangle's corner, stretched and offset by the frame's margin.
glm::dvec2 localTexel(const Chart& chart, const ChartFrame& frame, double scale, const glm::dvec2& corner) {
    return (corner - chart.min) * scale * frame.stretch + frame.margin;
}

// The chart's frame among the placements axisFrames allows per axis (up to nine) that claims the most texels for
// its reads (kTargetClaimedPerRead; ties: fewer reads, then the first), with its read texels in `read`.
ChartFrame chooseChartFrame(const Chart& chart, const glm::dvec2& extent, double scale, std::vector<uint8_t>& read) {
    const std::vector<AxisFrame> along_x = axisFrames(extent.x * scale), along_y = axisFrames(extent.y * scale);
    ChartFrame best;
    double best_score = -INFINITY;
    size_t best_read = 0;
    std::vector<uint8_t> candidate_read, claimed;
    for (const AxisFrame& x : along_x)
        for (const AxisFrame& y : along_y) {
            ChartFrame frame{glm::ivec2(x.texels, y.texels), glm::dvec2(x.margin, y.margin),
                             glm::dvec2(x.stretch, y.stretch)};
            const size_t claimed_count = rasteriseChartFrame(chart, frame, scale, candidate_read, claimed);
            const size_t read_count = size_t(std::count(candidate_read.begin(), candidate_read.end(), uint8_t(1)));
            const double score = double(claimed_count) - kTargetClaimedPerRead * double(read_count);
            if (score > best_score || (score == best_score && read_count < best_read)) {
                best = frame;
                best_score = score;
                best_read = read_count;
                read.swap(candidate_read);
            }
        }
    return best;
}

// Phase 7: what the packer needs of each chart at a density: which texels of its frame (chooseChartFrame) its
// bilinear lookups read. Packing these sets apart, rather than the touched texels with a ring of gutter each, lets
// two charts share the one gutter texel that only one of them reads: the rule that keeps bilinear filtering (and
// the chart-aware dilation) from mixing charts, at half the gutter of the touched rule on thin parts.
std::vector<detail::ChartShape> chartShapes(const std::vector<Chart>& charts,
                                            const std::vector<glm::dvec2>& extents, double scale) {
    std::vector<detail::ChartShape> shapes(charts.size());
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        detail::ChartShape& shape = shapes[chart_index];
        shape.inner = chooseChartFrame(charts[chart_index], extents[chart_index], scale, shape.occupied).inner;
    }
    return shapes;
}

}  // namespace gusuku::bake::detail

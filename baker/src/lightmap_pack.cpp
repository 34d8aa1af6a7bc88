// Packing lightmap charts into the square lightmap, and choosing the lightmap's size from the surface area.
//
// The packer keeps one height per lightmap column (a skyline) and drops each chart (largest perimeter first), at
// each of its four turns and every x (rectangles: every step of the skyline), onto it: the chart rests where the
// first of its columns meets the skyline, judged by the shape of the texels it touches (grown by the padding),
// not by its bounding rectangle, so a gable's triangle and the next one turned upside down lock into a
// parallelogram. Two placement rules (PlacementRule) are tried and the first that fits wins: neither is best on
// every model (on the sample, the shared shrine and the shared house each wins somewhere). The texels left under
// an overhang are kept as holes, per column runs of empty rows; a small chart (kHoleFillMaxTexels) goes into the
// lowest hole that holds it before it is dropped on the skyline (the shrine's beam ends and short pieces fill
// the holes, so the same charts fit a smaller lightmap).

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/lightmap_uv.h"
#include "lightmap_pack.h"

namespace gusuku::bake {
namespace detail {
namespace {

// A chart's padded footprint at one turn: per column the first and one-past-last occupied row.
struct TurnedFootprint {
    int width = 0;
    int height = 0;
    std::vector<int> bottom;  // per column: first row occupied (height when none)
    std::vector<int> top;     // per column: one past the last row occupied (0 when none)
    bool rectangular = true;  // every column spans every row
};

// The cell of the unturned inner rectangle that lands at (column, row) of the turned one.
glm::ivec2 unturnedCell(const glm::ivec2& inner, int quarter_turns, int column, int row) {
    switch (quarter_turns & 3) {
        case 0: return {column, row};
        case 1: return {row, inner.y - 1 - column};
        case 2: return {inner.x - 1 - column, inner.y - 1 - row};
        default: return {inner.x - 1 - row, column};
    }
}

TurnedFootprint turnedFootprint(const ChartShape& shape, int quarter_turns, int padding) {
    const bool sideways = (quarter_turns & 1) != 0;
    const int inner_width = sideways ? shape.inner.y : shape.inner.x;
    const int inner_height = sideways ? shape.inner.x : shape.inner.y;
    TurnedFootprint footprint;
    footprint.width = inner_width + 2 * padding;
    footprint.height = inner_height + 2 * padding;
    footprint.bottom.assign(size_t(footprint.width), footprint.height);
    footprint.top.assign(size_t(footprint.width), 0);
    // Per turned inner column, the occupied rows' span; the padding grows it by `padding` every way.
    for (int column = 0; column < inner_width; ++column) {
        int first = -1, last = -1;
        for (int row = 0; row < inner_height; ++row) {
            const glm::ivec2 cell = unturnedCell(shape.inner, quarter_turns, column, row);
            if (!shape.occupied[size_t(cell.y) * size_t(shape.inner.x) + size_t(cell.x)]) continue;
            if (first < 0) first = row;
            last = row;
        }
        if (first < 0) continue;
        for (int grown = column; grown <= column + 2 * padding; ++grown) {
            footprint.bottom[size_t(grown)] = std::min(footprint.bottom[size_t(grown)], first);
            footprint.top[size_t(grown)] = std::max(footprint.top[size_t(grown)], last + 1 + 2 * padding);
        }
    }
    for (int column = 0; column < footprint.width; ++column)
        footprint.rectangular = footprint.rectangular && footprint.bottom[size_t(column)] == 0 &&
                                footprint.top[size_t(column)] == footprint.height;
    return footprint;
}

struct PackResult {
    int total_height = 0;  // texels the packing would need (may exceed the resolution)
    bool fits = false;
    std::vector<ChartPlacement> placements;
};

// Every chart's footprints at the turns worth trying: all four, or two when the chart touches every texel of its
// rectangle (a half turn then changes nothing).
std::vector<std::vector<TurnedFootprint>> turnedFootprints(const std::vector<ChartShape>& shapes, int padding) {
    std::vector<std::vector<TurnedFootprint>> footprints(shapes.size());
    for (size_t chart = 0; chart < shapes.size(); ++chart) {
        const ChartShape& shape = shapes[chart];
        const bool full = std::all_of(shape.occupied.begin(), shape.occupied.end(), [](uint8_t cell) { return cell != 0; });
        for (int turns = 0; turns < (full ? 2 : 4); ++turns)
            footprints[chart].push_back(turnedFootprint(shape, turns, padding));
    }
    return footprints;
}

// Where a chart goes among the skyline's candidates (ties: the second key, then the leftmost).
enum class PlacementRule {
    LowestBottom,     ///< lowest resting row, then lowest top
    LowestTopAndGap,  ///< lowest top plus mean empty texels left under it, then fewest empty texels
};
constexpr PlacementRule kPlacementRules[] = {PlacementRule::LowestBottom, PlacementRule::LowestTopAndGap};

// Charts whose padded footprint has at most this many texels look for a hole before resting on the skyline: the
// small ones come last (largest perimeter first), when the big ones have left holes under their overhangs.
constexpr int kHoleFillMaxTexels = 512;

// Empty runs [start, end) of one column under the skyline, in rising order, and the longest run's length.
struct ColumnHoles {
    std::vector<glm::ivec2> runs;
    int longest = 0;
    void add(const glm::ivec2& run) {
        runs.push_back(run);
        longest = std::max(longest, run.y - run.x);
    }
};

bool holeHolds(const ColumnHoles& column, int start, int end) {
    if (end - start > column.longest) return false;
    // The last run starting at or below `start` is the only one that can hold it (runs do not overlap).
    auto after = std::upper_bound(column.runs.begin(), column.runs.end(), start,
                                  [](int row, const glm::ivec2& run) { return row < run.x; });
    return after != column.runs.begin() && end <= (after - 1)->y;
}

// Takes [start, end) out of the column's run that holds it.
void fillHole(ColumnHoles& column, int start, int end) {
    std::vector<glm::ivec2>& runs = column.runs;
    for (size_t at = 0; at < runs.size(); ++at) {
        const glm::ivec2 run = runs[at];
        if (!(run.x <= start && end <= run.y)) continue;
        runs.erase(runs.begin() + std::ptrdiff_t(at));
        if (end < run.y) runs.insert(runs.begin() + std::ptrdiff_t(at), glm::ivec2(end, run.y));
        if (run.x < start) runs.insert(runs.begin() + std::ptrdiff_t(at), glm::ivec2(run.x, start));
        break;
    }
    column.longest = 0;
    for (const glm::ivec2& run : runs) column.longest = std::max(column.longest, run.y - run.x);
}

struct HolePlace {
    bool found = false;
    int x = 0, y = 0, turns = 0;
};

// The lowest place (then leftmost) where a turn of the chart lies wholly in holes: each of its columns' spans
// inside one empty run, its first column resting on a run's start.
HolePlace lowestHole(const std::vector<ColumnHoles>& holes, const std::vector<TurnedFootprint>& turns, int resolution) {
    HolePlace best;
    int longest = 0;
    for (const ColumnHoles& column : holes) longest = std::max(longest, column.longest);
    for (int turn = 0; turn < int(turns.size()); ++turn) {
        const TurnedFootprint& footprint = turns[size_t(turn)];
        int first = 0, tallest = 0;
        while (first < footprint.width && footprint.top[size_t(first)] == 0) ++first;
        if (first == footprint.width) continue;
        for (int column = first; column < footprint.width; ++column)
            tallest = std::max(tallest, footprint.top[size_t(column)] - footprint.bottom[size_t(column)]);
        if (tallest > longest) continue;  // no hole is that tall
        const int first_span = footprint.top[size_t(first)] - footprint.bottom[size_t(first)];
        for (int x = 0; x + footprint.width <= resolution; ++x) {
            if (holes[size_t(x + first)].longest < first_span) continue;
            for (const glm::ivec2& run : holes[size_t(x + first)].runs) {
                const int y = run.x - footprint.bottom[size_t(first)];
                if (best.found && y >= best.y) break;  // runs rise: no lower place in this column
                if (run.y - run.x < first_span || y < 0) continue;
                bool holds = true;
                for (int column = first; column < footprint.width && holds; ++column)
                    if (footprint.top[size_t(column)] > 0)
                        holds = holeHolds(holes[size_t(x + column)], y + footprint.bottom[size_t(column)],
                                          y + footprint.top[size_t(column)]);
                if (holds) best = HolePlace{true, x, y, turn};
            }
        }
    }
    return best;
}

PackResult skylinePack(const std::vector<ChartShape>& shapes, const std::vector<std::vector<TurnedFootprint>>& footprints,
                       int resolution, int padding, PlacementRule rule) {
    PackResult result;
    result.placements.resize(shapes.size());
    std::vector<size_t> order(shapes.size());
    std::iota(order.begin(), order.end(), size_t(0));
    auto shortSide = [&](size_t chart) { return std::min(shapes[chart].inner.x, shapes[chart].inner.y); };
    auto longSide = [&](size_t chart) { return std::max(shapes[chart].inner.x, shapes[chart].inner.y); };
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const int perimeter_a = shortSide(a) + longSide(a), perimeter_b = shortSide(b) + longSide(b);
        if (perimeter_a != perimeter_b) return perimeter_a > perimeter_b;
        if (shortSide(a) != shortSide(b)) return shortSide(a) > shortSide(b);
        if (longSide(a) != longSide(b)) return longSide(a) > longSide(b);
        return a < b;
    });
    result.fits = true;
    std::vector<int> skyline(size_t(resolution), 0);
    std::vector<ColumnHoles> holes{size_t(resolution)};  // per column: empty runs under the skyline
    std::vector<int> steps;
    std::vector<uint32_t> tried(size_t(resolution), 0);
    uint32_t stamp = 0;
    for (size_t chart : order) {
        int best_top = INT_MAX, best_x = 0, best_y = 0, best_turns = 0;
        long long best_waste = LLONG_MAX, best_key = LLONG_MAX;
        TurnedFootprint best_footprint;
        (void)shapes;
        // Candidate x: a chart's left or right side against a step of the skyline (or a lightmap edge); between
        // steps a chart only slides along a level stretch, where it rests no lower.
        steps.clear();
        steps.push_back(0);
        for (int x = 1; x < resolution; ++x)
            if (skyline[size_t(x)] != skyline[size_t(x - 1)]) steps.push_back(x);
        steps.push_back(resolution);
        for (int turns = 0; turns < int(footprints[chart].size()); ++turns) {
            const TurnedFootprint& footprint = footprints[chart][size_t(turns)];
            const int* bottom = footprint.bottom.data();
            const int* column_top = footprint.top.data();
            ++stamp;
            // A shaped chart (one that leaves texels of its rectangle untouched) may lock into the skyline's
            // slopes anywhere: it tries every x.
            const bool every_x = !footprint.rectangular;
            const size_t candidates = every_x ? size_t(resolution) : 2 * steps.size();
            for (size_t candidate = 0; candidate < candidates; ++candidate) {
                const int x = every_x ? int(candidate)
                                      : candidate % 2 == 0 ? steps[candidate / 2] : steps[candidate / 2] - footprint.width;
                if (x < 0 || x + footprint.width > resolution || tried[size_t(x)] == stamp) continue;
                tried[size_t(x)] = stamp;
                const int* heights = skyline.data() + x;
                int y = 0;
                for (int column = 0; column < footprint.width; ++column)
                    if (column_top[column] > 0) y = std::max(y, heights[column] - bottom[column]);
                int top = 0;
                for (int column = 0; column < footprint.width; ++column)
                    if (column_top[column] > 0) top = std::max(top, y + column_top[column]);
                long long waste = 0;
                for (int column = 0; column < footprint.width; ++column)
                    if (column_top[column] > 0) waste += y + bottom[column] - heights[column];
                // LowestBottom: bottom-left. LowestTopAndGap: the top plus the mean gap left under the chart.
                const long long key = rule == PlacementRule::LowestBottom ? y : top + waste / std::max(1, footprint.width);
                const long long second = rule == PlacementRule::LowestBottom ? top : waste;
                if (key < best_key || (key == best_key && second < best_waste)) {
                    best_key = key;
                    best_top = top;
                    best_waste = second;
                    best_x = x;
                    best_y = y;
                    best_turns = turns;
                }
            }
        }
        if (best_top != INT_MAX) best_footprint = footprints[chart][size_t(best_turns)];
        ChartPlacement& placement = result.placements[chart];
        // A small chart goes into a hole left under an earlier chart's overhang when one holds it: the lowest.
        HolePlace hole;
        if (best_top != INT_MAX && footprints[chart][0].width * footprints[chart][0].height <= kHoleFillMaxTexels)
            hole = lowestHole(holes, footprints[chart], resolution);
        if (hole.found) {
            best_turns = hole.turns;
            best_footprint = footprints[chart][size_t(best_turns)];
            best_x = hole.x;
            best_y = hole.y;
            best_top = 0;  // the skyline does not move
            for (int column = 0; column < best_footprint.width; ++column)
                if (best_footprint.top[size_t(column)] > 0)
                    fillHole(holes[size_t(best_x + column)], best_y + best_footprint.bottom[size_t(column)],
                             best_y + best_footprint.top[size_t(column)]);
        } else if (best_top == INT_MAX) {  // wider than the lightmap every way
            result.fits = false;
            best_footprint = footprints[chart][0];
            best_x = 0;
            best_y = result.total_height;
            best_top = best_y + best_footprint.height;
        } else {
            for (int column = 0; column < best_footprint.width; ++column)
                if (best_footprint.top[size_t(column)] > 0) {
                    const int rests = best_y + best_footprint.bottom[size_t(column)];
                    if (rests > skyline[size_t(best_x + column)])
                        holes[size_t(best_x + column)].add(glm::ivec2(skyline[size_t(best_x + column)], rests));
                    skyline[size_t(best_x + column)] = best_y + best_footprint.top[size_t(column)];
                }
        }
        placement.quarter_turns = best_turns;
        placement.inner_width = best_footprint.width - 2 * padding;
        placement.inner_height = best_footprint.height - 2 * padding;
        placement.x = best_x + padding;
        placement.y = best_y + padding;
        result.total_height = std::max(result.total_height, best_top);
    }
    if (result.total_height > resolution) result.fits = false;
    return result;
}

// 2 x 2 texels per chart: what must fit even at the lowest density (bilinear lookups on a point read the four texels
// around it; a chart reads at least two texels along each axis), so the density search below always ends.
std::vector<ChartShape> pointShapes(size_t count) {
    ChartShape point;
    point.inner = {2, 2};
    point.occupied = {1, 1, 1, 1};
    return std::vector<ChartShape>(count, point);
}

}  // namespace

glm::dvec2 placedTexel(const ChartPlacement& placement, const glm::ivec2& inner, const glm::dvec2& local) {
    const glm::dvec2 origin(placement.x, placement.y);
    switch (placement.quarter_turns & 3) {
        case 0: return origin + local;
        case 1: return origin + glm::dvec2(double(inner.y) - local.y, local.x);
        case 2: return origin + glm::dvec2(double(inner.x) - local.x, double(inner.y) - local.y);
        default: return origin + glm::dvec2(local.y, double(inner.x) - local.x);
    }
}

glm::ivec2 innerTexelSize(const glm::dvec2& extent_m, double texels_per_metre) {
    return glm::ivec2(int(std::floor(extent_m.x * texels_per_metre)) + 1,
                      int(std::floor(extent_m.y * texels_per_metre)) + 1);
}

ChartPacking packChartShapes(const ChartShapesAt& shapes_at, double texels_per_metre, int resolution, int padding) {
    ChartPacking packing;
    std::vector<ChartShape> shapes = shapes_at(texels_per_metre);
    // The first placement rule that fits (the lowest top when none does, for the density bracket).
    auto pack = [&](const std::vector<ChartShape>& charts) {
        const std::vector<std::vector<TurnedFootprint>> footprints = turnedFootprints(charts, padding);
        PackResult best;
        for (const PlacementRule rule : kPlacementRules) {
            PackResult attempt = skylinePack(charts, footprints, resolution, padding, rule);
            if (attempt.fits) return attempt;
            if (best.placements.empty() || attempt.total_height < best.total_height) best = std::move(attempt);
        }
        return best;
    };
    PackResult attempt = pack(shapes);
    if (attempt.fits) {
        packing.texels_per_metre = texels_per_metre;
        packing.placements = std::move(attempt.placements);
        return packing;
    }
    if (!pack(pointShapes(shapes.size())).fits)
        throw InputError("lightmap", "resolution",
                         std::to_string(shapes.size()) + " charts with " + std::to_string(padding) +
                             " texels of padding do not fit in " + std::to_string(resolution) + "^2 texels even at " +
                             "2 x 2 texels each; raise the lightmap resolution");

    // Bracket the largest density that fits, then bisect it.
    double failing_density = texels_per_metre;
    double fitting_density = texels_per_metre;
    PackResult fitting;
    for (;;) {
        const double shrink = std::clamp(std::sqrt(double(resolution) / double(attempt.total_height)), 0.3, 0.95);
        fitting_density *= shrink;
        attempt = pack(shapes_at(fitting_density));
        if (attempt.fits) break;
        failing_density = fitting_density;
    }
    fitting = std::move(attempt);
    for (int step = 0; step < 12; ++step) {
        const double middle = 0.5 * (fitting_density + failing_density);
        PackResult trial = pack(shapes_at(middle));
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

int smallestFittingResolution(const std::vector<ChartShape>& shapes, int max_resolution, int padding) {
    const int capped_maximum = max_resolution / 4 * 4;
    double occupied_area = 0.0;
    int longest_side = 1;
    for (const ChartShape& shape : shapes) {
        for (uint8_t cell : shape.occupied) occupied_area += cell ? 1.0 : 0.0;
        longest_side = std::max(longest_side, std::max(shape.inner.x, shape.inner.y) + 2 * padding);
    }
    const std::vector<std::vector<TurnedFootprint>> footprints = turnedFootprints(shapes, padding);
    auto fits = [&](int resolution) {
        for (const PlacementRule rule : kPlacementRules)
            if (skylinePack(shapes, footprints, resolution, padding, rule).fits) return true;
        return false;
    };
    // Multiples of 4 from the occupied area's bound: grow by an eighth until one fits, then bisect down to within
    // 1.6 % of the smallest (packing is nearly monotone in the side; the answer returned always fits).
    int low = std::max(4, (std::max(int(std::ceil(std::sqrt(occupied_area))), longest_side) + 3) / 4 * 4);
    if (low >= capped_maximum) return capped_maximum;
    if (fits(low)) return low;
    int high = low;
    for (;;) {
        low = high;
        high = std::min(capped_maximum, (high + high / 8 + 7) / 4 * 4);
        if (high >= capped_maximum) {
            if (!fits(capped_maximum)) return capped_maximum;
            break;
        }
        if (fits(high)) break;
    }
    while (high - low > std::max(4, high / 64)) {  // low does not fit, high does; within 1.6 % is enough
        const int middle = (low + high) / 8 * 4;
        if (middle <= low || middle >= high) break;
        if (fits(middle))
            high = middle;
        else
            low = middle;
    }
    return high;
}

}  // namespace detail

double meshSurfaceAreaM2(const TriangleMesh& mesh) {
    double area_m2 = 0.0;
    for (size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        const glm::dvec3 p0(mesh.positions[mesh.indices[triangle * 3 + 0]]);
        const glm::dvec3 p1(mesh.positions[mesh.indices[triangle * 3 + 1]]);
        const glm::dvec3 p2(mesh.positions[mesh.indices[triangle * 3 + 2]]);
        const double double_area = glm::length(glm::cross(p1 - p0, p2 - p0));
        if (std::isfinite(double_area)) area_m2 += 0.5 * double_area;
    }
    return area_m2;
}

int chooseLightmapResolution(const TriangleMesh& mesh, double texels_per_metre, int max_resolution) {
    if (!(texels_per_metre > 0.0) || !std::isfinite(texels_per_metre))
        throw InputError("lightmap", "texels_per_metre",
                         "must be finite and positive, got " + std::to_string(texels_per_metre));
    if (max_resolution < 4)
        throw InputError("lightmap", "max_resolution", "must be at least 4, got " + std::to_string(max_resolution));
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw InputError("lightmap", "mesh indices", "index " + std::to_string(index) + " is out of range");
    const double area_m2 = meshSurfaceAreaM2(mesh);
    const double side = std::ceil(std::sqrt(area_m2 * texels_per_metre * texels_per_metre * kLightmapPackingOverhead));
    const int capped_maximum = max_resolution / 4 * 4;
    if (!(side < double(capped_maximum))) return capped_maximum;
    const int rounded_up = (int(side) + 3) / 4 * 4;
    return std::clamp(rounded_up, 4, capped_maximum);
}

}  // namespace gusuku::bake

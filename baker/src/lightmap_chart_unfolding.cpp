// Phase 5 of generateLightmapCharts (lightmap_charting.h): join charts across sharp edges by unfolding one about
// their seam, where the joined chart saves gutter texels and overlaps nothing of itself.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "lightmap_charting.h"

namespace gusuku::bake::detail {
namespace {

constexpr double kMaxUnfoldAngleDeg = 90.0;      // charts meeting at up to this are unfolded into one (phase 5)
// ... when that saves at least this share of the smaller chart's padded texels: big charts joined for a few gutter
// texels make long strips that pack worse than their parts.
constexpr double kMinUnfoldSaving = 0.25;
// ... and the joined chart takes at most this share of all the charts' padded texels: a piece that big leaves the
// packer little room.
constexpr double kMaxUnfoldedShare = 1.0 / 16.0;

// Phase 5: join charts across sharp edges (up to kMaxUnfoldAngleDeg: a beam's corners) by unfolding one about the
// seam, as a box's net lies flat: a thin beam's four long faces become one strip that pays its gutter once,
// instead of four one-texel charts each with a texel of gutter on both sides. Unfolding is a rigid move in the
// plane, so the density stays as requested. A join is taken when the joined chart overlaps nothing of itself,
// saves at least kMinUnfoldSaving of the smaller chart's padded rectangle, and stays under kMaxUnfoldedShare of all
// the charts' padded texels. Seams are tried longest first, again after every round that joined something (a strip
// grows a face at a time); a pair refused is tried again only once one of its charts has grown.
// A triangle edge whose neighbour across it lies in another chart, at most the unfold angle away.
struct Seam {
    uint32_t triangle[2];
    uint32_t welded[2];  // the edge's welded vertices
};
// The seams two charts share; length: the seams' total flattened length, which orders the joins.
struct ChartPair {
    double length = 0.0;
    std::vector<Seam> seams;
};
// Keyed by (lower chart << 32 | higher chart).
using ChartPairs = std::unordered_map<uint64_t, ChartPair>;

ChartPairs findSeams(const MeshAnalysis& analysis, const std::vector<int64_t>& chart_of) {
    const std::vector<TriangleInfo>& triangles = analysis.triangles;
    const EdgeNeighbours& adjacency = analysis.adjacency;
    const double min_normal_dot = std::cos(kMaxUnfoldAngleDeg * std::numbers::pi / 180.0) - 1e-3;
    ChartPairs pairs;
    for (uint32_t triangle = 0; triangle < triangles.size(); ++triangle) {
        if (triangles[triangle].degenerate) continue;
        for (int edge = 0; edge < 3; ++edge) {
            const size_t slot = size_t(triangle) * 3 + size_t(edge);
            for (uint32_t at = adjacency.offsets[slot]; at < adjacency.offsets[slot + 1]; ++at) {
                const uint32_t next = adjacency.neighbours[at];
                const int64_t here = chart_of[triangle], there = chart_of[next];
                if (here == there || here > there) continue;  // each seam once, from the lower chart's side
                if (glm::dot(triangles[triangle].normal, triangles[next].normal) < min_normal_dot) continue;
                const uint32_t a = triangles[triangle].welded[edge], b = triangles[triangle].welded[(edge + 1) % 3];
                ChartPair& pair = pairs[uint64_t(here) << 32 | uint64_t(there)];
                pair.seams.push_back(Seam{{triangle, next}, {a, b}});
            }
        }
    }
    return pairs;
}

// A flattened triangle from a chart's corner list (3 per slot) and its welded vertices.
FlatTriangle flatTriangleAt(const std::vector<glm::dvec2>& corners, size_t slot, const TriangleInfo& info) {
    FlatTriangle flat;
    flat.min = glm::dvec2(INFINITY);
    flat.max = glm::dvec2(-INFINITY);
    for (int i = 0; i < 3; ++i) {
        flat.corner[i] = corners[slot * 3 + size_t(i)];
        flat.welded[i] = info.welded[i];
        flat.min = glm::min(flat.min, flat.corner[i]);
        flat.max = glm::max(flat.max, flat.corner[i]);
    }
    return flat;
}

// Phase 5 (unfoldAcrossSharpEdges below) as rounds over the chart pairs, longest seams first. Charts joined into
// another are emptied and point to it through root (a union-find); renumber() drops them at the end.
class ChartUnfolder {
public:
    ChartUnfolder(const MeshAnalysis& analysis, std::vector<int64_t>& chart_of, std::vector<Chart>& charts,
                  double texels_per_metre, int padding, double snap_tolerance)
        : analysis_(analysis), triangles_(analysis.triangles), chart_of_(chart_of), charts_(charts),
          texels_per_metre_(texels_per_metre), padding_(padding), snap_tolerance_(snap_tolerance),
          slot_of_(triangles_.size(), 0), padded_area_(charts.size()), root_(charts.size()),
          version_(charts.size(), 0) {
        for (const Chart& chart : charts_)
            for (uint32_t slot = 0; slot < chart.triangles.size(); ++slot) slot_of_[chart.triangles[slot]] = slot;
        for (size_t chart = 0; chart < charts_.size(); ++chart)
            padded_area_[chart] = paddedTexelArea(smallestRectangle(charts_[chart].corners), texels_per_metre_, padding_);
        total_padded_area_ = std::accumulate(padded_area_.begin(), padded_area_.end(), 0.0);
        std::iota(root_.begin(), root_.end(), int64_t(0));
    }

    // Rounds until one joins nothing: a strip grows a face at a time, so a pair may only pay after another join.
    void joinAll(ChartPairs& pairs) {
        const std::vector<std::pair<double, uint64_t>> order = seamOrder(pairs);
        for (bool joined_any = true; joined_any;) {
            joined_any = false;
            for (const auto& [length, key] : order) joined_any = tryJoin(key, pairs.at(key)) || joined_any;
        }
    }

    // Drop the emptied charts; renumber.
    void renumber() {
        std::vector<int64_t> renumbered(charts_.size(), -1);
        std::vector<Chart> kept_charts;
        for (size_t chart = 0; chart < charts_.size(); ++chart) {
            if (root_[chart] != int64_t(chart)) continue;
            renumbered[chart] = int64_t(kept_charts.size());
            kept_charts.push_back(std::move(charts_[chart]));
        }
        for (int64_t& chart : chart_of_) chart = renumbered[size_t(chart)];
        charts_ = std::move(kept_charts);
    }

private:
    // Where a triangle's corner of this welded vertex lies in its chart (its chart's list, at slot_of * 3).
    glm::dvec2 cornerOf(uint32_t triangle, uint32_t welded) const {
        const Chart& chart = charts_[size_t(chart_of_[triangle])];
        for (int i = 0; i < 3; ++i)
            if (triangles_[triangle].welded[i] == welded) return chart.corners[size_t(slot_of_[triangle]) * 3 + size_t(i)];
        return chart.corners[size_t(slot_of_[triangle]) * 3];
    }

    double seamLength(const Seam& seam) const {
        return glm::length(cornerOf(seam.triangle[0], seam.welded[1]) - cornerOf(seam.triangle[0], seam.welded[0]));
    }

    // The pairs by their seams' total length, longest first (ties by key, so the order is the same every run).
    std::vector<std::pair<double, uint64_t>> seamOrder(ChartPairs& pairs) const {
        std::vector<std::pair<double, uint64_t>> order;
        for (auto& [key, pair] : pairs) {
            pair.length = 0.0;
            for (const Seam& seam : pair.seams) pair.length += seamLength(seam);
            order.emplace_back(pair.length, key);
        }
        std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) {
            return x.first != y.first ? x.first > y.first : x.second < y.second;
        });
        return order;
    }

    // The chart each chart was joined into (itself while whole), halving the path on the way.
    int64_t find(int64_t chart) {
        while (root_[size_t(chart)] != chart) chart = root_[size_t(chart)] = root_[size_t(root_[size_t(chart)])];
        return chart;
    }

    // Joins the pair's charts as they are now (the smaller moved onto the larger) when that pays and overlaps
    // nothing; a pair refused is tried again only once one of its charts has grown.
    bool tryJoin(uint64_t key, const ChartPair& pair) {
        int64_t keep = find(int64_t(key >> 32)), move = find(int64_t(key & 0xffffffffu));
        if (keep == move) return false;
        if (charts_[size_t(keep)].triangles.size() < charts_[size_t(move)].triangles.size()) std::swap(keep, move);
        const uint64_t versions = uint64_t(version_[size_t(keep)]) << 32 | version_[size_t(move)];
        const uint64_t pair_key = uint64_t(keep) << 32 | uint64_t(move);
        if (auto it = tried_.find(pair_key); it != tried_.end() && it->second == versions) return false;
        tried_[pair_key] = versions;
        unfoldMover(pair, keep, move);
        const Chart& kept = charts_[size_t(keep)];
        joined_ = kept.corners;
        joined_.insert(joined_.end(), moved_.begin(), moved_.end());
        const double joined_area = paddedTexelArea(smallestRectangle(joined_), texels_per_metre_, padding_);
        const double saved = padded_area_[size_t(keep)] + padded_area_[size_t(move)] - joined_area;
        if (joined_area > kMaxUnfoldedShare * total_padded_area_ ||
            saved < kMinUnfoldSaving * std::min(padded_area_[size_t(keep)], padded_area_[size_t(move)]))
            return false;
        if (movedOverlapsKept(kept, charts_[size_t(move)])) return false;
        join(keep, move, joined_area);
        return true;
    }

    // moved_: the moved chart's corners after the rigid move (rotation, then shift) unfolding it about the seam's
    // longest edge: both charts keep their lengths, so that edge lands exactly. The seam's other corners that land
    // within the snap tolerance become one with their partners (the two sides then share their uv1 exactly); those
    // that do not (a beam's strip closing on its first face, a curved roof's seam) stay cut, which the overlap
    // test allows only where nothing overlaps.
    void unfoldMover(const ChartPair& pair, int64_t keep, int64_t move) {
        const Seam* anchor = nullptr;
        double anchor_length = -1.0;
        for (const Seam& seam : pair.seams) {
            const double seam_length = seamLength(seam);
            if (seam_length > anchor_length) {
                anchor_length = seam_length;
                anchor = &seam;
            }
        }
        const bool anchor_first_kept = find(chart_of_[anchor->triangle[0]]) == keep;
        const uint32_t anchor_kept = anchor->triangle[anchor_first_kept ? 0 : 1];
        const uint32_t anchor_moved = anchor->triangle[anchor_first_kept ? 1 : 0];
        const glm::dvec2 from0 = cornerOf(anchor_moved, anchor->welded[0]), from1 = cornerOf(anchor_moved, anchor->welded[1]);
        const glm::dvec2 to0 = cornerOf(anchor_kept, anchor->welded[0]), to1 = cornerOf(anchor_kept, anchor->welded[1]);
        const double angle = std::atan2(cross2(from1 - from0, to1 - to0), glm::dot(from1 - from0, to1 - to0));
        const double c = std::cos(angle), s = std::sin(angle);
        const glm::dvec2 moved_centre = 0.5 * (from0 + from1), kept_centre = 0.5 * (to0 + to1);
        auto place = [&](const glm::dvec2& point) {  // counter-clockwise by `angle` about the anchor's middle
            const glm::dvec2 offset = point - moved_centre;
            return kept_centre + glm::dvec2(c * offset.x - s * offset.y, s * offset.x + c * offset.y);
        };
        const Chart& mover = charts_[size_t(move)];
        moved_.clear();
        for (const glm::dvec2& corner : mover.corners) moved_.push_back(place(corner));
        seam_target_.clear();
        for (const Seam& seam : pair.seams) {
            const bool first_kept = find(chart_of_[seam.triangle[0]]) == keep;
            for (uint32_t welded : seam.welded)
                seam_target_.emplace(welded, cornerOf(seam.triangle[first_kept ? 0 : 1], welded));
        }
        for (size_t slot = 0; slot < mover.triangles.size(); ++slot)
            for (int i = 0; i < 3; ++i) {
                auto it = seam_target_.find(triangles_[mover.triangles[slot]].welded[i]);
                glm::dvec2& corner = moved_[slot * 3 + size_t(i)];
                if (it != seam_target_.end() && glm::length(corner - it->second) <= snap_tolerance_) corner = it->second;
            }
    }

    // The moved triangles against the kept ones (each chart overlaps nothing of itself already).
    bool movedOverlapsKept(const Chart& kept, const Chart& mover) const {
        FlatChartIndex index(4.0 * analysis_.typical_edge, analysis_.overlap_tolerance, snap_tolerance_);
        for (size_t slot = 0; slot < kept.triangles.size(); ++slot)
            index.add(flatTriangleAt(kept.corners, slot, triangles_[kept.triangles[slot]]));
        bool overlaps = false;
        for (size_t slot = 0; slot < mover.triangles.size() && !overlaps; ++slot)
            overlaps = index.overlapsAny(flatTriangleAt(moved_, slot, triangles_[mover.triangles[slot]]));
        return overlaps;
    }

    // Join: the moved chart's triangles follow the kept chart's, its corners unfolded; the moved chart empties.
    void join(int64_t keep, int64_t move, double joined_area) {
        Chart& kept = charts_[size_t(keep)];
        Chart& mover = charts_[size_t(move)];
        const uint32_t first_slot = uint32_t(kept.triangles.size());
        for (size_t slot = 0; slot < mover.triangles.size(); ++slot) slot_of_[mover.triangles[slot]] = first_slot + uint32_t(slot);
        kept.triangles.insert(kept.triangles.end(), mover.triangles.begin(), mover.triangles.end());
        kept.corners = std::move(joined_);
        joined_.clear();
        for (uint32_t triangle : mover.triangles) chart_of_[triangle] = keep;
        mover.triangles.clear();
        mover.corners.clear();
        root_[size_t(move)] = keep;
        padded_area_[size_t(keep)] = joined_area;
        ++version_[size_t(keep)];
    }

    const MeshAnalysis& analysis_;
    const std::vector<TriangleInfo>& triangles_;
    std::vector<int64_t>& chart_of_;
    std::vector<Chart>& charts_;
    const double texels_per_metre_;
    const int padding_;
    const double snap_tolerance_;
    std::vector<uint32_t> slot_of_;    // a triangle's slot in its chart's triangle list
    std::vector<double> padded_area_;  // each chart's padded texels (paddedTexelArea) as it is now
    double total_padded_area_ = 0.0;   // of all charts before joining
    std::vector<int64_t> root_;        // the chart each chart was joined into (itself while whole)
    std::vector<uint32_t> version_;    // bumped when a chart grows: a refused pair may now join
    std::unordered_map<uint64_t, uint64_t> tried_;  // pair key -> both charts' versions when last refused
    std::vector<glm::dvec2> moved_, joined_;        // the moved chart's corners unfolded; the kept ones then those
    std::unordered_map<uint32_t, glm::dvec2> seam_target_;  // welded vertex -> where the kept chart has it
};

}  // namespace

void unfoldAcrossSharpEdges(const MeshAnalysis& analysis, std::vector<int64_t>& chart_of, std::vector<Chart>& charts,
                            double texels_per_metre, int padding, double snap_tolerance) {
    ChartPairs pairs = findSeams(analysis, chart_of);
    ChartUnfolder unfolder(analysis, chart_of, charts, texels_per_metre, padding, snap_tolerance);
    unfolder.joinAll(pairs);
    unfolder.renumber();
}

}  // namespace gusuku::bake::detail

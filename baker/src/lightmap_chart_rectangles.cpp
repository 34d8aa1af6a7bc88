// Phase 6 of generateLightmapCharts (lightmap_charting.h): turn each chart in its plane to its smallest bounding
// rectangle; the same measure (paddedTexelArea) judges phase 5's joins.

#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "lightmap_charting.h"
#include "lightmap_pack.h"

namespace gusuku::bake::detail {
namespace {

constexpr int kRotationSteps = 18;  // 5 degree steps over a quarter turn: a rectangle repeats after 90 degrees

glm::dvec2 turned(const glm::dvec2& point, double cos_angle, double sin_angle) {
    return glm::dvec2(cos_angle * point.x + sin_angle * point.y, -sin_angle * point.x + cos_angle * point.y);
}

}  // namespace

RectangleFit smallestRectangle(const std::vector<glm::dvec2>& points) {
    RectangleFit best;
    double best_area = INFINITY;
    for (int step = 0; step < kRotationSteps; ++step) {
        const double angle = (std::numbers::pi / 2.0) * step / kRotationSteps;
        const double c = std::cos(angle), s = std::sin(angle);
        glm::dvec2 min(INFINITY), max(-INFINITY);
        for (const glm::dvec2& point : points) {
            const glm::dvec2 flat = turned(point, c, s);
            min = glm::min(min, flat);
            max = glm::max(max, flat);
        }
        const double area = (max.x - min.x) * (max.y - min.y);
        if (area < best_area) {
            best_area = area;
            best = RectangleFit{angle, min, max};
        }
    }
    return best;
}

// Texels a chart's smallest rectangle takes at the requested density with its gutter: what joining charts saves.
double paddedTexelArea(const RectangleFit& fit, double texels_per_metre, int padding) {
    const glm::ivec2 inner = detail::innerTexelSize(fit.max - fit.min, texels_per_metre);
    return double(inner.x + 2 * padding) * double(inner.y + 2 * padding);
}

// Phase 6: turn each chart in its plane to its smallest bounding rectangle (fewer wasted texels), after making
// the corners a welded vertex has within snap_tolerance in a chart one point (an unfolded seam's two sides then
// share their uv1 exactly, as one chart). Sets each chart's corners and min/max; returns the rectangles' extents
// in metres.
std::vector<glm::dvec2> fitChartRectangles(const std::vector<TriangleInfo>& triangles, std::vector<Chart>& charts,
                                           double snap_tolerance) {
    std::vector<glm::dvec2> extents(charts.size());
    std::unordered_map<uint32_t, std::vector<glm::dvec2>> points_of_welded;
    for (size_t chart_index = 0; chart_index < charts.size(); ++chart_index) {
        Chart& chart = charts[chart_index];
        points_of_welded.clear();
        for (size_t slot = 0; slot < chart.triangles.size(); ++slot)
            for (int i = 0; i < 3; ++i) {
                glm::dvec2& corner = chart.corners[slot * 3 + size_t(i)];
                std::vector<glm::dvec2>& points = points_of_welded[triangles[chart.triangles[slot]].welded[i]];
                bool snapped = false;
                for (const glm::dvec2& point : points)
                    if (glm::length(point - corner) <= snap_tolerance) {
                        corner = point;
                        snapped = true;
                        break;
                    }
                if (!snapped) points.push_back(corner);
            }
        const RectangleFit fit = smallestRectangle(chart.corners);
        const double c = std::cos(fit.angle), s = std::sin(fit.angle);
        for (glm::dvec2& corner : chart.corners) corner = turned(corner, c, s);
        chart.min = fit.min;
        chart.max = fit.max;
        extents[chart_index] = chart.max - chart.min;
    }
    return extents;
}

}  // namespace gusuku::bake::detail

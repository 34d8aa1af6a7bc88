#pragma once
// A small SVG chart writer for gusuku-bench: points and lines in series, a linear or log-10 x axis, a linear y
// axis from 0, labelled reference lines (the goals). Plain SVG 1.1 text, no scripts, no fonts beyond sans-serif.

#include <string>
#include <vector>

namespace gusuku::bench {

struct ChartPoint {
    double x = 0.0, y = 0.0;
    std::string label;  ///< drawn beside the point; may be empty
};

struct ChartSeries {
    std::string name;     ///< in the legend
    std::string colour;   ///< any SVG colour, "#1f77b4"
    std::vector<ChartPoint> points;
    bool connect = false; ///< join the points in order with a line
};

struct ChartReference {
    double value = 0.0;   ///< x for a vertical line, y for a horizontal one
    std::string label;
    bool vertical = false;
    std::string colour = "#888888";
};

struct Chart {
    std::string title;
    std::string x_label, y_label;
    bool log_x = false;
    std::vector<ChartSeries> series;
    std::vector<ChartReference> references;
    int width = 900, height = 560;
};

/// The chart as an SVG document. Axes span the data and the reference lines with a margin (log x: whole decades).
/// Non-finite or (log x) non-positive values are left out.
std::string renderSvgChart(const Chart& chart);

/// Escapes &, <, > and quotes for SVG text.
std::string escapeXml(const std::string& text);

}  // namespace gusuku::bench

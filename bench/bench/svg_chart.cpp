// SVG charts for gusuku-bench (see svg_chart.h).

#include "svg_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace gusuku::bench {

std::string escapeXml(const std::string& text) {
    std::string escaped;
    for (char c : text) {
        switch (c) {
            case '&': escaped += "&amp;"; break;
            case '<': escaped += "&lt;"; break;
            case '>': escaped += "&gt;"; break;
            case '"': escaped += "&quot;"; break;
            default: escaped += c;
        }
    }
    return escaped;
}

namespace {

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", value);
    return text;
}

std::string tickText(double value) {
    char text[32];
    if (std::abs(value) >= 100 || value == std::round(value)) std::snprintf(text, sizeof text, "%g", value);
    else std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

}  // namespace

std::string renderSvgChart(const Chart& chart) {
    auto usableX = [&](double x) { return std::isfinite(x) && (!chart.log_x || x > 0.0); };
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_max = 0.0;
    for (const ChartSeries& series : chart.series)
        for (const ChartPoint& point : series.points)
            if (usableX(point.x) && std::isfinite(point.y)) {
                x_min = std::min(x_min, point.x);
                x_max = std::max(x_max, point.x);
                y_max = std::max(y_max, point.y);
            }
    for (const ChartReference& reference : chart.references) {
        if (reference.vertical && usableX(reference.value)) {
            x_min = std::min(x_min, reference.value);
            x_max = std::max(x_max, reference.value);
        } else if (!reference.vertical && std::isfinite(reference.value)) {
            y_max = std::max(y_max, reference.value);
        }
    }
    if (!(x_min <= x_max)) x_min = chart.log_x ? 1.0 : 0.0, x_max = chart.log_x ? 10.0 : 1.0;
    if (chart.log_x) {
        x_min = std::pow(10.0, std::floor(std::log10(x_min)));
        x_max = std::pow(10.0, std::ceil(std::log10(x_max)));
        if (x_max <= x_min) x_max = x_min * 10.0;
    } else if (x_max <= x_min) {
        x_max = x_min + 1.0;
    }
    y_max = y_max > 0.0 ? y_max * 1.1 : 1.0;

    const double left = 70, right = chart.width - 230, top = 40, bottom = chart.height - 55;
    auto px = [&](double x) {
        const double t = chart.log_x ? (std::log10(x) - std::log10(x_min)) / (std::log10(x_max) - std::log10(x_min))
                                     : (x - x_min) / (x_max - x_min);
        return left + t * (right - left);
    };
    auto py = [&](double y) { return bottom - y / y_max * (bottom - top); };

    std::ostringstream svg;
    svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\""
        << chart.width << "\" height=\"" << chart.height << "\" viewBox=\"0 0 " << chart.width << ' '
        << chart.height << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"" << chart.width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
        << escapeXml(chart.title) << "</text>\n";
    // Grid and ticks.
    std::vector<double> x_ticks;
    if (chart.log_x) {
        for (double decade = x_min; decade <= x_max * 1.0001; decade *= 10.0) x_ticks.push_back(decade);
    } else {
        for (int i = 0; i <= 6; ++i) x_ticks.push_back(x_min + (x_max - x_min) * i / 6.0);
    }
    for (double tick : x_ticks)
        svg << "<line x1=\"" << number(px(tick)) << "\" y1=\"" << top << "\" x2=\"" << number(px(tick)) << "\" y2=\""
            << bottom << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << number(px(tick)) << "\" y=\"" << bottom + 16
            << "\" text-anchor=\"middle\">" << tickText(tick) << "</text>\n";
    for (int i = 0; i <= 5; ++i) {
        const double tick = y_max * i / 5.5;
        svg << "<line x1=\"" << left << "\" y1=\"" << number(py(tick)) << "\" x2=\"" << right << "\" y2=\""
            << number(py(tick)) << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << left - 6 << "\" y=\""
            << number(py(tick) + 4) << "\" text-anchor=\"end\">" << tickText(tick) << "</text>\n";
    }
    svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
        << bottom - top << "\" fill=\"none\" stroke=\"black\"/>\n";
    svg << "<text x=\"" << (left + right) / 2 << "\" y=\"" << chart.height - 15 << "\" text-anchor=\"middle\">"
        << escapeXml(chart.x_label) << "</text>\n";
    svg << "<text transform=\"translate(18," << (top + bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << escapeXml(chart.y_label) << "</text>\n";
    // Reference lines.
    for (const ChartReference& reference : chart.references) {
        if (reference.vertical) {
            if (!usableX(reference.value)) continue;
            const double x = px(reference.value);
            svg << "<line x1=\"" << number(x) << "\" y1=\"" << top << "\" x2=\"" << number(x) << "\" y2=\"" << bottom
                << "\" stroke=\"" << reference.colour << "\" stroke-dasharray=\"5,4\"/>\n<text transform=\"translate("
                << number(x + 4) << ',' << top + 6 << ") rotate(90)\" fill=\"" << reference.colour
                << "\" font-size=\"11\">" << escapeXml(reference.label) << "</text>\n";
        } else {
            if (!std::isfinite(reference.value)) continue;
            const double y = py(reference.value);
            svg << "<line x1=\"" << left << "\" y1=\"" << number(y) << "\" x2=\"" << right << "\" y2=\"" << number(y)
                << "\" stroke=\"" << reference.colour << "\" stroke-dasharray=\"5,4\"/>\n<text x=\"" << right - 4
                << "\" y=\"" << number(y - 4) << "\" text-anchor=\"end\" fill=\"" << reference.colour
                << "\" font-size=\"11\">" << escapeXml(reference.label) << "</text>\n";
        }
    }
    // Series, then the legend.
    int legend_row = 0;
    for (const ChartSeries& series : chart.series) {
        std::string path;
        for (const ChartPoint& point : series.points) {
            if (!usableX(point.x) || !std::isfinite(point.y)) continue;
            path += (path.empty() ? "M" : " L") + number(px(point.x)) + "," + number(py(point.y));
            svg << "<circle cx=\"" << number(px(point.x)) << "\" cy=\"" << number(py(point.y)) << "\" r=\"4\" fill=\""
                << series.colour << "\"/>\n";
            if (!point.label.empty())
                svg << "<text x=\"" << number(px(point.x) + 6) << "\" y=\"" << number(py(point.y) - 6)
                    << "\" font-size=\"10\" fill=\"" << series.colour << "\">" << escapeXml(point.label) << "</text>\n";
        }
        if (series.connect && !path.empty())
            svg << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << series.colour << "\" stroke-width=\"1.5\"/>\n";
        const double legend_y = top + 10 + 18 * legend_row++;
        svg << "<circle cx=\"" << right + 20 << "\" cy=\"" << legend_y << "\" r=\"4\" fill=\"" << series.colour
            << "\"/>\n<text x=\"" << right + 30 << "\" y=\"" << legend_y + 4 << "\">" << escapeXml(series.name)
            << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace gusuku::bench

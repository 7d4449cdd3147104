#include "report/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "util/file.hpp"
#include "util/xml_escape.hpp"

namespace wp {
namespace {

// Colour-blind-safe palette (Okabe and Ito).
constexpr std::array<const char*, 7> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                 "#E69F00", "#56B4E9", "#000000"};

std::string fixed(double value, int decimals = 1) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// A tick label for 10^exponent * mantissa: plain decimals from 0.001 to 10000,
// otherwise "2e-5" style.
std::string tick_text(int exponent, int mantissa) {
    if (exponent >= -3 && exponent <= 4) {
        const double value = mantissa * std::pow(10.0, exponent);
        return fixed(value, std::max(0, -exponent));
    }
    char text[32];
    std::snprintf(text, sizeof text, "%de%d", mantissa, exponent);
    return text;
}

bool plottable(double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && x > 0.0 && y > 0.0;
}

// A log10 axis range from the data, padded and never empty.
struct Range {
    double lo = 0.0, hi = 1.0;
    void fit(double min_log, double max_log) {
        double span = max_log - min_log;
        if (span < 0.3) { // a single value or a very narrow range: show about a decade
            const double mid = 0.5 * (min_log + max_log);
            min_log = mid - 0.5;
            max_log = mid + 0.5;
            span = 1.0;
        }
        lo = min_log - 0.04 * span;
        hi = max_log + 0.04 * span;
    }
};

// Ticks of a log axis: (log10 value, label or empty for a minor tick).
std::vector<std::pair<double, std::string>> ticks(const Range& range) {
    const int first = static_cast<int>(std::floor(range.lo));
    const int last = static_cast<int>(std::ceil(range.hi));
    int decades_inside = 0;
    for (int e = first; e <= last; ++e)
        if (e >= range.lo && e <= range.hi)
            ++decades_inside;
    // With fewer than three labelled decades, also label 2x and 5x.
    const bool label_between = decades_inside < 3;
    std::vector<std::pair<double, std::string>> out;
    for (int e = first; e <= last; ++e) {
        for (int m = 1; m <= 9; ++m) {
            const double v = e + std::log10(static_cast<double>(m));
            if (v < range.lo || v > range.hi)
                continue;
            const bool labelled = m == 1 || (label_between && (m == 2 || m == 5));
            out.emplace_back(v, labelled ? tick_text(e, m) : std::string());
        }
    }
    return out;
}

} // namespace

PlotSeries slope_line(double slope, double x0, double y0, double x_min, double x_max,
                      std::string label) {
    PlotSeries line;
    line.label = std::move(label);
    line.colour = "#888888";
    line.dashed = true;
    line.markers = false;
    for (double x : {x_min, x_max}) {
        line.x.push_back(x);
        line.y.push_back(y0 * std::pow(x / x0, slope));
    }
    return line;
}

std::string render_svg(const LogLogPlot& plot) {
    double min_x = HUGE_VAL, max_x = -HUGE_VAL, min_y = HUGE_VAL, max_y = -HUGE_VAL;
    for (const PlotSeries& s : plot.series) {
        if (s.x.size() != s.y.size())
            throw std::invalid_argument("plot series '" + s.label + "': x and y differ in length");
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            if (!plottable(s.x[i], s.y[i]))
                continue;
            min_x = std::min(min_x, std::log10(s.x[i]));
            max_x = std::max(max_x, std::log10(s.x[i]));
            min_y = std::min(min_y, std::log10(s.y[i]));
            max_y = std::max(max_y, std::log10(s.y[i]));
        }
    }
    if (!(min_x <= max_x))
        throw std::invalid_argument("plot has no point with positive, finite coordinates");
    Range rx, ry;
    rx.fit(min_x, max_x);
    ry.fit(min_y, max_y);

    const double left = 84, right = 24, top = plot.title.empty() ? 20 : 44, bottom = 64;
    const double w = plot.width - left - right, h = plot.height - top - bottom;
    auto px = [&](double lx) { return left + (lx - rx.lo) / (rx.hi - rx.lo) * w; };
    auto py = [&](double ly) { return top + (ry.hi - ly) / (ry.hi - ry.lo) * h; };

    std::string svg;
    svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(plot.width) +
           "\" height=\"" + std::to_string(plot.height) + "\" viewBox=\"0 0 " +
           std::to_string(plot.width) + " " + std::to_string(plot.height) +
           "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n";
    svg += "<rect x=\"0\" y=\"0\" width=\"" + std::to_string(plot.width) + "\" height=\"" +
           std::to_string(plot.height) + "\" fill=\"white\"/>\n";
    if (!plot.title.empty())
        svg += "<text x=\"" + fixed(left + w / 2) +
               "\" y=\"26\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">" +
               xml_escape(plot.title) + "</text>\n";

    // Grid and ticks.
    svg += "<g stroke-width=\"1\">\n";
    for (const auto& [v, text] : ticks(rx)) {
        const double x = px(v);
        if (!text.empty())
            svg += "<line x1=\"" + fixed(x) + "\" y1=\"" + fixed(top) + "\" x2=\"" + fixed(x) +
                   "\" y2=\"" + fixed(top + h) + "\" stroke=\"#e4e4e4\"/>\n";
        const double len = text.empty() ? 4 : 7;
        svg += "<line x1=\"" + fixed(x) + "\" y1=\"" + fixed(top + h) + "\" x2=\"" + fixed(x) +
               "\" y2=\"" + fixed(top + h + len) + "\" stroke=\"#333\"/>\n";
        if (!text.empty())
            svg += "<text x=\"" + fixed(x) + "\" y=\"" + fixed(top + h + 22) +
                   "\" text-anchor=\"middle\" stroke=\"none\">" + text + "</text>\n";
    }
    for (const auto& [v, text] : ticks(ry)) {
        const double y = py(v);
        if (!text.empty())
            svg += "<line x1=\"" + fixed(left) + "\" y1=\"" + fixed(y) + "\" x2=\"" +
                   fixed(left + w) + "\" y2=\"" + fixed(y) + "\" stroke=\"#e4e4e4\"/>\n";
        const double len = text.empty() ? 4 : 7;
        svg += "<line x1=\"" + fixed(left - len) + "\" y1=\"" + fixed(y) + "\" x2=\"" +
               fixed(left) + "\" y2=\"" + fixed(y) + "\" stroke=\"#333\"/>\n";
        if (!text.empty())
            svg += "<text x=\"" + fixed(left - 10) + "\" y=\"" + fixed(y + 4) +
                   "\" text-anchor=\"end\" stroke=\"none\">" + text + "</text>\n";
    }
    svg += "</g>\n";
    svg += "<rect x=\"" + fixed(left) + "\" y=\"" + fixed(top) + "\" width=\"" + fixed(w) +
           "\" height=\"" + fixed(h) + "\" fill=\"none\" stroke=\"#333\"/>\n";
    svg += "<text x=\"" + fixed(left + w / 2) + "\" y=\"" + fixed(plot.height - 16.0) +
           "\" text-anchor=\"middle\">" + xml_escape(plot.x_label) + "</text>\n";
    svg += "<text transform=\"translate(20 " + fixed(top + h / 2) +
           ") rotate(-90)\" text-anchor=\"middle\">" + xml_escape(plot.y_label) + "</text>\n";

    // Series, clipped to the plot area.
    svg += "<defs><clipPath id=\"area\"><rect x=\"" + fixed(left) + "\" y=\"" + fixed(top) +
           "\" width=\"" + fixed(w) + "\" height=\"" + fixed(h) + "\"/></clipPath></defs>\n";
    std::vector<std::string> colours;
    std::size_t next_colour = 0;
    for (const PlotSeries& s : plot.series) {
        const std::string colour =
            s.colour.empty() ? kPalette[next_colour++ % kPalette.size()] : s.colour;
        colours.push_back(colour);
        std::string points;
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (plottable(s.x[i], s.y[i]))
                points +=
                    fixed(px(std::log10(s.x[i])), 2) + "," + fixed(py(std::log10(s.y[i])), 2) + " ";
        if (!points.empty())
            points.pop_back();
        svg += "<g clip-path=\"url(#area)\">\n<polyline fill=\"none\" stroke=\"" + colour +
               "\" stroke-width=\"2\"" +
               (s.dashed ? std::string(" stroke-dasharray=\"7 5\"") : std::string()) +
               " points=\"" + points + "\"/>\n";
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            if (!plottable(s.x[i], s.y[i]))
                continue;
            const double x = px(std::log10(s.x[i])), y = py(std::log10(s.y[i]));
            if (s.markers)
                svg += "<circle cx=\"" + fixed(x, 2) + "\" cy=\"" + fixed(y, 2) +
                       "\" r=\"3.5\" fill=\"" + colour + "\"/>\n";
            if (i < s.point_labels.size() && !s.point_labels[i].empty()) {
                // Right of the point, or left of it near the right edge.
                const bool left_side = x > left + w - 60;
                svg += "<text x=\"" + fixed(left_side ? x - 5 : x + 5) + "\" y=\"" + fixed(y - 6) +
                       "\" font-size=\"10\" fill=\"" + colour + "\"" +
                       (left_side ? " text-anchor=\"end\"" : "") + ">" +
                       xml_escape(s.point_labels[i]) + "</text>\n";
            }
        }
        svg += "</g>\n";
    }

    // Legend in the top-right corner of the plot area.
    std::size_t entries = 0, longest = 0;
    for (const PlotSeries& s : plot.series)
        if (!s.label.empty()) {
            ++entries;
            longest = std::max(longest, s.label.size());
        }
    if (entries > 0) {
        const double row = 18, lw = 44 + 7.0 * static_cast<double>(longest);
        const double lx = left + w - lw - 10, ly = top + 10;
        svg += "<g>\n<rect x=\"" + fixed(lx) + "\" y=\"" + fixed(ly) + "\" width=\"" + fixed(lw) +
               "\" height=\"" + fixed(row * static_cast<double>(entries) + 8) +
               "\" fill=\"white\" fill-opacity=\"0.9\" stroke=\"#999\"/>\n";
        double y = ly + 4 + row / 2;
        for (std::size_t i = 0; i < plot.series.size(); ++i) {
            const PlotSeries& s = plot.series[i];
            if (s.label.empty())
                continue;
            svg += "<line x1=\"" + fixed(lx + 8) + "\" y1=\"" + fixed(y) + "\" x2=\"" +
                   fixed(lx + 34) + "\" y2=\"" + fixed(y) + "\" stroke=\"" + colours[i] +
                   "\" stroke-width=\"2\"" +
                   (s.dashed ? std::string(" stroke-dasharray=\"7 5\"") : std::string()) + "/>\n";
            svg += "<text x=\"" + fixed(lx + 40) + "\" y=\"" + fixed(y + 4) + "\">" +
                   xml_escape(s.label) + "</text>\n";
            y += row;
        }
        svg += "</g>\n";
    }
    svg += "</svg>\n";
    return svg;
}

void write_svg(const std::filesystem::path& path, const LogLogPlot& plot) {
    const std::string text = render_svg(plot);
    write_bytes_atomically(path, text.data(), text.size());
}

} // namespace wp

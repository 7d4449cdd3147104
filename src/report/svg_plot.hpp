// A small log-log line plot written as SVG: convergence curves (error against
// time), without a plotting dependency.
//
// Each series becomes one <polyline> (plus a <circle> per point when it has
// markers); axes have decade ticks with labels, minor ticks at 2..9, grid
// lines, axis titles and a legend. The output is self-contained XML that any
// browser or the Markdown viewers of GitHub/GitLab show.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace wp {

struct PlotSeries {
    std::string label;     // legend text; empty: not in the legend
    std::vector<double> x; // points with a non-positive or non-finite coordinate are skipped
    std::vector<double> y;
    std::string colour; // any SVG colour; empty: the next of a fixed palette
    bool dashed = false;
    bool markers = true;
    std::vector<std::string> point_labels; // optional text beside each point (e.g. "64 spp")
};

struct LogLogPlot {
    std::string title;
    std::string x_label;
    std::string y_label;
    int width = 760;
    int height = 520;
    std::vector<PlotSeries> series;
};

// The line y = y0 (x / x0)^slope over [x_min, x_max], e.g. the ideal Monte Carlo
// rate (RMSE slope -1/2 against time) through a measured point.
PlotSeries slope_line(double slope, double x0, double y0, double x_min, double x_max,
                      std::string label);

// The SVG document. Throws std::invalid_argument when no series has a plottable point
// or a series' x and y differ in length.
std::string render_svg(const LogLogPlot& plot);

// render_svg written atomically; throws FileError when the file cannot be written.
void write_svg(const std::filesystem::path& path, const LogLogPlot& plot);

} // namespace wp

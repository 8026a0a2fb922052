#pragma once
// Small SVG line charts for the reports the CLI writes (no plotting dependency): labelled axes
// with decade ticks on log scales, one coloured, labelled polyline per series.
#include <string>
#include <vector>

namespace mocapdb::cli {

struct PlotSeries {
    std::string name;
    std::vector<double> x;
    std::vector<double> y;
};

struct PlotSpec {
    std::string title;
    std::string x_label;
    std::string y_label;
    bool log_x = true;
    bool log_y = true;
    std::vector<PlotSeries> series;
    std::string note;  ///< one line under the plot (data, machine, date)
};

/// The SVG document. Points that are not finite (or ≤ 0 on a log axis) are skipped.
std::string render_line_plot(const PlotSpec& spec);

}  // namespace mocapdb::cli

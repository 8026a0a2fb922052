#pragma once
// A small SVG heat map (no plotting dependency): values on a regular 2-D grid drawn as coloured cells
// with a colour bar, labelled axes, and marked points (e.g. the samples of a reliability map).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mocapdb::cli {

struct HeatMapSpec {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::string value_label;
    double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;  ///< centres of the first and last cells
    Eigen::MatrixXd values;                 ///< ny by nx (row 0 = y_lo), finite values are coloured, others grey
    double value_lo = 0.0, value_hi = 1.0;  ///< colour scale range
    std::vector<double> point_x;            ///< marked points (drawn when inside the plot)
    std::vector<double> point_y;
    std::string point_label;  ///< legend text of the points
    std::string note;         ///< one line under the plot
};

/// The SVG document.
std::string render_heat_map(const HeatMapSpec& spec);

}  // namespace mocapdb::cli

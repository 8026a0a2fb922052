#include "svg_heatmap.hpp"

#include "svg_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mocapdb::cli {
namespace {

constexpr double kMapWidth = 760, kMapHeight = 560, kMapLeft = 90, kMapRight = 150, kMapTop = 50, kMapBottom = 90;

using svg::escape;
using svg::label;
using svg::num;

/// Low values red, high values blue (the paper's Figure 8: blue = reliable), through a pale middle.
std::string colour(double f) {
    f = std::clamp(f, 0.0, 1.0);
    const double lo[3] = {215, 48, 39}, mid[3] = {255, 255, 191}, hi[3] = {49, 54, 149};
    double rgb[3];
    for (int k = 0; k < 3; ++k)
        rgb[k] = f < 0.5 ? lo[k] + (mid[k] - lo[k]) * (f / 0.5) : mid[k] + (hi[k] - mid[k]) * ((f - 0.5) / 0.5);
    char buf[16];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(rgb[0])),
                  static_cast<int>(std::lround(rgb[1])), static_cast<int>(std::lround(rgb[2])));
    return buf;
}

}  // namespace

std::string render_heat_map(const HeatMapSpec& s) {
    const Eigen::Index ny = s.values.rows(), nx = s.values.cols();
    const double pw = kMapWidth - kMapLeft - kMapRight, ph = kMapHeight - kMapTop - kMapBottom;
    // Cell edges: half a step beyond the first and last centres.
    const double dx = nx > 1 ? (s.x_hi - s.x_lo) / static_cast<double>(nx - 1) : 1.0;
    const double dy = ny > 1 ? (s.y_hi - s.y_lo) / static_cast<double>(ny - 1) : 1.0;
    const double x0 = s.x_lo - 0.5 * dx, x1 = s.x_hi + 0.5 * dx, y0 = s.y_lo - 0.5 * dy, y1 = s.y_hi + 0.5 * dy;
    const auto px = [&](double x) { return kMapLeft + (x - x0) / (x1 - x0) * pw; };
    const auto py = [&](double y) { return kMapTop + ph - (y - y0) / (y1 - y0) * ph; };
    const double range = s.value_hi > s.value_lo ? s.value_hi - s.value_lo : 1.0;

    std::string o;
    o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kMapWidth) + "\" height=\"" + num(kMapHeight) +
         "\" font-family=\"sans-serif\" font-size=\"13\">\n";
    o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o += "<text x=\"" + num(kMapWidth / 2) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" + escape(s.title) +
         "</text>\n";
    const double cw = pw / static_cast<double>(std::max<Eigen::Index>(nx, 1));
    const double ch = ph / static_cast<double>(std::max<Eigen::Index>(ny, 1));
    for (Eigen::Index j = 0; j < ny; ++j)
        for (Eigen::Index i = 0; i < nx; ++i) {
            const double v = s.values(j, i);
            const std::string fill = std::isfinite(v) ? colour((v - s.value_lo) / range) : "#bbbbbb";
            o += "<rect x=\"" + num(kMapLeft + static_cast<double>(i) * cw) + "\" y=\"" +
                 num(kMapTop + ph - static_cast<double>(j + 1) * ch) + "\" width=\"" + num(cw + 0.3) + "\" height=\"" +
                 num(ch + 0.3) + "\" fill=\"" + fill + "\"/>\n";
        }
    o += "<rect x=\"" + num(kMapLeft) + "\" y=\"" + num(kMapTop) + "\" width=\"" + num(pw) + "\" height=\"" + num(ph) +
         "\" fill=\"none\" stroke=\"black\"/>\n";
    // Axis ticks: 5 intervals on each axis.
    for (int k = 0; k <= 4; ++k) {
        const double xv = x0 + (x1 - x0) * k / 4.0, yv = y0 + (y1 - y0) * k / 4.0;
        o += "<line x1=\"" + num(px(xv)) + "\" y1=\"" + num(kMapTop + ph) + "\" x2=\"" + num(px(xv)) + "\" y2=\"" +
             num(kMapTop + ph + 6) + "\" stroke=\"black\"/>\n";
        o += "<text x=\"" + num(px(xv)) + "\" y=\"" + num(kMapTop + ph + 22) + "\" text-anchor=\"middle\">" +
             label(xv) + "</text>\n";
        o += "<line x1=\"" + num(kMapLeft - 6) + "\" y1=\"" + num(py(yv)) + "\" x2=\"" + num(kMapLeft) + "\" y2=\"" +
             num(py(yv)) + "\" stroke=\"black\"/>\n";
        o += "<text x=\"" + num(kMapLeft - 10) + "\" y=\"" + num(py(yv) + 4) + "\" text-anchor=\"end\">" + label(yv) +
             "</text>\n";
    }
    o += "<text x=\"" + num(kMapLeft + pw / 2) + "\" y=\"" + num(kMapTop + ph + 48) + "\" text-anchor=\"middle\">" +
         escape(s.x_label) + "</text>\n";
    o += "<text transform=\"translate(24," + num(kMapTop + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         escape(s.y_label) + "</text>\n";
    // Points.
    for (std::size_t k = 0; k < s.point_x.size() && k < s.point_y.size(); ++k) {
        const double x = s.point_x[k], y = s.point_y[k];
        if (!(x >= x0 && x <= x1 && y >= y0 && y <= y1)) continue;
        o += "<circle cx=\"" + num(px(x)) + "\" cy=\"" + num(py(y)) +
             "\" r=\"4\" fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
    }
    // Colour bar.
    const double bx = kMapLeft + pw + 30, bw = 20;
    for (int k = 0; k < 50; ++k) {
        const double f = (k + 0.5) / 50.0;
        o += "<rect x=\"" + num(bx) + "\" y=\"" + num(kMapTop + ph - (k + 1) * ph / 50.0) + "\" width=\"" + num(bw) +
             "\" height=\"" + num(ph / 50.0 + 0.3) + "\" fill=\"" + colour(f) + "\"/>\n";
    }
    o += "<rect x=\"" + num(bx) + "\" y=\"" + num(kMapTop) + "\" width=\"" + num(bw) + "\" height=\"" + num(ph) +
         "\" fill=\"none\" stroke=\"black\"/>\n";
    for (int k = 0; k <= 4; ++k) {
        const double v = s.value_lo + (s.value_hi - s.value_lo) * k / 4.0;
        o += "<text x=\"" + num(bx + bw + 6) + "\" y=\"" + num(kMapTop + ph - ph * k / 4.0 + 4) + "\">" + label(v) +
             "</text>\n";
    }
    o += "<text x=\"" + num(bx) + "\" y=\"" + num(kMapTop - 10) + "\">" + escape(s.value_label) + "</text>\n";
    if (!s.point_label.empty()) {
        o += "<circle cx=\"" + num(kMapLeft + 8) + "\" cy=\"" + num(kMapHeight - 22) +
             "\" r=\"4\" fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
        o += "<text x=\"" + num(kMapLeft + 18) + "\" y=\"" + num(kMapHeight - 18) + "\">" + escape(s.point_label) +
             "</text>\n";
    }
    if (!s.note.empty())
        o += "<text x=\"" + num(kMapWidth - 10) + "\" y=\"" + num(kMapHeight - 18) +
             "\" text-anchor=\"end\" font-size=\"11\" fill=\"#555\">" + escape(s.note) + "</text>\n";
    o += "</svg>\n";
    return o;
}

}  // namespace mocapdb::cli

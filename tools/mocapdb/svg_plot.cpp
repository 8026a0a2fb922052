#include "svg_plot.hpp"

#include "svg_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mocapdb::cli {
namespace {

constexpr double kPlotWidth = 760, kPlotHeight = 520, kPlotLeft = 90, kPlotRight = 190, kPlotTop = 50, kPlotBottom = 80;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

using svg::escape;
using svg::num;

std::string tick_label(double v) { return svg::label(v, 6); }

struct Axis {
    double lo = 0, hi = 1;
    bool log = true;
    double map(double v, double from, double to) const {
        const double a = log ? std::log10(v) : v;
        const double l = log ? std::log10(lo) : lo, h = log ? std::log10(hi) : hi;
        return from + (a - l) / (h - l) * (to - from);
    }
    std::vector<double> ticks() const {
        std::vector<double> t;
        if (log) {
            for (double d = std::floor(std::log10(lo)); d <= std::ceil(std::log10(hi)); d += 1.0) {
                const double v = std::pow(10.0, d);
                if (v >= lo * 0.999 && v <= hi * 1.001) t.push_back(v);
            }
        } else {
            const double step = std::pow(10.0, std::floor(std::log10((hi - lo) / 2)));
            for (double v = std::ceil(lo / step) * step; v <= hi + 1e-12; v += step) t.push_back(v);
        }
        return t;
    }
};

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

Axis fit_axis(const std::vector<PlotSeries>& series, bool x, bool log) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const PlotSeries& s : series)
        for (double v : x ? s.x : s.y)
            if (usable(v, log)) {
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
    Axis a;
    a.log = log;
    if (!std::isfinite(lo)) {
        a.lo = log ? 1 : 0;
        a.hi = log ? 10 : 1;
        return a;
    }
    if (log) {
        a.lo = std::pow(10.0, std::floor(std::log10(lo)));
        a.hi = std::pow(10.0, std::ceil(std::log10(hi)));
        if (a.hi <= a.lo) a.hi = a.lo * 10;
    } else {
        const double pad = hi > lo ? 0.05 * (hi - lo) : 1.0;
        a.lo = lo - pad;
        a.hi = hi + pad;
    }
    return a;
}

}  // namespace

std::string render_line_plot(const PlotSpec& spec) {
    const Axis ax = fit_axis(spec.series, true, spec.log_x), ay = fit_axis(spec.series, false, spec.log_y);
    const double x0 = kPlotLeft, x1 = kPlotWidth - kPlotRight, y0 = kPlotHeight - kPlotBottom, y1 = kPlotTop;
    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kPlotWidth) + "\" height=\"" +
                      num(kPlotHeight) + "\" viewBox=\"0 0 " + num(kPlotWidth) + " " + num(kPlotHeight) +
                      "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg += "<text x=\"" + num(kPlotWidth / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">" +
           escape(spec.title) + "</text>\n";
    for (double t : ax.ticks()) {
        const double x = ax.map(t, x0, x1);
        svg += "<line x1=\"" + num(x) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(x) + "\" y2=\"" + num(y1) +
               "\" stroke=\"#ddd\"/>\n<text x=\"" + num(x) + "\" y=\"" + num(y0 + 16) + "\" text-anchor=\"middle\">" +
               tick_label(t) + "</text>\n";
    }
    for (double t : ay.ticks()) {
        const double y = ay.map(t, y0, y1);
        svg += "<line x1=\"" + num(x0) + "\" y1=\"" + num(y) + "\" x2=\"" + num(x1) + "\" y2=\"" + num(y) +
               "\" stroke=\"#ddd\"/>\n<text x=\"" + num(x0 - 6) + "\" y=\"" + num(y + 4) + "\" text-anchor=\"end\">" +
               tick_label(t) + "</text>\n";
    }
    svg += "<rect x=\"" + num(x0) + "\" y=\"" + num(y1) + "\" width=\"" + num(x1 - x0) + "\" height=\"" + num(y0 - y1) +
           "\" fill=\"none\" stroke=\"black\"/>\n";
    svg += "<text x=\"" + num((x0 + x1) / 2) + "\" y=\"" + num(y0 + 40) + "\" text-anchor=\"middle\">" +
           escape(spec.x_label) + "</text>\n";
    svg += "<text transform=\"translate(" + num(24) + " " + num((y0 + y1) / 2) +
           ") rotate(-90)\" text-anchor=\"middle\">" + escape(spec.y_label) + "</text>\n";
    for (std::size_t k = 0; k < spec.series.size(); ++k) {
        const PlotSeries& s = spec.series[k];
        const std::string colour = kColours[k % (sizeof kColours / sizeof *kColours)];
        std::vector<std::pair<double, double>> pts;
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
            if (usable(s.x[i], spec.log_x) && usable(s.y[i], spec.log_y))
                pts.emplace_back(ax.map(s.x[i], x0, x1), ay.map(s.y[i], y0, y1));
        std::sort(pts.begin(), pts.end());
        if (pts.size() > 1) {
            svg += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\" points=\"";
            for (const auto& p : pts) svg += num(p.first) + "," + num(p.second) + " ";
            svg += "\"/>\n";
        }
        for (const auto& p : pts)
            svg += "<circle cx=\"" + num(p.first) + "\" cy=\"" + num(p.second) + "\" r=\"3.5\" fill=\"" + colour +
                   "\"/>\n";
        const double ly = y1 + 10 + 20.0 * static_cast<double>(k);
        svg += "<line x1=\"" + num(x1 + 15) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(x1 + 40) + "\" y2=\"" + num(ly) +
               "\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n<text x=\"" + num(x1 + 46) + "\" y=\"" +
               num(ly + 4) + "\">" + escape(s.name) + "</text>\n";
    }
    if (!spec.note.empty())
        svg += "<text x=\"" + num(x0) + "\" y=\"" + num(kPlotHeight - 12) + "\" font-size=\"10\" fill=\"#555\">" +
               escape(spec.note) + "</text>\n";
    svg += "</svg>\n";
    return svg;
}

}  // namespace mocapdb::cli

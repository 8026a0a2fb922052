#pragma once
// Text helpers shared by the SVG writers (svg_plot, svg_heatmap).
#include <cstdio>
#include <string>

namespace mocapdb::cli::svg {

/// s with <, > and & escaped for SVG text and attributes.
inline std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else out += c;
    }
    return out;
}

/// A coordinate with two decimals.
inline std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

/// A tick or legend label (%g with `digits` significant digits).
inline std::string label(double v, int digits = 3) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

}  // namespace mocapdb::cli::svg

// Text helpers of the eval writers (eval_report_parts.hpp) and write_eval_report (eval_report.hpp).
#include "eval_report_parts.hpp"
#include "eval_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "mocapdb/io/text_file.hpp"

namespace mocapdb::cli::eval_report {

// How a set's samples were cut, for the data table.
std::string cycles_note(const eval::EvalSetSpec& spec) {
    if (spec.flight_windows)
        return " (the jump of each clip: 0.5 s before take-off to 0.5 s after landing of its longest flight)";
    if (!spec.gait_cycles) return "";
    if (spec.max_cycles_per_clip == 1)
        return " (one gait cycle per clip, the middle one: every sample starts at the same phase)";
    if (spec.max_cycles_per_clip == 0) return " (every gait cycle of each clip)";
    return " (at most " + std::to_string(spec.max_cycles_per_clip) + " gait cycles per clip, evenly spread)";
}

std::string fmt(double v, int digits) {
    if (!std::isfinite(v)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string fixed(double v, int decimals) {
    if (!std::isfinite(v)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string fmt(const std::optional<double>& v, int digits) { return v ? fmt(*v, digits) : "n/a"; }

std::string fixed(const std::optional<double>& v, int decimals) { return v ? fixed(*v, decimals) : "n/a"; }

std::string percent(const std::optional<double>& value) {
    if (!value) return "";
    return fixed(*value, 0) + " %";
}

void put(const std::filesystem::path& path, const std::string& text) {
    write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::string params_text(const eval::EvalSet& s) {
    std::string out;
    const auto ranges = eval::parameter_ranges(s);
    for (std::size_t k = 0; k < s.set.parameter_names.size(); ++k)
        out += (k ? ", " : "") + s.set.parameter_names[k] + " [" + s.set.parameter_units[k] + "] " +
               fmt(ranges[k].first, 4) + " .. " + fmt(ranges[k].second, 4);
    return out;
}

std::string caption(const RunInfo& info, const eval::EvalSet& s, const std::string& parameters) {
    return "*Data: set `" + s.spec.name + "` (N = " + std::to_string(s.size()) +
           " samples, T = " + std::to_string(s.aligned.frames()) +
           " aligned frames, D = " + std::to_string(s.aligned.dofs()) + " dofs; " + params_text(s) +
           "). Parameters: " + parameters + ". Machine: " + info.machine + ". Date: " + info.date + ".*\n";
}

std::string short_caption(const RunInfo& info, const std::string& data, const std::string& parameters) {
    return "*Data: " + data + ". Parameters: " + parameters + ". Machine: " + info.machine + ". Date: " + info.date +
           ".*\n";
}

std::string svg_note(const RunInfo& info) { return info.date + "; " + info.machine; }

std::string method_label(const eval::MethodSpec& m) {
    if (m.kind != eval::MethodKind::TuckerKriging) return m.name;
    return m.name + " (" + ranks_text(m.ranks) + ")";
}

}  // namespace mocapdb::cli::eval_report

namespace mocapdb::cli {

using namespace eval_report;

void write_eval_report(const EvalResults& e, const std::filesystem::path& out) {
    std::filesystem::create_directories(out);
    for (const SetResults& r : e.sets) {
        const std::string n = r.set->spec.name;
        if (r.has_loo) {
            put(out / ("loo_" + n + ".csv"), loo_csv(r));
            put(out / ("loo_frames_" + n + ".csv"), loo_frames_csv(r));
            put(out / ("loo_" + n + ".svg"), loo_svg(e.info, r, true));
            put(out / ("loo_motion_" + n + ".svg"), loo_svg(e.info, r, false));
        }
        if (r.has_constraint) {
            put(out / ("constraint_" + n + ".csv"), constraint_csv(r));
            put(out / ("reliability_" + n + ".svg"), reliability_svg(e.info, r));
        }
        if (r.has_reduction) {
            put(out / ("reduction_" + n + ".csv"), reduction_csv(r));
            put(out / ("reduction_" + n + ".svg"), reduction_svg(e.info, r));
        }
        if (r.has_compression) {
            put(out / ("compression_" + n + ".csv"), compression_csv(r));
            put(out / ("compression_" + n + ".svg"), compression_svg(e.info, r));
        }
    }
    put(out / "runtime.csv", runtime_csv(e));
    put(out / "runtime.svg", runtime_svg(e.info, e, false));
    put(out / "runtime_build.svg", runtime_svg(e.info, e, true));
    put(out / "results.json", results_json(e));
    put(out / "REPORT.md", report_md(e));
}

}  // namespace mocapdb::cli

// Writers of mocapdb eval's outputs: REPORT.md (tables, figure links, the generated comparison), the
// CSV files, the SVG figures and results.json. Every number shown comes from EvalResults.
#include "eval_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "json_writer.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/eval/verdicts.hpp"
#include "mocapdb/io/text_file.hpp"
#include "svg_plot.hpp"

namespace mocapdb::cli {
namespace {

using eval::EvalResults;
using eval::RunInfo;
using eval::SetResults;

// How a set's samples were cut, for the data table.
std::string cycles_note(const eval::EvalSetSpec& spec) {
    if (spec.flight_windows) return " (the jump of each clip: 0.5 s before take-off to 0.5 s after landing of its longest flight)";
    if (!spec.gait_cycles) return "";
    if (spec.max_cycles_per_clip == 1) return " (one gait cycle per clip, the middle one: every sample starts at the same phase)";
    if (spec.max_cycles_per_clip == 0) return " (every gait cycle of each clip)";
    return " (at most " + std::to_string(spec.max_cycles_per_clip) + " gait cycles per clip, evenly spread)";
}

std::string fmt(double v, int digits = 3) {
    if (!std::isfinite(v)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string fixed(double v, int decimals = 2) {
    if (!std::isfinite(v)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string percent(double value) {
    if (std::isnan(value)) return "";
    return fixed(value, 0) + " %";
}

void put(const std::filesystem::path& path, const std::string& text) {
    write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::size_t left = 1;  ///< leading text columns (left-aligned)
    std::string str() const {
        std::ostringstream s;
        s << "|";
        for (const auto& h : header) s << " " << h << " |";
        s << "\n|";
        for (std::size_t k = 0; k < header.size(); ++k) s << (k < left ? "---" : "---:") << "|";
        s << "\n";
        for (const auto& r : rows) {
            s << "|";
            for (const auto& c : r) s << " " << c << " |";
            s << "\n";
        }
        return s.str();
    }
};

std::string params_text(const eval::EvalSet& s) {
    std::string out;
    const auto ranges = eval::parameter_ranges(s);
    for (std::size_t k = 0; k < s.set.parameter_names.size(); ++k)
        out += (k ? ", " : "") + s.set.parameter_names[k] + " [" + s.set.parameter_units[k] + "] " + fmt(ranges[k].first, 4) +
               " .. " + fmt(ranges[k].second, 4);
    return out;
}

std::string caption(const RunInfo& info, const eval::EvalSet& s, const std::string& parameters) {
    return "*Data: set `" + s.spec.name + "` (N = " + std::to_string(s.size()) + " samples, T = " +
           std::to_string(s.aligned.frames()) + " aligned frames, D = " + std::to_string(s.aligned.dofs()) +
           " dofs; " + params_text(s) + "). Parameters: " + parameters + ". Machine: " + info.machine + ". Date: " +
           info.date + ".*\n";
}

std::string short_caption(const RunInfo& info, const std::string& data, const std::string& parameters) {
    return "*Data: " + data + ". Parameters: " + parameters + ". Machine: " + info.machine + ". Date: " + info.date + ".*\n";
}

std::string svg_note(const RunInfo& info) { return info.date + "; " + info.machine; }

std::string method_label(const eval::MethodSpec& m) {
    if (m.kind != eval::MethodKind::TuckerKriging) return m.name;
    return m.name + " (" + std::to_string(m.ranks[0]) + "x" + std::to_string(m.ranks[1]) + "x" + std::to_string(m.ranks[2]) + ")";
}

// ---------------------------------------------------------------------------------------------------
// CSV

std::string loo_csv(const SetResults& r) {
    const eval::EvalSet& s = *r.set;
    std::ostringstream o;
    o.precision(9);
    o << "sample,label";
    for (const auto& n : s.set.parameter_names) o << "," << n;
    o << ",method,mean_cm,max_cm,pose_mean_cm,pose_max_cm,duration_error_s,skating_cm_per_s,original_skating_cm_per_s\n";
    for (const auto& m : r.loo.methods)
        for (std::size_t k = 0; k < r.loo.samples.size(); ++k) {
            const Eigen::Index i = r.loo.samples[k];
            const auto kk = static_cast<Eigen::Index>(k);
            o << i << "," << s.labels[static_cast<std::size_t>(i)];
            for (Eigen::Index c = 0; c < s.set.parameters.cols(); ++c) o << "," << s.set.parameters(i, c);
            o << "," << m.method << "," << m.sample_mean_cm(kk) << "," << m.sample_max_cm(kk) << "," << m.sample_pose_mean_cm(kk)
              << "," << m.sample_pose_max_cm(kk) << "," << m.duration_error_s(kk)
              << "," << (m.skating_cm_per_s.size() ? m.skating_cm_per_s(kk) : 0.0) << ","
              << (r.loo.original_skating_cm_per_s.size() ? r.loo.original_skating_cm_per_s(kk) : 0.0) << "\n";
        }
    return o.str();
}

std::string loo_frames_csv(const SetResults& r) {
    std::ostringstream o;
    o.precision(9);
    o << "frame";
    for (const auto& m : r.loo.methods)
        o << "," << m.method << " mean_cm," << m.method << " max_cm," << m.method << " pose_mean_cm";
    o << "\n";
    for (Eigen::Index t = 0; t < r.set->aligned.frames(); ++t) {
        o << t;
        for (const auto& m : r.loo.methods) o << "," << m.frame_mean_cm(t) << "," << m.frame_max_cm(t) << "," << m.frame_pose_mean_cm(t);
        o << "\n";
    }
    return o.str();
}

std::string constraint_csv(const SetResults& r) {
    const eval::EvalSet& s = *r.set;
    const auto& c = r.constraint;
    std::ostringstream o;
    o.precision(9);
    o << "point";
    for (const auto& n : s.set.parameter_names) o << "," << n;
    o << ",rho,method";
    for (const auto& n : s.set.parameter_names) o << ",achieved_" << n;
    o << ",error_normalized,valid\n";
    for (const auto& m : c.methods)
        for (Eigen::Index q = 0; q < c.grid.rows(); ++q) {
            o << q;
            for (Eigen::Index k = 0; k < c.grid.cols(); ++k) o << "," << c.grid(q, k);
            o << "," << m.reliability(q) << "," << m.method;
            for (Eigen::Index k = 0; k < c.grid.cols(); ++k) o << "," << m.achieved(q, k);
            o << "," << m.error(q) << "," << (m.valid[static_cast<std::size_t>(q)] ? 1 : 0) << "\n";
        }
    return o.str();
}

std::string reduction_csv(const SetResults& r) {
    std::ostringstream o;
    o.precision(9);
    o << "kept,max_reliability,greedy_mean_cm,greedy_max_cm,random_mean_cm,greedy_pose_mean_cm,random_pose_mean_cm\n";
    for (const auto& p : r.reduction.points)
        o << p.kept << "," << p.max_reliability << "," << p.greedy_mean_cm << "," << p.greedy_max_cm << "," << p.random_mean_cm
          << "," << p.greedy_pose_mean_cm << "," << p.random_pose_mean_cm << "\n";
    return o.str();
}

std::string ranks_text(const std::vector<long long>& r) {
    std::string s;
    for (std::size_t i = 0; i < r.size(); ++i) s += (i ? "x" : "") + std::to_string(r[i]);
    return s.empty() ? "-" : s;
}

std::string compression_csv(const SetResults& r) {
    std::ostringstream o;
    o.precision(9);
    o << "method,target_cm,target_met,ranks,setting,bytes,ratio,rmse_cm,mean_cm,max_cm,precompute_s,us_per_pose,access\n";
    for (const auto& row : r.compression.rows)
        o << row.method << "," << row.target_cm << "," << (row.target_met ? 1 : 0) << "," << ranks_text(row.ranks) << ","
          << row.setting << "," << row.bytes << "," << row.ratio << "," << row.stats.rmse_cm << "," << row.stats.mean_cm
          << "," << row.stats.max_cm << "," << row.precompute_s << "," << row.us_per_pose << "," << row.access << "\n";
    return o.str();
}

std::string runtime_csv(const EvalResults& e) {
    std::ostringstream o;
    o.precision(9);
    o << "method,samples,frames,build_seconds,build_us_per_frame,synth_us_per_frame\n";
    for (const auto& row : e.runtime)
        o << row.method << "," << row.samples << "," << row.frames << "," << row.build_seconds << "," << row.build_us_per_frame
          << "," << row.synth_us_per_frame << "\n";
    return o.str();
}

// ---------------------------------------------------------------------------------------------------
// SVG

std::string loo_svg(const RunInfo& info, const SetResults& r, bool pose) {
    PlotSpec p;
    p.title = "Leave-one-out prediction on " + r.set->spec.name + ": " + (pose ? "root-relative pose" : "motion (with root trajectory)") +
              " error over time";
    p.x_label = "aligned frame";
    p.y_label = "mean joint-position error over left-out samples (cm)";
    p.log_x = false;
    p.log_y = false;
    for (const auto& m : r.loo.methods) {
        PlotSeries s{m.method, {}, {}};
        for (Eigen::Index t = 0; t < m.frame_mean_cm.size(); ++t) {
            s.x.push_back(static_cast<double>(t));
            s.y.push_back(pose ? m.frame_pose_mean_cm(t) : m.frame_mean_cm(t));
        }
        p.series.push_back(s);
    }
    p.note = "N = " + std::to_string(r.set->size()) + "; " + svg_note(info);
    return render_line_plot(p);
}

std::string reliability_svg(const RunInfo& info, const SetResults& r) {
    PlotSpec p;
    p.title = "Reliability against constraint error on " + r.set->spec.name;
    p.x_label = "reliability rho(c) (bins of 0.1)";
    p.y_label = "mean |c - c_hat| in the bin (normalized units)";
    p.log_x = false;
    p.log_y = false;
    const auto& c = r.constraint;
    for (const auto& m : c.methods) {
        PlotSeries s{m.method, {}, {}};
        for (const auto& [centre, error] : eval::error_by_reliability(m, 10)) {
            s.x.push_back(centre);
            s.y.push_back(error);
        }
        p.series.push_back(s);
    }
    p.note = std::to_string(c.grid.rows()) + " grid points; " + svg_note(info);
    return render_line_plot(p);
}

std::string reduction_svg(const RunInfo& info, const SetResults& r) {
    PlotSpec p;
    p.title = "Sample reduction on " + r.set->spec.name + ": kept samples against error";
    p.x_label = "samples kept";
    p.y_label = "mean root-relative pose error of the removed samples (cm)";
    p.log_x = false;
    p.log_y = false;
    PlotSeries g{"greedy by reliability", {}, {}}, rnd{"random removal", {}, {}};
    for (const auto& pt : r.reduction.points) {
        g.x.push_back(static_cast<double>(pt.kept));
        g.y.push_back(pt.greedy_pose_mean_cm);
        rnd.x.push_back(static_cast<double>(pt.kept));
        rnd.y.push_back(pt.random_pose_mean_cm);
    }
    p.series = {g};
    if (r.reduction_options.random_orders > 0) p.series.push_back(rnd);
    p.note = "tau = " + fmt(r.reduction_options.tau) + " keeps " + std::to_string(r.reduction.kept_at_tau) + " of " +
             std::to_string(r.set->size()) + "; " + svg_note(info);
    return render_line_plot(p);
}

std::string compression_svg(const RunInfo& info, const SetResults& r) {
    PlotSpec p;
    p.title = "Compression on " + r.set->spec.name + ": ratio against max joint error";
    p.x_label = "max joint-position error (cm), log";
    p.y_label = "compression ratio, log";
    for (const auto& row : r.compression.rows) {
        if (row.target_cm == 0.0 || !row.target_met) continue;
        auto it = std::find_if(p.series.begin(), p.series.end(), [&](const PlotSeries& s) { return s.name == row.method; });
        if (it == p.series.end()) {
            p.series.push_back({row.method, {}, {}});
            it = p.series.end() - 1;
        }
        it->x.push_back(row.stats.max_cm);
        it->y.push_back(row.ratio);
    }
    p.note = svg_note(info);
    return render_line_plot(p);
}

std::string runtime_svg(const RunInfo& info, const EvalResults& e, bool build) {
    PlotSpec p;
    p.title = std::string(build ? "Preprocessing" : "Synthesis") + " time against samples (" + e.runtime_set + ")";
    p.x_label = "training samples N, log";
    p.y_label = build ? "build time (s), log" : "time per synthesized frame (us), log";
    for (const auto& row : e.runtime) {
        auto it = std::find_if(p.series.begin(), p.series.end(), [&](const PlotSeries& s) { return s.name == row.method; });
        if (it == p.series.end()) {
            p.series.push_back({row.method, {}, {}});
            it = p.series.end() - 1;
        }
        it->x.push_back(static_cast<double>(row.samples));
        it->y.push_back(build ? row.build_seconds : row.synth_us_per_frame);
    }
    p.note = svg_note(info);
    return render_line_plot(p);
}

// ---------------------------------------------------------------------------------------------------
// JSON

void json_vec(JsonWriter& j, const VecX& v) {
    j.begin_array();
    for (Eigen::Index k = 0; k < v.size(); ++k) j.value(v(k));
    j.end_array();
}

std::string results_json(const EvalResults& e) {
    JsonWriter j;
    j.begin_object();
    j.key("command").value(e.info.command);
    j.key("mode").value(e.info.mode);
    j.key("date").value(e.info.date);
    j.key("machine").value(e.info.machine);
    j.key("load_average").value(e.info.load);
    j.key("build").value(e.info.build);
    j.key("wall_seconds").value(e.info.wall_seconds);
    j.key("cpu_seconds").value(e.info.cpu_seconds);
    j.key("sets").begin_array();
    for (const SetResults& r : e.sets) {
        const eval::EvalSet& s = *r.set;
        j.begin_object();
        j.key("name").value(s.spec.name);
        j.key("description").value(s.spec.description);
        j.key("skeleton").value(s.skeleton_source);
        j.key("clips").begin_array();
        for (const auto& c : s.clip_ids) j.value(c);
        j.end_array();
        j.key("samples").value(static_cast<long long>(s.size()));
        j.key("repairs").begin_array();
        for (const RepairedFrames& x : s.set.repairs)
            j.begin_object().key("clip").value(x.clip).key("joint").value(x.joint).key("begin").value(x.begin).key("end").value(x.end).end_object();
        j.end_array();
        j.key("frames").value(static_cast<long long>(s.aligned.frames()));
        j.key("dofs").value(static_cast<long long>(s.aligned.dofs()));
        j.key("build_seconds").value(r.build_seconds);
        j.key("parameters").begin_array();
        const auto ranges = eval::parameter_ranges(s);
        for (std::size_t k = 0; k < s.set.parameter_names.size(); ++k) {
            j.begin_object().key("name").value(s.set.parameter_names[k]).key("unit").value(s.set.parameter_units[k]);
            j.key("min").value(ranges[k].first).key("max").value(ranges[k].second);
            j.end_object();
        }
        j.end_array();
        j.key("methods").begin_array();
        for (const auto& m : r.methods) {
            j.begin_object().key("name").value(m.name).key("kind").value(eval::to_string(m.kind));
            j.key("kriging").value(m.is_kriging());
            if (m.kind == eval::MethodKind::TuckerKriging) {
                j.key("ranks").begin_array();
                for (auto x : m.ranks) j.value(static_cast<long long>(x));
                j.end_array();
            }
            j.end_object();
        }
        j.end_array();
        if (r.has_headroom) {
            const eval::KernelHeadroom& h = r.headroom;
            j.key("kernel_headroom").begin_object();
            j.key("kernels").value(static_cast<long long>(h.kernels));
            j.key("best_pose_mean_cm").value(h.best_pose_mean_cm).key("median_pose_mean_cm").value(h.median_pose_mean_cm);
            j.key("best_p").value(h.best.paper_p()).key("best_range").value(h.best.range);
            j.key("best_nugget_share").value(h.best.nugget).key("best_anisotropy").value(h.best_anisotropy);
            j.end_object();
        }
        if (r.has_loo) {
            j.key("loo").begin_object();
            j.key("seconds").value(r.loo_seconds);
            j.key("samples").begin_array();
            for (auto i : r.loo.samples) j.value(static_cast<long long>(i));
            j.end_array();
            if (r.loo.original_skating_cm_per_s.size()) {
                j.key("original_skating_cm_per_s");
                json_vec(j, r.loo.original_skating_cm_per_s);
            }
            j.key("methods").begin_array();
            for (const auto& m : r.loo.methods) {
                j.begin_object().key("method").value(m.method);
                j.key("mean_cm").value(m.mean_cm).key("max_cm").value(m.max_cm);
                j.key("pose_mean_cm").value(m.pose_mean_cm).key("pose_max_cm").value(m.pose_max_cm);
                j.key("pose_worst").begin_object();
                j.key("sample").value(static_cast<long long>(m.pose_worst_sample));
                j.key("frame").value(static_cast<long long>(m.pose_worst_frame));
                j.key("joint").value(m.pose_worst_joint);
                j.end_object();
                j.key("build_seconds").value(m.build_seconds).key("synth_seconds").value(m.synth_seconds);
                j.key("sample_mean_cm");
                json_vec(j, m.sample_mean_cm);
                j.key("sample_max_cm");
                json_vec(j, m.sample_max_cm);
                j.key("frame_mean_cm");
                json_vec(j, m.frame_mean_cm);
                j.key("frame_max_cm");
                json_vec(j, m.frame_max_cm);
                j.key("sample_pose_mean_cm");
                json_vec(j, m.sample_pose_mean_cm);
                j.key("sample_pose_max_cm");
                json_vec(j, m.sample_pose_max_cm);
                j.key("frame_pose_mean_cm");
                json_vec(j, m.frame_pose_mean_cm);
                j.key("duration_error_s");
                json_vec(j, m.duration_error_s);
                if (m.skating_cm_per_s.size()) {
                    j.key("skating_cm_per_s");
                    json_vec(j, m.skating_cm_per_s);
                }
                j.end_object();
            }
            j.end_array().end_object();
        }
        if (r.has_constraint) {
            const auto& c = r.constraint;
            j.key("constraint").begin_object();
            j.key("grid_points").value(static_cast<long long>(c.grid.rows()));
            j.key("scale");
            json_vec(j, c.scale);
            j.key("reliability");
            json_vec(j, c.reliability);
            j.key("rho_outside_3sd").value(c.rho_outside_3sd);
            if (std::isfinite(c.loo_mean_z2)) j.key("loo_mean_z2").value(c.loo_mean_z2);
            j.key("methods").begin_array();
            for (const auto& m : c.methods) {
                j.begin_object().key("method").value(m.method);
                j.key("failures").value(static_cast<long long>(m.failures));
                j.key("pearson_rho_error").value(m.pearson);
                j.key("own_reliability").value(m.own_reliability);
                if (m.own_reliability) j.key("rho_outside_3sd").value(m.rho_outside_3sd);
                j.key("seconds").value(m.seconds);
                j.key("regions").begin_array();
                std::vector<eval::RegionStats> all = m.regions;
                all.push_back(m.all);
                for (const auto& g : all) {
                    j.begin_object().key("rho_at_least").value(g.threshold).key("points").value(static_cast<long long>(g.points));
                    j.key("max").value(g.max).key("rmse").value(g.rmse).key("axis_rmse");
                    json_vec(j, g.axis_rmse);
                    j.end_object();
                }
                j.end_array();
                j.key("error");
                json_vec(j, m.error);
                j.end_object();
            }
            j.end_array().end_object();
        }
        if (r.has_reduction) {
            const auto& d = r.reduction;
            j.key("reduction").begin_object();
            j.key("tau").value(r.reduction_options.tau);
            j.key("samples").value(static_cast<long long>(d.samples));
            j.key("kept_at_tau").value(static_cast<long long>(d.kept_at_tau));
            j.key("removal_order").begin_array();
            for (auto i : d.removal_order) j.value(static_cast<long long>(i));
            j.end_array();
            j.key("max_reliability").begin_array();
            for (double v : d.max_reliability) j.value(v);
            j.end_array();
            j.key("points").begin_array();
            for (const auto& p : d.points)
                j.begin_object()
                    .key("kept").value(static_cast<long long>(p.kept))
                    .key("max_reliability").value(p.max_reliability)
                    .key("greedy_mean_cm").value(p.greedy_mean_cm)
                    .key("greedy_max_cm").value(p.greedy_max_cm)
                    .key("random_mean_cm").value(p.random_mean_cm)
                    .key("greedy_pose_mean_cm").value(p.greedy_pose_mean_cm)
                    .key("random_pose_mean_cm").value(p.random_pose_mean_cm)
                    .end_object();
            j.end_array().end_object();
        }
        if (r.has_compression) {
            j.key("compression").begin_object();
            j.key("raw_bytes").value(static_cast<long long>(r.compression.raw_bytes));
            j.key("side_bytes").value(static_cast<long long>(r.compression.side_bytes));
            j.key("rows").begin_array();
            for (const auto& row : r.compression.rows) {
                j.begin_object().key("method").value(row.method).key("target_cm").value(row.target_cm);
                j.key("target_met").value(row.target_met);
                j.key("ranks").begin_array();
                for (long long k : row.ranks) j.value(k);
                j.end_array();
                j.key("bytes").value(static_cast<long long>(row.bytes)).key("ratio").value(row.ratio);
                j.key("rmse_cm").value(row.stats.rmse_cm).key("max_cm").value(row.stats.max_cm);
                j.key("precompute_s").value(row.precompute_s).key("us_per_pose").value(row.us_per_pose);
                j.key("access").value(row.access);
                j.end_object();
            }
            j.end_array().end_object();
        }
        j.end_object();
    }
    j.end_array();
    j.key("runtime").begin_object();
    j.key("set").value(e.runtime_set);
    j.key("rows").begin_array();
    for (const auto& row : e.runtime)
        j.begin_object()
            .key("method").value(row.method)
            .key("samples").value(static_cast<long long>(row.samples))
            .key("frames").value(static_cast<long long>(row.frames))
            .key("build_seconds").value(row.build_seconds)
            .key("build_us_per_frame").value(row.build_us_per_frame)
            .key("synth_us_per_frame").value(row.synth_us_per_frame)
            .end_object();
    j.end_array().end_object();
    j.end_object();
    return j.str();
}

// ---------------------------------------------------------------------------------------------------
// REPORT.md

// The text of one metric's verdict.
struct MetricText {
    std::string name;
    std::string unit;
};

MetricText metric_text(const eval::MetricVerdict& v) {
    switch (v.metric) {
        case eval::Metric::LooPoseMean: return {"leave-one-out mean pose error (root-relative)", " cm"};
        case eval::Metric::LooPoseMax: return {"leave-one-out max pose error (root-relative)", " cm"};
        case eval::Metric::LooMotionMean: return {"leave-one-out mean motion error (with root trajectory)", " cm"};
        case eval::Metric::LooMotionMax: return {"leave-one-out max motion error (with root trajectory)", " cm"};
        case eval::Metric::LooDuration: return {"leave-one-out duration error", " s"};
        case eval::Metric::FootSkating: return {"foot skating of the synthesized motions", " cm/s"};
        case eval::Metric::ConstraintReliableRmse: return {"constraint RMSE |c - c_hat| where rho >= " + fmt(v.threshold), " (normalized)"};
        case eval::Metric::ConstraintRmse: return {"constraint RMSE over the whole grid", " (normalized)"};
    }
    return {"", ""};
}

const eval::LooMethodResult* loo_method(const SetResults& r, const std::string& n) {
    for (const auto& m : r.loo.methods)
        if (m.method == n) return &m;
    return nullptr;
}

const eval::ConstraintMethodResult* constraint_method(const SetResults& r, const std::string& n) {
    for (const auto& m : r.constraint.methods)
        if (m.method == n) return &m;
    return nullptr;
}

std::string split_text(const eval::MetricVerdict& v) {
    if (!v.split) return "";
    const eval::EdgeSplit& s = *v.split;
    const std::string contrast =
        v.best.method.rfind("nn-blend", 0) == 0
            ? "Kriging's linear trend extrapolates beyond the remaining samples; the nearest-neighbour blend is a "
              "convex combination of its neighbours and cannot leave them."
            : "RBF has the same linear trend; the two differ in how the residuals are interpolated (fitted "
              "variogram vs cubic B-splines with support twice the nearest-neighbour distance).";
    std::ostringstream w;
    w << "Mean error split by position of the left-out sample: on the " << s.edge_samples
      << " samples at the edge of the parameter range (the fold must extrapolate) " << v.best.method << " "
      << fmt(s.best_edge) << " cm vs " << v.best_kriging.method << " " << fmt(s.kriging_edge) << " cm; on the "
      << s.interior_samples << " interior samples " << fmt(s.best_interior) << " cm vs " << fmt(s.kriging_interior) << " cm. ";
    switch (s.location) {
        case eval::LossLocation::BothMoreAtEdge:
            w << "Kriging loses on both groups, more at the edge, where the fold extrapolates. " << contrast;
            break;
        case eval::LossLocation::BothMoreInterior:
            w << "Kriging loses on both groups, more on interior samples, so this is not (only) extrapolation: "
                 "with these samples the fitted variograms and trend predict a left-out motion worse than a "
                 "local blend of its neighbours.";
            break;
        case eval::LossLocation::InteriorOnly:
            w << "The loss is on interior samples only (kriging is better at the edge): with these samples the "
                 "fitted variograms and trend predict an interior motion worse than a local blend of its neighbours.";
            break;
        case eval::LossLocation::EdgeOnly:
            w << "The loss comes from the edge samples only, where the fold extrapolates. " << contrast;
            break;
        case eval::LossLocation::None: break;
    }
    return w.str();
}

// Why a baseline won a metric, from the results behind the verdict.
std::string why_text(const SetResults& r, const eval::MetricVerdict& v) {
    const eval::EvalSet& s = *r.set;
    switch (v.metric) {
        case eval::Metric::LooPoseMean:
        case eval::Metric::LooMotionMean: return split_text(v);
        case eval::Metric::LooPoseMax: {
            const auto* base = loo_method(r, v.best.method);
            const auto* kr = loo_method(r, v.best_kriging.method);
            if (!base || !kr || base->pose_worst_sample < 0 || kr->pose_worst_sample < 0) return std::string();
            return "A single worst frame over all folds: " + v.best.method + " at " +
                   s.labels[static_cast<std::size_t>(base->pose_worst_sample)] + " frame " + std::to_string(base->pose_worst_frame) +
                   " (" + base->pose_worst_joint + "), " + v.best_kriging.method + " at " +
                   s.labels[static_cast<std::size_t>(kr->pose_worst_sample)] + " frame " + std::to_string(kr->pose_worst_frame) +
                   " (" + kr->pose_worst_joint + ").";
        }
        case eval::Metric::LooMotionMax:
            return "A single worst frame over all folds; see the per-sample maxima in loo_" + s.spec.name + ".csv.";
        case eval::Metric::LooDuration:
            return "Every method predicts the duration from the samples' inverse-warp increments (Tucker and naive with "
                   "their coefficient kernel, per-pose / per-element kriging and RBF with a per-set kernel of their own, the "
                   "blend with its weights; lib/include/mocapdb/eval/synthesis_method.hpp).";
        case eval::Metric::FootSkating:
            return "The original samples skate " + fmt(eval::mean_or_nan(r.loo.original_skating_cm_per_s)) +
                   " cm/s by the same measure (the nearest-neighbour blend mixes at most 3 samples, kriging all of them).";
        case eval::Metric::ConstraintReliableRmse: {
            const auto* base = constraint_method(r, v.best.method);
            const auto* kr = constraint_method(r, v.best_kriging.method);
            if (!base || !kr) return std::string();
            return "Over the whole grid (including rho < " + fmt(v.threshold) + "): " + v.best.method + " RMSE " +
                   fmt(base->all.rmse) + ", " + v.best_kriging.method + " " + fmt(kr->all.rmse) +
                   ". The achieved parameters are measured on the synthesized clips with the same extractors; "
                   "a blend that stays close to one captured sample reproduces that sample's measured parameters.";
        }
        case eval::Metric::ConstraintRmse: return "";
    }
    return "";
}

std::string losses_section(const EvalResults& e) {
    const eval::Verdicts verdicts = eval::judge(e);
    std::ostringstream o;
    o << "## Where our kriging loses\n\n"
      << "Generated from the numbers above: for every set and metric, the best method overall against the best of our "
         "kriging methods (per-pose, per-element, Tucker + kriging, naive). Lower is better everywhere. A line starting "
         "with **LOSES** means a baseline (RBF or the nearest-neighbour blend) beat every kriging variant on that metric.\n\n";
    for (const eval::SetVerdicts& sv : verdicts.sets) {
        const SetResults& r = *sv.results;
        o << "### " << r.set->spec.name << "\n\n";
        for (const eval::MetricVerdict& v : sv.metrics) {
            const MetricText t = metric_text(v);
            const std::string& unit = t.unit;
            switch (v.outcome) {
                case eval::Outcome::Tie:
                    o << "- " << t.name << ": tie — " << v.best.method << " " << fmt(v.best.value) << unit << ", best kriging ("
                      << v.best_kriging.method << ") " << fmt(v.best_kriging.value) << unit << ", within 5 % or "
                      << fmt(eval::tie_floor(v.metric)) << unit << ".\n";
                    break;
                case eval::Outcome::KrigingWins:
                    o << "- " << t.name << ": kriging wins (" << v.best.method << " " << fmt(v.best.value) << unit << ").\n";
                    break;
                case eval::Outcome::Loses:
                    o << "- **LOSES** " << t.name << ": " << v.best.method << " " << fmt(v.best.value) << unit
                      << " against the best kriging variant, " << v.best_kriging.method << ", " << fmt(v.best_kriging.value) << unit
                      << " (" << percent(v.kriging_worse_percent) << " worse). " << why_text(r, v) << "\n";
                    break;
            }
        }
        for (const eval::CompressionVerdict& c : sv.compression) {
            if (c.tucker_wins) {
                o << "- compression at max error <= " << fmt(c.target_cm) << " cm: a Tucker variant wins (" << c.best.method
                  << ", ratio " << fmt(c.best.ratio) << ").\n";
            } else {
                o << "- **LOSES** compression at max error <= " << fmt(c.target_cm) << " cm: " << c.best.method << " ratio "
                  << fmt(c.best.ratio) << " against plain Tucker " << fmt(c.tucker.ratio)
                  << ". The Tucker model is what synthesis needs (pose-level random access in "
                  << fmt(c.tucker.us_per_pose) << " us/pose); " << c.best.method << " is "
                  << (c.best.access == "stream" ? "a stream codec (decodes the whole set: " : "(") << fmt(c.best.us_per_pose)
                  << " us/pose).\n";
            }
        }
        o << "\n";
    }
    if (verdicts.runtime) {
        const eval::RuntimeVerdicts& v = *verdicts.runtime;
        o << "### Runtime (" << e.runtime_set << ")\n\n";
        if (v.fastest_build && v.slowest_kriging_build) {
            const eval::RuntimeRow& fb = *v.fastest_build;
            o << "- " << (v.build_loses ? "**LOSES** preprocessing" : "preprocessing") << " at N = " << v.samples << ": fastest is "
              << fb.method << " (" << fmt(fb.build_seconds) << " s); the fastest kriging variant, "
              << (v.fastest_kriging_build ? v.fastest_kriging_build->method : std::string("-")) << ", takes "
              << (v.fastest_kriging_build ? fmt(v.fastest_kriging_build->build_seconds) : std::string("-")) << " s, the slowest, "
              << v.slowest_kriging_build->method << ", " << fmt(v.slowest_kriging_build->build_seconds)
              << " s. Kriging fits variograms (per-element: one per dof and frame; per-pose: one per frame) and factorizes "
                 "a system per kernel; RBF factorizes one system and the blend only stores the samples.\n";
        }
        if (v.fastest_synthesis) {
            o << "- " << (v.synthesis_loses ? "**LOSES** synthesis time" : "synthesis time") << " at N = " << v.samples
              << ": fastest is " << v.fastest_synthesis->method << " (" << fmt(v.fastest_synthesis->synth_us_per_frame)
              << " us per frame).\n";
        }
        o << "\n";
    }
    o << "In all: a baseline beats every kriging variant in " << verdicts.losses << " of " << verdicts.comparisons
      << " comparisons (" << verdicts.ties << " more are ties within 5 %).\n\n";
    return o.str();
}

std::string report_md(const EvalResults& e) {
    const RunInfo& info = e.info;
    std::ostringstream o;
    o << "# mocapdb evaluation report\n\n"
      << "Generated by `" << info.command << "` — do not edit by hand; rerun the command instead.\n\n"
      << "| | |\n|---|---|\n"
      << "| command | `" << info.command << "` (" << info.mode << " run) |\n"
      << "| date | " << info.date << " |\n"
      << "| machine | " << info.machine << " |\n"
      << "| load average at start | " << info.load << " |\n"
      << "| build | " << info.build << " |\n"
      << "| wall time | " << fixed(info.wall_seconds, 1) << " s (CPU time " << fixed(info.cpu_seconds, 1)
      << " s; single-threaded experiments, so wall time above CPU time means the machine was shared) |\n\n"
      << "The data used in this project was obtained from mocap.cs.cmu.edu. The database was created with funding from "
         "NSF EIA-0196217.\n\n";

    // Data
    o << "## Data\n\n";
    Table t{{"set", "description", "clips", "N", "T", "D", "parameters (range)", "skeleton", "build s"}, {}, 3};
    for (const SetResults& r : e.sets) {
        const eval::EvalSet& s = *r.set;
        std::string clips;
        for (std::size_t k = 0; k < s.clip_ids.size(); ++k) clips += (k ? " " : "") + s.clip_ids[k];
        if (!s.skipped.empty()) {
            clips += " (no sample:";
            for (const auto& c : s.skipped) clips += " " + c;
            clips += ")";
        }
        t.rows.push_back({"`" + s.spec.name + "`", s.spec.description + cycles_note(s.spec),
                          clips, std::to_string(s.size()), std::to_string(s.aligned.frames()), std::to_string(s.aligned.dofs()),
                          params_text(s), s.skeleton_source, fixed(r.build_seconds, 1)});
    }
    o << t.str() << "\n"
      << short_caption(info, "CMU ASF/AMC clips at 120 Hz from `--data`/cmu-asfamc",
                       "parameters measured by lib/include/mocapdb/dataset/param_extractors.hpp (turn [rad], speed [cm/s], "
                       "jump [cm]); DTW alignment to T frames against the median-length sample")
      << "\nA set has one skeleton: the first clip's (column *skeleton*). Clips of other subjects (the `jumps` set: "
         "subjects 13, 16, 105) are replayed on it (same CMU joints and channels; their parameters were measured on their "
         "own skeletons before the swap), so their joint positions use subject 13's bone lengths.\n\n";
    // Solver dropouts are repaired before segmentation and alignment, and named here.
    {
        std::string repaired;
        for (const SetResults& r : e.sets) {
            const eval::EvalSet& s = *r.set;
            for (const auto& c : s.clip_ids) {
                const std::string d = describe_repairs(c, s.set.repairs);
                if (!d.empty()) repaired += std::string(repaired.empty() ? "" : "; ") + "`" + s.spec.name + "` " + c + ": " + d;
            }
        }
        o << "Solver dropouts (a joint's rotation channels exactly 0 for a few frames while it moves elsewhere; "
             "lib/include/mocapdb/dataset/dropout_repair.hpp) repaired by interpolation from the clean frames before "
             "segmentation and alignment (frames 0-based, inclusive): "
          << (repaired.empty() ? std::string("none found") : repaired) << ".\n\n";
    }

    // Methods
    o << "Methods (lib/include/mocapdb/eval/synthesis_method.hpp): *per-pose kriging* (one kernel per aligned frame on the "
         "pose-distance signal, the geostatistical paper §3.4), *per-element kriging* (one kernel per dof and frame, §3.2), "
         "*tucker-Ecm* (Tucker model at the smallest HOSVD ranks whose max joint error on the whole set is <= E cm, kriging of "
         "the sample-mode coefficients: the multilinear paper; the basis is refitted in every fold), *naive kriging* "
         "(per-set kriging of the uncompressed samples), *rbf* (Rose et al.: linear trend + cubic B-spline radial basis), "
         "*nn-blend k=3* (inverse-distance weights over the 3 nearest samples in normalized parameters). All blend the "
         "samples linearly; parameters are normalized per axis (mean 0, standard deviation 1).\n\n";

    // 1. LOO
    o << "## 1. Leave-one-out whole-motion prediction\n\n"
      << "Each sample is left out, every method is rebuilt on the others (variograms, trends, Tucker basis, timing kernel) "
         "and synthesizes the motion at the sample's parameters; the error is the joint-position distance (cm, forward "
         "kinematics, all joints incl. end sites, canonical frame) to the sample, frame by frame in aligned time (the geostatistical paper §5.1, Figures 6-7). "
         "*pose* error: root-relative (the root's floor position and heading removed in every frame, as the alignment's pose "
         "distance), i.e. the posture; *motion* error: in the canonical frame, so the root's trajectory counts too. "
         "*duration err* compares the synthesized duration with the sample's.\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_loo) continue;
        const eval::EvalSet& s = *r.set;
        const auto durations = eval::duration_range(s);
        o << "### " << s.spec.name << "\n\n";
        // Gain over the linear trend alone: 1 - pose mean / trend-only pose mean.
        const std::vector<double> gains = eval::gain_over_trend(r);
        Table lt{{"method", "pose mean cm", "gain over trend-only", "pose max cm", "worst (sample, frame, joint)", "motion mean cm", "motion max cm", "duration err s", "build s/fold", "synth ms"}, {}};
        for (std::size_t k = 0; k < r.loo.methods.size(); ++k) {
            const auto& m = r.loo.methods[k];
            const std::string gain = std::isfinite(gains[k]) ? fixed(100.0 * gains[k], 1) + " %" : std::string("-");
            lt.rows.push_back({method_label(r.methods[k]), fixed(m.pose_mean_cm, 2), gain, fixed(m.pose_max_cm, 1),
                               m.pose_worst_sample >= 0 ? s.labels[static_cast<std::size_t>(m.pose_worst_sample)] + ", " +
                                                              std::to_string(m.pose_worst_frame) + ", " + m.pose_worst_joint
                                                        : "-",
                               fixed(m.mean_cm, 2), fixed(m.max_cm, 1),
                               fixed(eval::mean_or_nan(m.duration_error_s), 3), fmt(m.build_seconds), fmt(1e3 * m.synth_seconds)});
        }
        o << lt.str() << "\n";
        for (const auto& m : r.methods)
            if (eval::keeps_full_sample_rank(m, s))
                o << "Note: " << m.name << " keeps the full sample rank (R3 = " << m.ranks[2] << " >= N - 1, clamped to the "
                  << "training size in each fold): meeting the max-error target needs every sample direction, so its "
                     "kriged motions equal naive kriging's up to the dof/time truncation.\n";
        if (r.has_headroom) {
            const eval::KernelHeadroom& h = r.headroom;
            o << "Kernel headroom (lib/include/mocapdb/eval/kernel_headroom.hpp): of " << h.kernels
              << " fixed kernels tried in the same folds with naive kriging, the best reaches **" << fixed(h.best_pose_mean_cm, 2)
              << " cm** pose mean (p = " << fmt(h.best.paper_p()) << ", range " << fmt(h.best.range) << " sd, nugget share "
              << fmt(h.best.nugget) << ", axes after the first scaled by " << fmt(h.best_anisotropy) << "), the median kernel "
              << fixed(h.median_pose_mean_cm, 2)
              << " cm. That best is chosen on the very errors it is scored on, so no choice among these kernels made "
                 "from the training samples alone can do better.\n";
        }
        o << "\n"
          << caption(info, s, std::to_string(r.loo.samples.size()) + " folds (left-out samples" +
                                  (static_cast<Eigen::Index>(r.loo.samples.size()) < s.size() ? ", every " +
                                       std::to_string(r.loo.samples.size() > 1 ? r.loo.samples[1] - r.loo.samples[0] : 1) + "th sample" : "") +
                                  ")")
          << "\nSample durations in this set: " << fixed(durations.first, 2) << " .. " << fixed(durations.second, 2)
          << " s (the parameters do not fix a whole clip's duration, so the root travels different distances in aligned time)."
          << "\n\n![LOO pose error over time](loo_" << s.spec.name << ".svg) ![LOO motion error over time](loo_motion_" << s.spec.name
          << ".svg)  \nNumbers: [loo_" << s.spec.name << ".csv](loo_"
          << s.spec.name << ".csv) (per sample), [loo_frames_" << s.spec.name << ".csv](loo_frames_" << s.spec.name
          << ".csv) (per frame).\n\n";
    }

    // 2. Constraint accuracy
    o << "## 2. Constraint accuracy\n\n"
      << "On a regular grid over the samples' parameter box each method (built on all samples) synthesizes a clip; the "
         "same extractors measure the achieved parameters ĉ. Error |c − ĉ| in normalized units (per axis divided by the "
         "samples' standard deviation, listed under the table). MAX and RMSE over the grid points with reliability ρ(c) >= "
         "0.9, 0.8, 0.7 (each method's own ρ, computed with its own kernel, for Tucker and naive kriging; the naive kriging kernel's ρ for the methods without one), as in the geostatistical paper's Table 1; *fail* = "
         "grid points whose parameter could not be measured on the synthesized clip (excluded).\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_constraint) continue;
        const eval::EvalSet& s = *r.set;
        const auto& c = r.constraint;
        o << "### " << s.spec.name << "\n\n";
        Table ct{{"method"}, {}};
        for (double th : r.constraint_options.thresholds) {
            ct.header.push_back("ρ≥" + fmt(th) + " n");
            ct.header.push_back("MAX");
            ct.header.push_back("RMSE");
        }
        ct.header.push_back("all RMSE");
        ct.header.push_back("fail");
        for (const auto& m : c.methods) {
            std::vector<std::string> row{m.method};
            for (const auto& g : m.regions) {
                row.push_back(std::to_string(g.points));
                row.push_back(g.points ? fixed(g.max, 3) : "-");
                row.push_back(g.points ? fixed(g.rmse, 3) : "-");
            }
            row.push_back(fixed(m.all.rmse, 3));
            row.push_back(std::to_string(m.failures));
            ct.rows.push_back(row);
        }
        std::string scale;
        for (Eigen::Index k = 0; k < c.scale.size(); ++k)
            scale += (k ? ", " : "") + s.set.parameter_names[static_cast<std::size_t>(k)] + " " + fmt(c.scale(k), 4) + " " +
                     s.set.parameter_units[static_cast<std::size_t>(k)];
        std::string axis;
        for (const auto& m : c.methods) {
            axis += "; " + m.method + ":";
            for (Eigen::Index k = 0; k < m.all.axis_rmse.size(); ++k)
                axis += " " + fmt(m.all.axis_rmse(k)) + " " + s.set.parameter_units[static_cast<std::size_t>(k)];
        }
        o << ct.str() << "\nNormalization (one unit =): " << scale << ". RMSE per axis over the whole grid, in the parameters' own units" << axis
          << ".\n\n"
          << caption(info, s, std::to_string(c.grid.rows()) + " grid points (" +
                                  (s.set.parameters.cols() == 1 ? std::to_string(r.constraint_options.points_1d)
                                                                 : std::to_string(r.constraint_options.points_per_axis_2d) + " per axis") +
                                  ")")
          << "\nNumbers: [constraint_" << s.spec.name << ".csv](constraint_" << s.spec.name << ".csv).\n\n";
    }

    // 3. Reliability vs error
    o << "## 3. Reliability against error\n\n"
      << "Pearson correlation between ρ(c) and |c − ĉ| over the grid points of section 2 (the geostatistical paper reports "
         "−0.70: low reliability, large error). Negative means the reliability map warns where the constraints are missed.\n\n";
    {
        Table pt{{"set", "grid points"}, {}};
        std::vector<std::string> names;
        for (const SetResults& r : e.sets)
            if (r.has_constraint) {
                for (const auto& m : r.constraint.methods)
                    if (std::find(names.begin(), names.end(), m.method) == names.end()) names.push_back(m.method);
            }
        for (const auto& n : names) pt.header.push_back(n);
        for (const SetResults& r : e.sets) {
            if (!r.has_constraint) continue;
            std::vector<std::string> row{r.set->spec.name, std::to_string(r.constraint.grid.rows())};
            for (const auto& n : names) {
                std::string v = "-";
                for (const auto& m : r.constraint.methods)
                    if (m.method == n) v = fixed(m.pearson, 2);
                row.push_back(v);
            }
            pt.rows.push_back(row);
        }
        o << pt.str() << "\n"
          << short_caption(info, "the grids of section 2",
                           "each method's own ρ (Tucker, naive kriging), else the naive kriging kernel's ρ on all samples; "
                           "error normalized per axis");
        // The check: rho must fall to 0.5 or below 3 standard deviations outside the samples' box.
        Table ot{{"set", "LOO mean z² (naive kernel)", "ρ 3 sd outside (naive kernel)"}, {}};
        std::vector<std::string> own;
        for (const SetResults& r : e.sets)
            if (r.has_constraint)
                for (const auto& m : r.constraint.methods)
                    if (m.own_reliability && std::find(own.begin(), own.end(), m.method) == own.end()) own.push_back(m.method);
        for (const auto& n : own) ot.header.push_back(n);
        for (const SetResults& r : e.sets) {
            if (!r.has_constraint) continue;
            std::vector<std::string> row{r.set->spec.name, fixed(r.constraint.loo_mean_z2, 2),
                                         fixed(r.constraint.rho_outside_3sd, 3)};
            for (const auto& n : own) {
                std::string v = "-";
                for (const auto& m : r.constraint.methods)
                    if (m.method == n && m.own_reliability) v = fixed(m.rho_outside_3sd, 3);
                row.push_back(v);
            }
            ot.rows.push_back(row);
        }
        o << "\nCalibration of the prediction variance ρ is made of: leave-one-out mean z² of the naive kriging kernel "
             "(z_i² = squared error of the left-out sample's weighted, centred values over its kriging variance; near 1 "
             "when calibrated), and the largest ρ at the points 3 standard deviations outside the samples' parameter box "
             "(from the box's centre along each axis, both sides), where the reliability should warn (ρ <= 0.5):\n\n"
          << ot.str() << "\n";
        for (const SetResults& r : e.sets)
            if (r.has_constraint)
                o << "\n![reliability vs error](reliability_" << r.set->spec.name << ".svg)";
        o << "\n\n";
    }

    // 4. Sample reduction
    o << "## 4. Sample reduction\n\n"
      << "Greedy removal of the sample whose leave-one-out reliability is highest (the geostatistical paper §5.2: 69 → 29 "
         "samples at τ = 0.85), continued past τ to draw the curve; at each kept size, the mean joint error (cm; pose and motion "
         "as in section 1) of predicting every removed sample from a naive kriging model of the kept ones, against random "
         "removal orders.\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_reduction) continue;
        const eval::EvalSet& s = *r.set;
        o << "### " << s.spec.name << "\n\n"
          << "τ = " << fmt(r.reduction_options.tau) << " keeps **" << r.reduction.kept_at_tau << " of " << s.size()
          << "** samples";
        const eval::ReductionAtTau at_tau = eval::reduction_at_tau(r);
        if (at_tau == eval::ReductionAtTau::NothingRemoved)
            o << ": the highest leave-one-out reliability of any sample is already "
              << fixed(r.reduction.max_reliability.front(), 3) << " < τ, so "
              << "nothing is removed (the paper removes 40 of 69). With this set's fitted variogram no sample is "
              << "predicted reliably enough from the others; the curve below continues past τ to show what removal would cost";
        else if (at_tau == eval::ReductionAtTau::SomeRemoved)
            o << " (the paper: 29 of 69)";
        o << ".\n\n";
        Table rt{{"kept", "max LOO ρ", "greedy pose mean cm", "random pose mean cm", "greedy motion mean cm", "greedy motion max cm", "random motion mean cm"}, {}};
        const bool rnd = r.reduction_options.random_orders > 0;
        for (const auto& p : r.reduction.points)
            rt.rows.push_back({std::to_string(p.kept), fixed(p.max_reliability, 3), fixed(p.greedy_pose_mean_cm, 2),
                               rnd ? fixed(p.random_pose_mean_cm, 2) : "-", fixed(p.greedy_mean_cm, 2), fixed(p.greedy_max_cm, 1),
                               rnd ? fixed(p.random_mean_cm, 2) : "-"});
        o << rt.str() << "\n"
          << caption(info, s, "τ = " + fmt(r.reduction_options.tau) + ", " + std::to_string(r.reduction_options.random_orders) +
                                  " random orders (seed " + std::to_string(r.reduction_options.seed) + "), variogram fixed from all samples")
          << "\n![reduction](reduction_" << s.spec.name << ".svg)  \nNumbers: [reduction_" << s.spec.name << ".csv](reduction_"
          << s.spec.name << ".csv).\n\n";
    }

    // 5. Foot skating
    o << "## 5. Foot skating\n\n"
      << "Horizontal travel of the feet (ltoes, rtoes) while in detected contact (height within 5 cm of the foot's floor "
         "level and speed below 40 cm/s, lib/include/mocapdb/eval/foot_skating.hpp), per second of contact, on the clips "
         "synthesized in the leave-one-out folds (with their synthesized timing), against the original samples. Because "
         "contacts require a low speed, this measures slow sliding within contacts; *contact* differences show up in the "
         "LOO errors instead.\n\n";
    {
        Table ft{{"set", "original"}, {}};
        std::vector<std::string> names;
        for (const SetResults& r : e.sets)
            if (r.has_loo)
                for (const auto& m : r.loo.methods)
                    if (std::find(names.begin(), names.end(), m.method) == names.end()) names.push_back(m.method);
        for (const auto& n : names) ft.header.push_back(n);
        for (const SetResults& r : e.sets) {
            if (!r.has_loo || r.loo.original_skating_cm_per_s.size() == 0) continue;
            std::vector<std::string> row{r.set->spec.name, fixed(eval::mean_or_nan(r.loo.original_skating_cm_per_s), 2)};
            for (const auto& n : names) {
                std::string v = "-";
                for (const auto& m : r.loo.methods)
                    if (m.method == n && m.skating_cm_per_s.size()) v = fixed(eval::mean_or_nan(m.skating_cm_per_s), 2);
                row.push_back(v);
            }
            ft.rows.push_back(row);
        }
        o << ft.str() << "\n"
          << short_caption(info, "the leave-one-out folds of section 1 (cm/s, mean over left-out samples)",
                           "contact height tolerance 5 cm, speed tolerance 40 cm/s, feet ltoes/rtoes")
          << "\nPer-sample values: the `skating_cm_per_s` columns of the loo_*.csv files.\n\n";
    }

    // 6. Compression
    o << "## 6. Compression\n\n"
      << "The compression report of `mocapdb report` (lib/include/mocapdb/compression/rate_distortion.hpp) on each set's "
         "aligned tensor: per max joint-error target the cheapest setting of each method, its ranks, compression ratio "
         "(raw aligned float32 / bytes incl. side information), precompute seconds and µs per pose ('pose' = random access "
         "to one synthesized pose, 'stream' = decoding the whole set per pose), as the multilinear paper's Table 1.\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_compression) continue;
        const eval::EvalSet& s = *r.set;
        o << "### " << s.spec.name << "\n\n";
        Table ct{{"method", "target", "ranks", "bytes", "ratio", "max cm", "rmse cm", "precompute s", "µs/pose", "access"}, {}, 3};
        for (const auto& row : r.compression.rows)
            ct.rows.push_back({row.method, row.target_cm == 0.0 ? "lossless/raw" : "≤ " + fmt(row.target_cm) + " cm" + (row.target_met ? "" : " (not met)"),
                               ranks_text(row.ranks), std::to_string(row.bytes), fixed(row.ratio, 2), fmt(row.stats.max_cm),
                               fmt(row.stats.rmse_cm), fmt(row.precompute_s), fmt(row.us_per_pose), row.access});
        std::string targets;
        for (double tcm : r.compression_targets) targets += (targets.empty() ? "" : ", ") + fmt(tcm) + " cm";
        o << ct.str() << "\n"
          << caption(info, s, "targets " + targets + "; raw aligned float32 " + std::to_string(r.compression.raw_bytes) +
                                  " bytes; side information " + std::to_string(r.compression.side_bytes) + " bytes charged to every row")
          << "\n![compression](compression_" << s.spec.name << ".svg)  \nNumbers: [compression_" << s.spec.name
          << ".csv](compression_" << s.spec.name << ".csv).\n\n";
    }

    // 7. Runtime
    o << "## 7. Runtime\n\n"
      << "Preprocessing (building the method on N samples) and synthesis (one whole aligned motion, divided by T) on "
         "evenly spread subsets of `" << e.runtime_set << "`, single thread, median of repeats (the geostatistical paper's "
         "Tables 1-2 report runtime and preprocessing per frame).\n\n";
    {
        Table rt{{"method", "N", "build s", "build µs per frame (÷ N·T)", "synthesis µs per frame"}, {}};
        for (const auto& row : e.runtime)
            rt.rows.push_back({row.method, std::to_string(row.samples), fmt(row.build_seconds), fmt(row.build_us_per_frame),
                               fmt(row.synth_us_per_frame)});
        const eval::EvalSet* rs = nullptr;
        for (const auto& r : e.sets)
            if (r.set->spec.name == e.runtime_set) rs = r.set.get();
        o << rt.str() << "\n";
        if (rs) o << caption(info, *rs, "wall-clock medians; load average at start " + info.load);
        o << "\n![synthesis time](runtime.svg) ![build time](runtime_build.svg)  \nNumbers: [runtime.csv](runtime.csv).\n\n";
    }

    o << losses_section(e);

    o << "## Caveats\n\n"
      << "- The DTW alignment (reference sample, warps) is computed once per set with all samples; the leave-one-out folds "
         "refit everything else (variograms, trends, Tucker bases, timing kernels) without the left-out sample. The Tucker "
         "ranks of each tucker-Ecm method are chosen once on the whole set (the bases are refitted per fold at those ranks).\n"
      << "- Errors are measured in aligned time (synthesized aligned poses against the sample's aligned poses), so "
         "timing errors show only in the duration column, not in the joint errors.\n"
      << "- The regions of section 2 use one reliability map (naive kriging kernel) for every method, so RBF and the "
         "nearest-neighbour blend are judged on kriging's ρ.\n"
      << "- Timings are wall-clock on a shared 2-core machine (see the load average above) and single-threaded.\n"
      << "- The `jumps` set mixes three subjects on subject 13's skeleton (see Data).\n";
    if (info.mode != "full")
        o << "- This is a **" << info.mode << "** run: fewer sets, folds and grid points than the full report.\n";
    return o.str();
}

}  // namespace

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

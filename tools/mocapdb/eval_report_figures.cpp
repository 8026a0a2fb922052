// The eval writers' CSV tables and SVG figures (eval_report_parts.hpp).
#include "eval_report_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "mocapdb/dataset/dropout_repair.hpp"
#include "svg_plot.hpp"

namespace mocapdb::cli::eval_report {

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
            o << "," << m.method << "," << m.sample_mean_cm(kk) << "," << m.sample_max_cm(kk) << ","
              << m.sample_pose_mean_cm(kk) << "," << m.sample_pose_max_cm(kk) << "," << m.duration_error_s(kk) << ","
              << (m.skating_cm_per_s.size() ? m.skating_cm_per_s(kk) : 0.0) << ","
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
        for (const auto& m : r.loo.methods)
            o << "," << m.frame_mean_cm(t) << "," << m.frame_max_cm(t) << "," << m.frame_pose_mean_cm(t);
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
        o << p.kept << "," << p.max_reliability << "," << p.greedy_mean_cm << "," << p.greedy_max_cm << ","
          << p.random_mean_cm << "," << p.greedy_pose_mean_cm << "," << p.random_pose_mean_cm << "\n";
    return o.str();
}

std::string compression_csv(const SetResults& r) {
    std::ostringstream o;
    o.precision(9);
    o << "method,target_cm,target_met,ranks,setting,bytes,ratio,rmse_cm,mean_cm,max_cm,precompute_s,us_per_pose,access\n";
    for (const auto& row : r.compression.rows)
        o << row.method << "," << row.target_cm << "," << (row.target_met ? 1 : 0) << "," << ranks_text(row.ranks)
          << "," << row.setting << "," << row.bytes << "," << row.ratio << "," << row.stats.rmse_cm << ","
          << row.stats.mean_cm << "," << row.stats.max_cm << "," << row.precompute_s << "," << row.us_per_pose << ","
          << row.access << "\n";
    return o.str();
}

std::string runtime_csv(const EvalResults& e) {
    std::ostringstream o;
    o.precision(9);
    o << "method,samples,frames,build_seconds,build_us_per_frame,synth_us_per_frame\n";
    for (const auto& row : e.runtime)
        o << row.method << "," << row.samples << "," << row.frames << "," << row.build_seconds << ","
          << row.build_us_per_frame << "," << row.synth_us_per_frame << "\n";
    return o.str();
}

// ---------------------------------------------------------------------------------------------------
// SVG

std::string loo_svg(const RunInfo& info, const SetResults& r, bool pose) {
    PlotSpec p;
    p.title = "Leave-one-out prediction on " + r.set->spec.name + ": " +
              (pose ? "root-relative pose" : "motion (with root trajectory)") + " error over time";
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
        auto it =
            std::find_if(p.series.begin(), p.series.end(), [&](const PlotSeries& s) { return s.name == row.method; });
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
        auto it =
            std::find_if(p.series.begin(), p.series.end(), [&](const PlotSeries& s) { return s.name == row.method; });
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

}  // namespace mocapdb::cli::eval_report

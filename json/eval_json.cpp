#include "mocapdb_json/eval_json.hpp"

#include <cmath>

#include "json_fields.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/eval/verdicts.hpp"

namespace mocapdb::json {

void write_eval_results(JsonWriter& j, const eval::EvalResults& e) {
    using eval::SetResults;
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
        fields::strings(j, "clips", s.clip_ids);
        j.key("samples").value(static_cast<long long>(s.size()));
        fields::repairs(j, s.set.repairs);
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
            j.key("best_pose_mean_cm")
                .value(h.best_pose_mean_cm)
                .key("median_pose_mean_cm")
                .value(h.median_pose_mean_cm);
            j.key("best_p").value(h.best.paper_p()).key("best_range").value(h.best.range);
            j.key("best_nugget_share").value(h.best.nugget).key("best_anisotropy").value(h.best_anisotropy);
            j.end_object();
        }
        if (r.has_nested) {
            // The predictor synthesis chooses, by nested cross-validation (the whole document: mocapdb eval --set).
            const eval::SetEvaluation& n = r.nested;
            const eval::ChosenEvaluation& c = n.chosen;
            j.key("nested_choice").begin_object();
            j.key("folds").value(n.folds.size()).key("inner_folds").value(n.inner_folds);
            j.key("methods").begin_array();
            for (std::size_t q = 0; q < n.methods.size(); ++q)
                j.begin_object()
                    .key("name")
                    .value(n.methods[q].spec.name)
                    .key("pose_mean_cm")
                    .value(n.methods[q].loo.pose_mean_cm)
                    .key("picked")
                    .value(c.counts[q])
                    .end_object();
            j.end_array();
            j.key("averaged").value(c.counts.size() > n.methods.size() ? c.counts[n.methods.size()] : 0);
            j.key("chosen_pose_mean_cm").value(c.pose_mean).key("best").value(n.methods[c.best].spec.name);
            j.key("chosen_minus_best_cm").value(c.diff_mean_cm);
            if (c.diff_se_cm) j.key("paired_se_cm").value(*c.diff_se_cm);
            if (n.learned_metric) {
                const eval::LearnedMetricEvaluation& l = *n.learned_metric;
                j.key("learned_metric").begin_object();
                j.key("kind").value(l.kind).key("pose_mean_cm").value(l.pose_mean);
                j.key("fold_factors").begin_array();
                for (const VecX& f : l.factors) {
                    j.begin_array();
                    for (Eigen::Index a = 0; a < f.size(); ++a) j.value(f(a));
                    j.end_array();
                }
                j.end_array();
                j.end_object();
            }
            j.end_object();
        }
        if (r.has_edge) {
            // Where rho warns (eval/edge_evaluation.hpp): calibrated on one draw, judged on a fresh one.
            const eval::EdgeEvaluation& g = r.edge;
            const auto rates = [&j](const char* key, const workflow::FlagRates& f) {
                j.key(key).begin_object();
                j.key("misses").value(f.misses).key("flagged_misses").value(f.flagged_misses);
                j.key("inside_hits").value(f.inside_hits).key("flagged_inside_hits").value(f.flagged_inside_hits);
                j.key("detection").value(f.detection).key("false_alarms").value(f.false_alarms);
                j.end_object();
            };
            j.key("edge_warning").begin_object();
            j.key("calibration");
            fields::edge_warning(j, g.calibration);
            j.key("fresh_inside").value(g.fresh_inside).key("fresh_beyond").value(g.fresh_beyond);
            j.key("shell_sd").value(g.options.shell_sd);
            rates("calibrated", g.calibrated);
            j.key("fixed_rho_threshold").value(g.fixed_threshold);
            rates("fixed", g.fixed);
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
                fields::numbers(j, r.loo.original_skating_cm_per_s);
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
                fields::numbers(j, m.sample_mean_cm);
                j.key("sample_max_cm");
                fields::numbers(j, m.sample_max_cm);
                j.key("frame_mean_cm");
                fields::numbers(j, m.frame_mean_cm);
                j.key("frame_max_cm");
                fields::numbers(j, m.frame_max_cm);
                j.key("sample_pose_mean_cm");
                fields::numbers(j, m.sample_pose_mean_cm);
                j.key("sample_pose_max_cm");
                fields::numbers(j, m.sample_pose_max_cm);
                j.key("frame_pose_mean_cm");
                fields::numbers(j, m.frame_pose_mean_cm);
                j.key("duration_error_s");
                fields::numbers(j, m.duration_error_s);
                if (m.skating_cm_per_s.size()) {
                    j.key("skating_cm_per_s");
                    fields::numbers(j, m.skating_cm_per_s);
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
            fields::numbers(j, c.scale);
            j.key("reliability");
            fields::numbers(j, c.reliability);
            j.key("rho_outside_3sd").value(c.rho_outside_3sd);
            if (c.loo_mean_z2 && std::isfinite(*c.loo_mean_z2)) j.key("loo_mean_z2").value(*c.loo_mean_z2);
            j.key("methods").begin_array();
            for (const auto& m : c.methods) {
                j.begin_object().key("method").value(m.method);
                j.key("failures").value(static_cast<long long>(m.failures));
                j.key("pearson_rho_error").value(m.pearson);
                j.key("own_reliability").value(m.own_reliability);
                if (m.rho_outside_3sd) j.key("rho_outside_3sd").value(*m.rho_outside_3sd);
                j.key("seconds").value(m.seconds);
                j.key("regions").begin_array();
                std::vector<eval::RegionStats> all = m.regions;
                all.push_back(m.all);
                for (const auto& g : all) {
                    j.begin_object()
                        .key("rho_at_least")
                        .value(g.threshold)
                        .key("points")
                        .value(static_cast<long long>(g.points));
                    j.key("max").value(g.max).key("rmse").value(g.rmse).key("axis_rmse");
                    fields::numbers(j, g.axis_rmse);
                    j.end_object();
                }
                j.end_array();
                j.key("error");
                fields::numbers(j, m.error);
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
                    .key("kept")
                    .value(static_cast<long long>(p.kept))
                    .key("max_reliability")
                    .value(p.max_reliability)
                    .key("greedy_mean_cm")
                    .value(p.greedy_mean_cm)
                    .key("greedy_max_cm")
                    .value(p.greedy_max_cm)
                    .key("random_mean_cm")
                    .value(p.random_mean_cm)
                    .key("greedy_pose_mean_cm")
                    .value(p.greedy_pose_mean_cm)
                    .key("random_pose_mean_cm")
                    .value(p.random_pose_mean_cm)
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
            .key("method")
            .value(row.method)
            .key("samples")
            .value(static_cast<long long>(row.samples))
            .key("frames")
            .value(static_cast<long long>(row.frames))
            .key("build_seconds")
            .value(row.build_seconds)
            .key("build_us_per_frame")
            .value(row.build_us_per_frame)
            .key("synth_us_per_frame")
            .value(row.synth_us_per_frame)
            .end_object();
    j.end_array().end_object();
    j.end_object();
}

}  // namespace mocapdb::json

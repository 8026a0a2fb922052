#include "mocapdb_json/set_evaluation_json.hpp"

#include <optional>

#include "json_fields.hpp"

namespace mocapdb::json {
namespace {

using fields::numbers;

void write_method(JsonWriter& j, const eval::MethodEvaluation& m) {
    const eval::LooMethodResult& r = m.loo;
    j.begin_object();
    j.key("name").value(m.spec.name);
    j.key("kind").value(eval::to_string(m.spec.kind));
    if (m.spec.kind == eval::MethodKind::TuckerKriging) {
        j.key("ranks").begin_array();
        for (Eigen::Index x : m.spec.ranks) j.value(static_cast<long long>(x));
        j.end_array();
    }
    j.key("pose_mean_cm").value(r.pose_mean_cm);
    j.key("pose_max_cm").value(r.pose_max_cm);
    j.key("motion_mean_cm").value(r.mean_cm);
    j.key("motion_max_cm").value(r.max_cm);
    j.key("duration_error_s").value(r.duration_error_s.size() ? r.duration_error_s.mean() : 0.0);
    j.key("hit_rate").value(m.hit_rate);
    j.key("rho_pose_pearson").value(m.rho_pose_pearson);
    j.key("build_s").value(r.build_seconds);
    numbers(j, "sample_pose_mean_cm", r.sample_pose_mean_cm);
    numbers(j, "sample_motion_mean_cm", r.sample_mean_cm);
    j.end_object();
}

}  // namespace

void write_twins(JsonWriter& j, const SampleTwins& twins, const std::vector<std::string>& labels) {
    j.key("twins").begin_array();
    for (const auto& group : twins.groups) {
        j.begin_object().key("samples").begin_array();
        for (std::size_t i : group) j.value(i);
        j.end_array().key("labels").begin_array();
        for (std::size_t i : group) j.value(labels.at(i));
        j.end_array().end_object();
    }
    j.end_array();
}

void write_set_evaluation(JsonWriter& j, const eval::SetEvaluation& e) {
    j.begin_object();
    j.key("set").value(e.set);
    j.key("file").value(e.file);
    j.key("samples").value(e.labels.size());
    j.key("frames").value(static_cast<long long>(e.frames));
    j.key("folds").value(e.folds.size());
    j.key("fold_labels").begin_array();
    for (Eigen::Index i : e.folds) j.value(e.labels[static_cast<std::size_t>(i)]);
    j.end_array();
    j.key("inner_folds").value(e.inner_folds);
    j.key("parameters_measured").value(e.parameters_measured);
    j.key("hit_share").value(e.hit_share);
    j.key("parameters").begin_array();
    for (std::size_t p = 0; p < e.parameter_names.size(); ++p) {
        j.begin_object().key("name").value(e.parameter_names[p]).key("unit").value(e.parameter_units[p]);
        j.key("hit_tolerance").value(p < e.hit_tolerance.size() ? e.hit_tolerance[p] : std::nullopt);
        j.end_object();
    }
    j.end_array();
    write_twins(j, e.twins, e.labels);
    j.key("methods").begin_array();
    for (const eval::MethodEvaluation& m : e.methods) write_method(j, m);
    j.end_array();
    const eval::ChosenEvaluation& c = e.chosen;
    j.key("chosen").begin_object();
    j.key("pose_mean_cm").value(c.pose_mean);
    j.key("pose_max_cm").value(c.pose_max);
    j.key("motion_mean_cm").value(c.motion_mean);
    j.key("motion_max_cm").value(c.motion_max);
    j.key("hit_rate").value(c.hit_rate);
    j.key("picks").begin_object();
    for (std::size_t q = 0; q < e.methods.size(); ++q) j.key(e.methods[q].spec.name).value(c.counts[q]);
    j.key("average").value(c.counts.size() > e.methods.size() ? c.counts[e.methods.size()] : 0);
    j.end_object();
    j.key("fold_picks").begin_array();
    for (const std::string& name : c.pick_names) j.value(name);
    j.end_array();
    j.key("best_single").value(e.methods[c.best].spec.name);
    j.key("diff_mean_cm").value(c.diff_mean_cm);
    j.key("diff_se_cm").value(c.diff_se_cm);
    numbers(j, "sample_pose_mean_cm", c.pose_mean_cm);
    j.end_object();
    j.key("not_evaluated").begin_array();
    for (const std::string& s : e.not_evaluated) j.value(s);
    j.end_array();
    j.end_object();
}

}  // namespace mocapdb::json

#include "mocapdb_json/synthesis_json.hpp"

#include <cmath>

#include "json_fields.hpp"

namespace mocapdb::json {
namespace {

// The judgement behind a synthesis's warnings (workflow/synthesis_warnings.hpp).
void warning_fields(JsonWriter& j, const workflow::SynthesisWarnings& w) {
    j.key("reliability_threshold").value(synthesis::rho_threshold(w.threshold));
    j.key("variance_ratio").value(w.variance_ratio);
    j.key("max_variance_ratio").value(w.threshold.variance_ratio);
    j.key("beyond_sd").value(w.beyond_sd);
    j.key("max_beyond_sd");
    if (std::isfinite(w.threshold.beyond_sd)) j.value(w.threshold.beyond_sd);
    else j.null();
    j.key("nearby_misses").value(static_cast<long long>(w.nearby_misses));
    j.key("min_nearby_misses");  // null: no vote rule
    if (w.threshold.votes > 0) j.value(static_cast<long long>(w.threshold.votes));
    else j.null();
    j.key("reliability_calibrated").value(w.calibrated);
    j.key("flagged").value(w.flagged());
}

}  // namespace

void write_edge_warning(JsonWriter& j, const synthesis::EdgeWarning& w) { fields::edge_warning(j, w); }

void write_synthesis(JsonWriter& j, const SynthReport& r, const workflow::SynthOutcome& o) {
    const VecX& c = o.requested;
    j.begin_object();
    j.key("set").value(r.set);
    j.key("model").value(r.model);
    j.key("ranks").begin_array();
    for (Eigen::Index k : r.ranks) j.value(static_cast<long long>(k));
    j.end_array();
    j.key("parameters").begin_array();
    for (Eigen::Index k = 0; k < c.size(); ++k) {
        const auto p = static_cast<std::size_t>(k);
        const bool categorical = p < r.parameter_levels.size() && !r.parameter_levels[p].empty();
        j.begin_object();
        j.key("name").value(r.parameter_names[p]);
        j.key("unit").value(r.parameter_units[p]);
        if (categorical) {  // the level by name (c holds its index)
            j.key("kind").value("categorical");
            j.key("requested").value(r.parameter_levels[p][static_cast<std::size_t>(c(k))]);
            fields::strings(j, "levels", r.parameter_levels[p]);
        } else {
            j.key("kind").value("numeric");
            j.key("requested").value(c(k));
        }
        if (p < o.parameter_measured.size() && o.parameter_measured[p])
            j.key("measured").value(*o.parameter_measured[p]);
        for (const workflow::ParameterMiss& m : r.judged.misses)
            if (m.parameter == p) {
                j.key("missed").value(true);
                j.key("tolerance").value(m.tolerance);
            }
        j.end_object();
    }
    j.end_array();
    j.key("measured").begin_object();  // every applicable extractor's columns (workflow/synthesis_step.hpp)
    for (const workflow::Measurement& m : o.measurements) j.key(m.name).value(m.value);
    j.end_object();
    j.key("measured_units").begin_object();
    for (const workflow::Measurement& m : o.measurements) j.key(m.name).value(m.unit);
    j.end_object();
    j.key("reliability").value(o.reliability);
    warning_fields(j, r.judged);
    fields::strings(j, "warnings", r.warnings);
    j.key("frames").value(static_cast<long long>(o.clip.frame_count()));
    j.key("frame_rate").value(o.clip.frame_rate);
    j.key("duration_s").value(o.clip.duration());
    j.key("clamped_increments").value(static_cast<long long>(o.timing.clamped));
    j.key("load_s").value(r.load_s);
    j.key("precompute_s").value(r.precompute_s);
    j.key("kernel_stored").value(r.kernel_stored);
    j.key("local_neighbours").value(r.local_neighbours);
    j.key("predictor").value(r.predictor);
    j.key("predictor_choice");
    if (r.predictor_choice) fields::predictor_choice(j, *r.predictor_choice);
    else j.null();
    j.key("synth_s").value(o.seconds);
    j.key("output").value(r.output);
    j.end_object();
}

void write_pose_query(JsonWriter& j, const PoseQuery& q) {
    const Skeleton& sk = *q.skeleton;
    j.begin_object();
    j.key("set").value(q.set);
    j.key("model").value(q.model);
    j.key("predictor").value(q.predictor);
    j.key("frame").value(q.frame);
    j.key("reliability").value(q.reliability);
    warning_fields(j, q.judged);
    fields::strings(j, "warnings", q.warnings);
    if (q.joints) {
        const MatX& p = q.joint_positions;
        j.key("unit").value("cm");
        j.key("joints").begin_array();
        for (std::size_t k = 0; k < sk.size(); ++k) {
            const auto r = static_cast<Eigen::Index>(3 * k);
            j.begin_object();
            j.key("name").value(sk.joint(k).name);
            j.key("position").begin_array().value(p(r, 0)).value(p(r + 1, 0)).value(p(r + 2, 0)).end_array();
            j.end_object();
        }
        j.end_array();
    } else {
        j.key("unit").value("cm, rad");
        j.key("channels").begin_array();
        for (std::size_t k = 0; k < sk.size(); ++k) {
            const Joint& joint = sk.joint(k);
            for (std::size_t m = 0; m < joint.channels.size(); ++m) {
                j.begin_object();
                j.key("joint").value(joint.name);
                j.key("channel").value(to_string(joint.channels[m]));
                j.key("value").value(q.channels(0, static_cast<Eigen::Index>(sk.first_channel(k) + m)));
                j.end_object();
            }
        }
        j.end_array();
    }
    j.key("pose_vector");
    fields::numbers(j, q.pose);
    j.end_object();
}

void write_reliability_map(JsonWriter& j, const ReliabilityMapReport& r, const workflow::ReliabilityMap& m) {
    j.begin_object();
    j.key("set").value(r.set);
    j.key("model").value(r.model);
    j.key("x").value(r.x);
    j.key("y").value(r.y);
    j.key("cells").value(static_cast<long long>(m.rho.size()));
    j.key("min").value(m.rho_min);
    j.key("max").value(m.rho_max);
    j.key("mean").value(m.rho_mean);
    j.key("fraction_ge_0_85").value(m.fraction_trusted);
    j.key("svg").value(r.svg);
    if (!r.csv.empty()) j.key("csv").value(r.csv);
    j.end_object();
}

void write_reduction(JsonWriter& j, const ReductionReport& r, const workflow::ReductionOutcome& o) {
    const kriging::ReductionResult& res = o.result;
    const std::vector<std::string>& labels = o.labels;
    j.begin_object();
    j.key("set").value(r.set);
    j.key("tau").value(r.tau);
    j.key("samples").value(static_cast<long long>(o.set.samples.size()));
    j.key("kept").value(static_cast<long long>(res.kept.size()));
    j.key("stopped_on_threshold").value(res.stopped_on_threshold);
    j.key("removed").begin_array();
    for (std::size_t k = 0; k < res.removed.size(); ++k) {
        j.begin_object();
        j.key("sample").value(labels[static_cast<std::size_t>(res.removed[k])]);
        j.key("reliability").value(res.removed_reliability[k]);
        j.end_object();
    }
    j.end_array();
    j.key("kept_samples").begin_array();
    for (Eigen::Index k : res.kept) j.value(labels[static_cast<std::size_t>(k)]);
    j.end_array();
    j.key("max_reliability").begin_array();
    for (double v : res.max_reliability) j.value(v);
    j.end_array();
    if (r.written_set) j.key("written_set").value(*r.written_set);
    j.key("seconds").value(r.seconds);
    j.end_object();
}

}  // namespace mocapdb::json

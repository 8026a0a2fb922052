#include "mocapdb_json/gp_json.hpp"

#include "json_fields.hpp"

namespace mocapdb::json {
namespace {

using namespace mocapdb::gp;

/// The fit's members (of the open object).
void write_model(JsonWriter& w, const FitResult& f) {
    w.key("log_likelihood").value(f.log_likelihood);
    w.key("status").value(to_string(f.status));
    w.key("seconds").value(f.seconds);
    w.key("evaluations").value(f.evaluations);
    w.key("restarts").begin_array();
    for (const auto& r : f.restarts) {
        w.begin_object();
        w.key("log_likelihood").value(r.log_likelihood);
        w.key("status").value(to_string(r.status));
        w.key("message").value(r.message);
        w.key("iterations").value(r.iterations);
        w.key("evaluations").value(r.evaluations);
        w.key("seconds").value(r.seconds);
        w.end_object();
    }
    w.end_array();
    w.key("noise_variance").begin_array();
    const VecX noise = f.model.noise_variance();
    for (Eigen::Index i = 0; i < noise.size(); ++i) w.value(noise[i]);
    w.end_array();
    w.key("parameters").begin_object();
    const auto names = f.model.parameter_names();
    const VecX p = f.model.parameters();
    for (std::size_t i = 0; i < names.size(); ++i) w.key(names[i]).value(p[static_cast<Eigen::Index>(i)]);
    w.end_object();
}

/// The data's members (of the open object).
void write_data(JsonWriter& w, const MotionData& md) {
    fields::strings(w, "children", md.child_names);
    if (!md.data.groups.empty()) {
        w.key("groups").begin_array();
        for (std::size_t g : md.data.groups) w.value(static_cast<long long>(g));
        w.end_array();
    }
    w.key("frames").value(static_cast<long long>(md.data.frames()));
    w.key("duration_s").value(md.data.times[md.data.times.size() - 1]);
    fields::strings(w, "dofs", md.dof_names);
}

void mean_and_std(JsonWriter& w, const char* key, const MeanStd& m) {
    w.key(key).begin_object().key("mean").value(m.mean).key("std").value(m.std).end_object();
}

/// An undefined summary keeps both keys, null.
void mean_and_std(JsonWriter& w, const char* key, const std::optional<MeanStd>& m) {
    if (m) return mean_and_std(w, key, *m);
    w.key(key).begin_object().key("mean").null().key("std").null().end_object();
}

void write_runs(JsonWriter& w, const ModelRuns& m) {
    w.begin_object();
    mean_and_std(w, "mse", m.mse);
    mean_and_std(w, "smse", m.smse);
    mean_and_std(w, "msll", m.msll);
    w.key("fit_seconds").value(m.fit_seconds);
    fields::strings(w, "fit_status", m.fit_status);
    w.end_object();
}

/// "mohgp" and "moa": the two models' runs.
void write_both_models(JsonWriter& w, const ModelRuns& mohgp, const ModelRuns& moa) {
    w.key("mohgp");
    write_runs(w, mohgp);
    w.key("moa");
    write_runs(w, moa);
}

void write_synthesis_scores(JsonWriter& w, const SynthesisScores& s) {
    w.begin_array();
    for (std::size_t i = 0; i < s.mcc.size(); ++i) {
        w.begin_object();
        mean_and_std(w, "mcc", s.mcc[i]);
        mean_and_std(w, "mlc", s.mlc[i]);
        w.end_object();
    }
    w.end_array();
}

void fit_object(JsonWriter& w, const char* key, const FitResult& f) {
    w.key(key).begin_object();
    write_model(w, f);
    w.end_object();
}

}  // namespace

void write_gp_fit(JsonWriter& w, const std::string& model, const MotionData& md, const FitResult& f) {
    w.begin_object();
    w.key("model").value(model);
    write_data(w, md);
    write_model(w, f);
    w.end_object();
}

void write_gp_interpolation(JsonWriter& w, const std::string& model, const MotionData& md, const std::string& child,
                            const ChildInterpolation& c) {
    const InterpolationScores& s = c.scores;
    const GaussianPrediction& p = c.prediction;
    w.begin_object();
    w.key("model").value(model);
    write_data(w, md);
    w.key("child").value(child);
    w.key("observed_frames").begin_array();
    for (std::size_t i = 0; i < c.observed.size(); ++i)
        if (c.observed[i]) w.value(static_cast<long long>(i));
    w.end_array();
    w.key("mse").value(s.mse);
    w.key("smse").value(s.smse);
    w.key("msll").value(s.msll);
    w.key("predicted_values").value(static_cast<long long>(s.points));
    fit_object(w, "fit", c.fit);
    w.key("mean").begin_array();  // normalized units, D rows of T values
    for (Eigen::Index i = 0; i < p.mean.rows(); ++i) {
        w.begin_array();
        for (Eigen::Index t = 0; t < p.mean.cols(); ++t) w.value(p.mean(i, t));
        w.end_array();
    }
    w.end_array();
    w.end_object();
}

void write_gp_samples(JsonWriter& w, const std::string& model, const MotionData& md,
                      const std::vector<std::string>& files, const FitResult& f) {
    w.begin_object();
    w.key("model").value(model);
    write_data(w, md);
    fields::strings(w, "files", files);
    fit_object(w, "fit", f);
    w.end_object();
}

void write_gp_artificial(JsonWriter& w, const GpArtificialReport& a, const std::vector<ArtificialResult>& results) {
    w.begin_object();
    w.key("experiment").value("artificial");
    w.key("runs").value(static_cast<long long>(a.runs));
    w.key("q").value(static_cast<long long>(a.q));
    w.key("kernel").value(a.kernel);
    w.key("tests").begin_array();
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        w.begin_object();
        w.key("test").value(static_cast<long long>(a.tests[i]));
        w.key("noise").value(r.config.noise);
        w.key("outputs").value(static_cast<long long>(r.config.outputs));
        w.key("children").value(static_cast<long long>(r.config.children));
        write_both_models(w, r.mohgp, r.moa);
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

void write_gp_replicates(JsonWriter& w, const GpReplicatesReport& r, const MotionData& all,
                         const ReplicateExperiment& e) {
    const ReplicateInterpolation& interp = e.interpolation;
    w.begin_object();
    w.key("experiment").value("replicates");
    w.key("layers").value(static_cast<long long>(r.layers));
    write_data(w, all);
    w.key("test_child").value(r.test_child);
    fit_object(w, "mohgp_fit", interp.mohgp_fit);
    fit_object(w, "moa_fit", interp.moa_fit);
    w.key("interpolation").begin_array();
    for (const auto& row : interp.rows) {
        w.begin_object();
        w.key("observed").value(static_cast<long long>(row.observed));
        write_both_models(w, row.mohgp, row.moa);
        w.end_object();
    }
    w.end_array();
    if (e.synthesis) {
        const SynthesisResult& synth = *e.synthesis;
        w.key("synthesis").begin_object();
        w.key("samples").value(static_cast<long long>(r.samples));
        fields::strings(w, "real", r.real);
        w.key("mohgp");
        write_synthesis_scores(w, synth.mohgp);
        w.key("moa");
        write_synthesis_scores(w, synth.moa);
        w.key("control");
        write_synthesis_scores(w, synth.control);
        w.key("mohgp_fit_seconds").value(synth.mohgp_fit.seconds);
        w.key("moa_fit_seconds").value(synth.moa_fit.seconds);
        w.end_object();
    }
    w.end_object();
}

}  // namespace mocapdb::json

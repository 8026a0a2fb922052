#include "mocapdb/gp/model_steps.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/child_selection.hpp"

namespace mocapdb::gp {
namespace {

std::vector<TermSummary> summarize_layer(const Lmc& lmc) {
    std::vector<TermSummary> out;
    for (const LmcTerm& t : lmc.terms)
        out.push_back({t.kernel, std::exp(t.log_lengthscale), t.coregionalization().diagonal().mean()});
    return out;
}

}  // namespace

FitResult fit_model(const HgpData& data, const ModelSpec& spec, const FitOptions& options) {
    return fit(data, initial_model(data, spec), options);
}

ChildInterpolation interpolate_child(const HgpData& data, std::size_t child, std::size_t observed,
                                     const ModelSpec& spec, const FitOptions& fit_options, std::uint64_t mask_seed) {
    if (data.child_count() < 2)
        throw InvalidArgument("interpolating a child needs at least 2 children (the others train the model)");
    if (child >= data.child_count())
        throw InvalidArgument("child " + std::to_string(child) + " of only " + std::to_string(data.child_count()));
    if (observed + 2 > data.frames())
        throw InvalidArgument(std::to_string(observed) + " observed frames leave fewer than 2 of " +
                              std::to_string(data.frames()) + " frames to predict");
    ChildInterpolation out;
    const HgpData training = without_child(data, child);
    out.fit = fit_model(training, spec, fit_options);
    out.observed = random_observed_frames(data.frames(), observed, mask_seed);
    out.scores = score_interpolation(out.fit.model, data, child, out.observed);
    HgpData d = data;
    d.observed.assign(d.child_count(), {});
    d.observed[child] = out.observed;
    out.prediction = predict_child(out.fit.model, d, child, d.times);
    return out;
}

NewChildren sample_new_children(const HgpData& data, const ModelSpec& spec, const FitOptions& fit_options,
                                std::size_t count, const SampleOptions& sample_options) {
    NewChildren out;
    out.fit = fit_model(data, spec, fit_options);
    out.samples = sample_children(out.fit.model, data, data.times, count, sample_options);
    out.trend = synthesis_trend(out.fit.model, data, data.times);
    return out;
}

ReplicateSplit split_replicates(const HgpData& all, std::size_t training) {
    if (training > all.child_count())
        throw InvalidArgument("training children: " + std::to_string(training) + " of only " +
                              std::to_string(all.child_count()));
    ReplicateSplit out;
    out.training.times = all.times;
    out.training.children.assign(all.children.begin(), all.children.begin() + static_cast<std::ptrdiff_t>(training));
    out.real.assign(all.children.begin() + static_cast<std::ptrdiff_t>(training), all.children.end());
    return out;
}

ReplicateExperiment run_replicate_experiment(const HgpData& training, const std::vector<MatX>& real,
                                             std::size_t test_child, const std::vector<std::size_t>& observed_counts,
                                             std::size_t samples, const ExperimentOptions& options) {
    ReplicateExperiment out;
    out.interpolation = run_replicate_interpolation(training, test_child, observed_counts, options);
    if (!real.empty()) out.synthesis = run_synthesis(training, real, {}, samples, options);
    return out;
}

ModelSummary summarize_model(const HgpModel& model) {
    ModelSummary s;
    if (model.hierarchical) s.parent = summarize_layer(model.parent);
    if (model.grouped) s.group = summarize_layer(model.group);
    s.child = summarize_layer(model.child);
    const VecX noise = model.noise_variance();
    s.noise_mean = noise.mean();
    s.noise_min = noise.minCoeff();
    s.noise_max = noise.maxCoeff();
    return s;
}

}  // namespace mocapdb::gp

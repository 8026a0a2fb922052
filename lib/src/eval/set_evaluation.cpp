#include "mocapdb/eval/set_evaluation.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/stored_eval_set.hpp"
#include "mocapdb/gp/gp_metrics.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/edge_calibration.hpp"

namespace mocapdb::eval {
namespace {

using workflow::parameter_distance;

// 1 when every checked parameter measured back within its tolerance, else 0 (undefined = miss).
VecX fold_hits(const std::vector<std::vector<std::optional<double>>>& measured, const MatX& requested,
               const std::vector<std::optional<double>>& tolerance, const VecX& periods) {
    const auto params = static_cast<Eigen::Index>(tolerance.size());
    VecX hits(static_cast<Eigen::Index>(measured.size()));
    for (Eigen::Index k = 0; k < hits.size(); ++k) {
        const std::vector<std::optional<double>>& values = measured[static_cast<std::size_t>(k)];
        bool hit = true;
        for (Eigen::Index p = 0; p < params; ++p) {
            const auto at = static_cast<std::size_t>(p);
            const std::optional<double>& tol = tolerance[at];
            if (!tol) continue;
            const std::optional<double> v = at < values.size() ? values[at] : std::nullopt;
            const double period = periods.size() == params ? periods(p) : 0.0;
            if (!v || !(parameter_distance(*v, requested(k, p), period) <= *tol)) hit = false;
        }
        hits(k) = hit ? 1.0 : 0.0;
    }
    return hits;
}

std::optional<double> standard_error(const VecX& d) {
    if (d.size() < 2) return std::nullopt;
    const VecX c = d.array() - d.mean();
    return std::sqrt(c.squaredNorm() / static_cast<double>(d.size() - 1)) / std::sqrt(static_cast<double>(d.size()));
}

std::vector<std::vector<Eigen::Index>> twin_lists(const SampleTwins& twins, std::size_t n) {
    std::vector<std::vector<Eigen::Index>> out(n);
    const auto partners = twins.partners(n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j : partners[i]) out[i].push_back(static_cast<Eigen::Index>(j));
    return out;
}

// What synthesis would choose on `training` alone (synthesis/predictor_choice.hpp), as `compress` does on
// a whole set: the kriging candidate has the variogram fitted to the samples' position-weighted, centred
// aligned poses (the naive model's, whose distances the Tucker core slices keep), and the candidates are
// scored on their posture (the root's path left out), as the outer pose error.
synthesis::PredictorChoice synthesis_choice(const EvalSet& training,
                                            const std::vector<std::vector<Eigen::Index>>& twins, std::size_t folds) {
    const AlignedSet& a = training.aligned;
    const VecX weight = compression::position_error_weights(*training.skeleton);
    const Tensor3 x = compression::weighted_centred(a.tensor, compression::dof_means(a.tensor), weight);
    const MatX values = Eigen::Map<const MatX>(x.data(), a.dofs() * a.frames(), a.samples()).transpose();
    const kriging::ControlScaling scaling =
        kriging::ControlScaling::from_data(training.set.parameters, training.set.parameter_periods);
    const MatX xc = scaling.apply(training.set.parameters);
    const synthesis::SynthesisOptions options;
    const synthesis::KernelFit kernel =
        synthesis::fit_coefficient_kernel(xc, values, options, "nested cross-validation");
    std::vector<std::vector<std::size_t>> partners(twins.size());
    for (std::size_t i = 0; i < twins.size(); ++i)
        for (const Eigen::Index j : twins[i]) partners[i].push_back(static_cast<std::size_t>(j));
    synthesis::PredictorChoiceOptions choice;
    choice.folds = folds;
    choice.elements_per_sample = static_cast<double>(a.dofs() * a.frames());
    return synthesis::choose_predictor(xc, synthesis::posture_values(values, a.dofs()), kernel.variogram,
                                       options.kriging, partners, choice);
}

MethodKind method_kind(synthesis::Predictor predictor) {
    switch (predictor) {
        case synthesis::Predictor::Kriging: return MethodKind::NaiveKriging;
        case synthesis::Predictor::Rbf: return MethodKind::Rbf;
        case synthesis::Predictor::Trend: return MethodKind::TrendOnly;
        case synthesis::Predictor::Average: break;
    }
    return MethodKind::Average;
}

// The method that evaluates `predictor` (the naive model's kriging, RBF or the trend).
std::size_t method_of(const std::vector<MethodSpec>& methods, synthesis::Predictor predictor) {
    const MethodKind kind = method_kind(predictor);
    for (std::size_t q = 0; q < methods.size(); ++q)
        if (methods[q].kind == kind) return q;
    throw InvalidArgument(std::string("nested cross-validation: no method evaluates the predictor '") +
                          synthesis::to_string(predictor) + "' (set_methods gives one for each)");
}

// Nested CV: per outer fold, the predictor synthesis chooses on the fold's training samples alone (its
// inner cross-validation never sees the held-out sample or its twins).
std::vector<synthesis::PredictorChoice> nested_choices(const EvalSet& set, const std::vector<Eigen::Index>& folds,
                                                       const std::vector<std::vector<Eigen::Index>>& twins,
                                                       std::size_t inner_folds, const ProgressCallback& progress,
                                                       std::uint64_t done, std::uint64_t total) {
    std::vector<synthesis::PredictorChoice> out;
    for (Eigen::Index i : folds) {
        const std::vector<Eigen::Index> keep = loo_training(set.size(), i, twins);
        const EvalSet training = subset(set, keep);
        out.push_back(synthesis_choice(training, subset_twins(twins, keep), inner_folds));
        if (progress) progress({++done, total, "nested " + set.labels[static_cast<std::size_t>(i)]});
    }
    return out;
}

// The learned metric of LearnedMetricEvaluation applied to normalized points x (rows), for a training
// range [lo, hi] of the single parameter (warp) or the per-axis factors (ard).
MatX learned_metric_points(const MatX& x, const VecX& factors, bool warp, double lo, double hi) {
    MatX out = x;
    if (!warp) {
        for (Eigen::Index a = 0; a < x.cols(); ++a) out.col(a) *= factors(a);
        return out;
    }
    const double span = hi > lo ? hi - lo : 1.0;
    for (Eigen::Index r = 0; r < x.rows(); ++r) {
        const double u = 2.0 * (x(r, 0) - lo) / span - 1.0;
        out(r, 0) = lo + 0.5 * span * (std::copysign(std::pow(std::abs(u), factors(0)), u) + 1.0);
    }
    return out;
}

// One outer fold of LearnedMetricEvaluation: the metric with the lowest leave-one-out MSE of the training
// values, its kriging's pose error at the left-out sample, and the chosen factors.
std::pair<double, VecX> learned_metric_fold(const EvalSet& set, Eigen::Index left_out,
                                            const std::vector<Eigen::Index>& keep) {
    const EvalSet training = subset(set, keep);
    const AlignedSet& a = training.aligned;
    const VecX weight = compression::position_error_weights(*training.skeleton);
    const Tensor3 t = compression::weighted_centred(a.tensor, compression::dof_means(a.tensor), weight);
    const MatX values = Eigen::Map<const MatX>(t.data(), a.dofs() * a.frames(), a.samples()).transpose();
    const kriging::ControlScaling scaling = kriging::ControlScaling::from_data(training.set.parameters);
    const MatX xc = scaling.apply(training.set.parameters);
    VecX query;
    scaling.apply_point(set.set.parameters.row(left_out).transpose(), query);
    const bool warp = xc.cols() == 1;
    const double lo = xc.col(0).minCoeff(), hi = xc.col(0).maxCoeff();
    const synthesis::SynthesisOptions options;
    const auto fit = [&](const VecX& factors) {
        const synthesis::KernelFit k = synthesis::fit_coefficient_kernel(
            learned_metric_points(xc, factors, warp, lo, hi), values, options, "learned metric");
        const double mse = k.exponent_loo_mse.size() > 0 ? k.exponent_loo_mse.minCoeff() : HUGE_VAL;
        return std::make_pair(std::isfinite(mse) ? mse : HUGE_VAL, k.variogram);
    };
    VecX factors = VecX::Ones(xc.cols());
    auto best = fit(factors);
    const std::vector<double> grid =
        warp ? std::vector<double>{0.5, 0.7, 1.4, 2.0} : std::vector<double>{0.25, 0.35, 0.5, 0.7, 1.4, 2.0, 2.8, 4.0};
    for (Eigen::Index axis = warp ? 0 : 1; axis < xc.cols(); ++axis) {
        const double kept = factors(axis);
        double chosen = kept;
        for (const double g : grid) {
            factors(axis) = g;
            const auto trial = fit(factors);
            if (trial.first < best.first) {
                best = trial;
                chosen = g;
            }
        }
        factors(axis) = chosen;
    }
    const MatX x = learned_metric_points(xc, factors, warp, lo, hi);
    const MatX q = learned_metric_points(query.transpose(), factors, warp, lo, hi);
    const VecX w = kriging::Kriging::build(x, best.second, options.kriging).weights(q.row(0).transpose());
    MatX blend = MatX::Zero(a.dofs(), a.frames());
    for (Eigen::Index k = 0; k < w.size(); ++k) blend += w(k) * aligned_sample(a, k);
    const double pose =
        frame_joint_errors(*set.skeleton, aligned_sample(set.aligned, left_out), blend, true).col(0).mean();
    return {pose, factors};
}

}  // namespace

std::vector<MethodSpec> set_methods(const std::array<std::size_t, 3>& ranks) {
    std::vector<MethodSpec> out;
    MethodSpec m;
    m.kind = MethodKind::NaiveKriging;
    m.name = "kriging";
    out.push_back(m);
    m.kind = MethodKind::Rbf;
    m.name = "rbf";
    out.push_back(m);
    m.kind = MethodKind::TrendOnly;
    m.name = "trend";
    out.push_back(m);
    if (ranks[0] > 0 && ranks[1] > 0 && ranks[2] > 0) {
        m.kind = MethodKind::TuckerKriging;
        m.name = "tucker";
        m.ranks = {static_cast<Eigen::Index>(ranks[0]), static_cast<Eigen::Index>(ranks[1]),
                   static_cast<Eigen::Index>(ranks[2])};
        out.push_back(m);
    }
    return out;
}

std::vector<Eigen::Index> evenly_spread(Eigen::Index n, std::size_t count) {
    std::vector<Eigen::Index> out;
    if (n <= 0 || count == 0) return out;
    const auto c = static_cast<Eigen::Index>(std::min<std::size_t>(count, static_cast<std::size_t>(n)));
    for (Eigen::Index k = 0; k < c; ++k) out.push_back((2 * k + 1) * n / (2 * c));
    return out;
}

SetEvaluation evaluate_set(const EvalSet& set, const std::vector<MethodSpec>& methods,
                           const SetEvaluationOptions& options, const ProgressCallback& progress) {
    const std::string name = "set '" + set.set.name + "'";
    if (methods.empty()) throw InvalidArgument(name + ": no method to evaluate");
    if (options.max_folds < 1 || options.inner_folds < 1)
        throw InvalidArgument(name + ": the numbers of outer and inner folds must be at least 1");
    if (!(options.hit_share > 0.0) || !std::isfinite(options.hit_share))
        throw InvalidArgument(name + ": the hit tolerance share must be positive");
    if (set.size() < 5)
        throw InvalidArgument(name + " has " + std::to_string(set.size()) +
                              " samples; nested cross-validation needs at least 5");
    SetEvaluation out;
    out.set = set.set.name;
    out.labels = set.labels;
    out.frames = set.aligned.frames();
    out.parameter_names = set.set.parameter_names;
    out.parameter_units = set.set.parameter_units;
    out.inner_folds = options.inner_folds;
    out.hit_share = options.hit_share;
    out.twins = find_sample_twins(
        set.set, [&](std::size_t i) { return set.samples[i]; }, options.twins);
    const auto twins = twin_lists(out.twins, set.samples.size());
    out.folds = evenly_spread(set.size(), options.max_folds);
    for (Eigen::Index i : out.folds)
        if (loo_training(set.size(), i, twins).size() < 4)
            throw InvalidArgument(name + ": leaving out " + set.labels[static_cast<std::size_t>(i)] +
                                  " with its twins leaves fewer than 4 samples for the inner cross-validation");
    out.parameters_measured = !set.extractors.empty();
    out.not_evaluated.push_back(
        "MOHGP: not evaluated (it predicts a replicate motion from part of its own frames, not a motion from "
        "control parameters; docs/gp.md)");

    const std::uint64_t total = 2 * out.folds.size();
    LooOptions outer;
    outer.foot_skating = false;
    outer.samples = out.folds;
    outer.twins = twins;
    outer.measure_parameters = true;
    outer.reliability = true;
    ProgressCallback outer_progress;
    if (progress)
        outer_progress = [&](const Progress& p) { progress({p.done, total, std::string("fold ").append(p.item)}); };
    const LooResult loo = leave_one_out(set, methods, outer, outer_progress);

    const auto m = static_cast<Eigen::Index>(out.folds.size());
    MatX requested(m, set.set.parameters.cols());
    for (Eigen::Index k = 0; k < m; ++k)
        requested.row(k) = set.set.parameters.row(out.folds[static_cast<std::size_t>(k)]);
    if (out.parameters_measured) {
        out.hit_tolerance = workflow::sd_tolerance(set.set.parameters, options.hit_share);
        // Only the extracted parameters (the first columns) are measured back: not the CSV's or categories.
        std::size_t extracted = 0;
        for (const ParameterExtractor& x : set.extractors) extracted += x.names().size();
        for (std::size_t p = extracted; p < out.hit_tolerance.size(); ++p) out.hit_tolerance[p].reset();
    }
    for (std::size_t q = 0; q < methods.size(); ++q) {
        MethodEvaluation e;
        e.spec = methods[q];
        e.loo = loo.methods[q];
        if (out.parameters_measured && static_cast<Eigen::Index>(e.loo.measured.size()) == m) {
            e.hits = fold_hits(e.loo.measured, requested, out.hit_tolerance, set.set.parameter_periods);
            e.hit_rate = e.hits.mean();
        }
        if (e.loo.reliability.size() == m && m >= 2)
            e.rho_pose_pearson = gp::pearson(e.loo.reliability, e.loo.sample_pose_mean_cm);
        out.methods.push_back(std::move(e));
    }

    ChosenEvaluation& c = out.chosen;
    const std::vector<synthesis::PredictorChoice> choices =
        nested_choices(set, out.folds, twins, options.inner_folds, progress, out.folds.size(), total);
    c.counts.assign(methods.size() + 1, 0);
    c.pose_mean_cm.resize(m);
    c.motion_mean_cm.resize(m);
    VecX hits(m);
    bool every_hit_measured = out.parameters_measured;
    for (Eigen::Index k = 0; k < m; ++k) {
        const synthesis::PredictorChoice& choice = choices[static_cast<std::size_t>(k)];
        if (choice.chosen != synthesis::Predictor::Average) {
            const std::size_t q = method_of(methods, choice.chosen);
            c.picks.push_back(q);
            c.pick_names.push_back(methods[q].name);
            ++c.counts[q];
            c.pose_mean_cm(k) = out.methods[q].loo.sample_pose_mean_cm(k);
            c.motion_mean_cm(k) = out.methods[q].loo.sample_mean_cm(k);
            c.pose_max = std::max(c.pose_max, out.methods[q].loo.sample_pose_max_cm(k));
            c.motion_max = std::max(c.motion_max, out.methods[q].loo.sample_max_cm(k));
            if (out.methods[q].hits.size() == m) hits(k) = out.methods[q].hits(k);
            else every_hit_measured = false;
            continue;
        }
        // An average: its own leave-one-out fold (the mean of the members' motions, as synthesis blends).
        MethodSpec average;
        average.kind = MethodKind::Average;
        average.name = "average";
        for (const synthesis::Predictor p : choice.members()) {
            average.averaged.push_back(method_kind(p));
            average.name += (average.averaged.size() == 1 ? " of " : "+") + methods[method_of(methods, p)].name;
        }
        c.picks.push_back(methods.size());
        c.pick_names.push_back(average.name);
        ++c.counts[methods.size()];
        LooOptions one;
        one.foot_skating = false;
        one.samples = {out.folds[static_cast<std::size_t>(k)]};
        one.twins = twins;
        one.measure_parameters = true;
        const LooMethodResult r = leave_one_out(set, {average}, one).methods.front();
        c.pose_mean_cm(k) = r.sample_pose_mean_cm(0);
        c.motion_mean_cm(k) = r.sample_mean_cm(0);
        c.pose_max = std::max(c.pose_max, r.sample_pose_max_cm(0));
        c.motion_max = std::max(c.motion_max, r.sample_max_cm(0));
        if (out.parameters_measured && r.measured.size() == 1)
            hits(k) = fold_hits(r.measured, requested.row(k), out.hit_tolerance, set.set.parameter_periods)(0);
        else every_hit_measured = false;
    }
    c.pose_mean = c.pose_mean_cm.mean();
    c.motion_mean = c.motion_mean_cm.mean();
    if (every_hit_measured) c.hit_rate = hits.mean();
    // The best of the predictors the choice is made among (kriging, RBF, trend), in hindsight.
    c.best = method_of(methods, synthesis::Predictor::Kriging);
    for (const synthesis::Predictor p : synthesis::all_predictors()) {
        const std::size_t q = method_of(methods, p);
        if (out.methods[q].loo.pose_mean_cm < out.methods[c.best].loo.pose_mean_cm) c.best = q;
    }
    const VecX diff = c.pose_mean_cm - out.methods[c.best].loo.sample_pose_mean_cm;
    c.diff_mean_cm = diff.mean();
    c.diff_se_cm = standard_error(diff);

    const bool numeric = (set.set.parameter_periods.size() == 0 || !(set.set.parameter_periods.array() > 0.0).any()) &&
                         parameter_level_counts(set.set).empty();
    if (options.learned_metric && numeric && set.set.parameters.cols() >= 1) {
        LearnedMetricEvaluation l;
        l.kind = set.set.parameters.cols() == 1 ? "warp" : "ard";
        l.pose_mean_cm.resize(m);
        for (Eigen::Index k = 0; k < m; ++k) {
            const Eigen::Index i = out.folds[static_cast<std::size_t>(k)];
            auto [pose, factors] = learned_metric_fold(set, i, loo_training(set.size(), i, twins));
            l.pose_mean_cm(k) = pose;
            l.factors.push_back(std::move(factors));
        }
        l.pose_mean = l.pose_mean_cm.mean();
        out.learned_metric = std::move(l);
    }
    return out;
}

SetEvaluation evaluate_stored_set(const std::filesystem::path& db_file, const std::string& set,
                                  const SetEvaluationOptions& options, const ProgressCallback& progress) {
    const Database db(db_file);
    std::array<std::size_t, 3> ranks{};
    for (const SetRecord& r : db.sets())
        if (r.name == set && r.model) ranks = r.model_ranks;
    const EvalSet eval_set = load_eval_set(db, set);
    SetEvaluation out = evaluate_set(eval_set, set_methods(ranks), options, progress);
    out.file = db_file.string();
    if (ranks[0] == 0)
        out.not_evaluated.push_back("tucker: not evaluated (the set has no stored model; mocapdb compress makes one)");
    return out;
}

}  // namespace mocapdb::eval

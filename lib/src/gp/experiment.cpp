#include "mocapdb/gp/experiment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <Eigen/Cholesky>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

namespace {

MatX draw(const MatX& cov, std::mt19937_64& rng, Eigen::Index d, Eigen::Index t) {
    MatX c = cov;
    const double scale = std::max(cov.diagonal().maxCoeff(), 1e-300);
    Eigen::LLT<MatX> llt;
    for (double jitter = 1e-10; jitter < 1.0; jitter *= 10.0) {
        c = cov;
        c.diagonal().array() += jitter * scale;
        llt.compute(c);
        if (llt.info() == Eigen::Success) break;
    }
    std::normal_distribution<double> normal(0.0, 1.0);
    VecX xi(cov.rows());
    for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = normal(rng);
    const VecX v = llt.matrixL() * xi;
    MatX y(d, t);
    for (Eigen::Index i = 0; i < d; ++i) y.row(i) = v.segment(i * t, t).transpose();
    return y;
}

/// Random `count` distinct frames of `frames`, as a mask.
std::vector<bool> random_mask(std::size_t frames, std::size_t count, std::mt19937_64& rng) {
    std::vector<std::size_t> idx(frames);
    std::iota(idx.begin(), idx.end(), 0);
    std::shuffle(idx.begin(), idx.end(), rng);
    std::vector<bool> mask(frames, false);
    for (std::size_t i = 0; i < std::min(count, frames); ++i) mask[idx[i]] = true;
    return mask;
}

/// MOHGP (two or three layers, as options.spec says) or, with !hierarchical, the flat MOA baseline.
FitResult fit_model(const HgpData& training, const ExperimentOptions& options, bool hierarchical) {
    ModelSpec spec = options.spec;
    spec.hierarchical = hierarchical;
    spec.grouped = spec.grouped && hierarchical;
    return fit(training, initial_model(training, spec), options.fit);
}

}  // namespace

std::vector<ArtificialConfig> thesis_artificial_configs() {
    std::vector<ArtificialConfig> out;
    for (double noise : {0.001, 0.01, 0.1})
        for (auto [d, r] : {std::pair<std::size_t, std::size_t>{3, 5}, {6, 6}, {3, 10}}) {
            ArtificialConfig c;
            c.noise = noise;
            c.outputs = d;
            c.children = r;
            out.push_back(c);
        }
    return out;
}

HgpModel artificial_generator(const ArtificialConfig& config, std::uint64_t seed) {
    if (config.outputs == 0 || config.generator_terms == 0 || !(config.noise > 0.0))
        throw InvalidArgument("artificial_generator: need outputs ≥ 1, terms ≥ 1, noise > 0");
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const Eigen::Index d = static_cast<Eigen::Index>(config.outputs);
    HgpModel m;
    m.hierarchical = true;
    m.noise_floor = 0.0;
    auto term = [&](double ell_lo, double ell_hi, double w_scale, double kappa_lo, double kappa_hi) {
        LmcTerm t;
        t.kernel = KernelType::Rbf;
        t.log_lengthscale = std::log(ell_lo + (ell_hi - ell_lo) * uniform(rng));
        t.W.resize(d, 1);
        for (Eigen::Index i = 0; i < d; ++i) t.W(i, 0) = w_scale * normal(rng);
        t.log_kappa.resize(d);
        for (Eigen::Index i = 0; i < d; ++i) t.log_kappa[i] = std::log(kappa_lo + (kappa_hi - kappa_lo) * uniform(rng));
        return t;
    };
    for (std::size_t q = 0; q < config.generator_terms; ++q) m.parent.terms.push_back(term(0.5, 2.0, 1.0, 0.05, 0.2));
    for (std::size_t q = 0; q < config.generator_terms; ++q) m.child.terms.push_back(term(0.3, 1.5, 0.3, 0.01, 0.05));
    m.log_noise = VecX::Constant(d, std::log(config.noise));
    return m;
}

std::vector<MatX> sample_hierarchy(const HgpModel& truth, const VecX& times, std::size_t children, std::uint64_t seed,
                                   MatX* out_parent) {
    validate(truth);
    if (!truth.hierarchical) throw InvalidArgument("sample_hierarchy: the model must be hierarchical");
    const Eigen::Index d = static_cast<Eigen::Index>(truth.outputs()), t = times.size();
    std::mt19937_64 rng(seed);
    const MatX g = draw(lmc_covariance(truth.parent, times, times), rng, d, t);
    const MatX kf = lmc_covariance(truth.child, times, times);
    const VecX noise = truth.noise_variance();
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<MatX> out;
    for (std::size_t r = 0; r < children; ++r) {
        MatX y = g + draw(kf, rng, d, t);
        for (Eigen::Index i = 0; i < d; ++i)
            for (Eigen::Index f = 0; f < t; ++f) y(i, f) += std::sqrt(noise[i]) * normal(rng);
        out.push_back(y);
    }
    if (out_parent) *out_parent = g;
    return out;
}

void ModelRuns::summarize() {
    std::vector<double> a, c;
    std::vector<std::optional<double>> b;
    for (const auto& s : runs) {
        a.push_back(s.mse);
        b.push_back(s.smse);
        c.push_back(s.msll);
    }
    mse = mean_std(a);
    smse = mean_std_of_all(b);
    msll = mean_std(c);
}

namespace {

/// Scores of a prediction of the test child at every frame under the mask `observed`: the truth is its
/// values at the unobserved frames; the trivial model's moments come from every observed value
/// (siblings and the test child's observed frames).
InterpolationScores score_prediction(const GaussianPrediction& p, const HgpData& data, std::size_t test_child,
                                     const std::vector<bool>& observed) {
    const Eigen::Index dd = static_cast<Eigen::Index>(data.outputs());
    std::vector<Eigen::Index> missing;
    for (std::size_t f = 0; f < observed.size(); ++f)
        if (!observed[f]) missing.push_back(static_cast<Eigen::Index>(f));
    const Eigen::Index nm = static_cast<Eigen::Index>(missing.size());
    MatX truth(dd, nm), mean_pred(dd, nm), variance(dd, nm);
    for (Eigen::Index i = 0; i < nm; ++i) {
        const Eigen::Index f = missing[static_cast<std::size_t>(i)];
        truth.col(i) = data.children[test_child].col(f);
        mean_pred.col(i) = p.mean.col(f);
        variance.col(i) = p.variance.col(f) + p.noise;
    }
    variance = variance.cwiseMax(1e-12);  // round-off can make a tiny variance ≤ 0
    VecX sum = VecX::Zero(dd), sq = VecX::Zero(dd);
    double n = 0.0;
    for (std::size_t r = 0; r < data.child_count(); ++r)
        for (std::size_t f = 0; f < data.frames(); ++f)
            if (r == test_child ? static_cast<bool>(observed[f]) : data.is_observed(r, f)) {
                sum += data.children[r].col(static_cast<Eigen::Index>(f));
                sq += data.children[r].col(static_cast<Eigen::Index>(f)).cwiseAbs2();
                n += 1.0;
            }
    const VecX mean = sum / n;
    const VecX var = (sq / n - mean.cwiseAbs2()).cwiseMax(1e-12);
    return interpolation_scores(truth, mean_pred, variance, mean, var);
}

}  // namespace

std::vector<InterpolationScores> score_interpolations(const HgpModel& model, const HgpData& data,
                                                      std::size_t test_child,
                                                      const std::vector<std::vector<bool>>& masks) {
    if (test_child >= data.child_count())
        throw InvalidArgument("score_interpolation: no child " + std::to_string(test_child));
    for (const auto& m : masks)
        if (m.size() != data.frames()) throw InvalidArgument("score_interpolation: a mask needs one flag per frame");
    bool siblings_complete = true;
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != test_child && !data.is_complete(r)) siblings_complete = false;
    std::vector<GaussianPrediction> preds;
    if (siblings_complete) {
        preds = predict_child_masks(model, data, test_child, masks);
    } else {
        for (const auto& m : masks) {
            HgpData d = data;
            d.observed.resize(d.child_count());
            d.observed[test_child] = m;
            preds.push_back(predict_child(model, d, test_child, data.times));
        }
    }
    std::vector<InterpolationScores> out;
    for (std::size_t i = 0; i < masks.size(); ++i)
        out.push_back(score_prediction(preds[i], data, test_child, masks[i]));
    return out;
}

InterpolationScores score_interpolation(const HgpModel& model, const HgpData& data, std::size_t test_child,
                                        const std::vector<bool>& observed) {
    return score_interpolations(model, data, test_child, {observed}).front();
}

ArtificialResult run_artificial(const ArtificialConfig& config, const ExperimentOptions& options) {
    if (config.children < 2 || config.observed >= config.inputs || config.inputs < 3)
        throw InvalidArgument("run_artificial: need ≥ 2 children and fewer observed inputs than inputs");
    ArtificialResult result;
    result.config = config;
    const VecX times = VecX::LinSpaced(static_cast<Eigen::Index>(config.inputs), 0.0, 2.0 * kPi);
    std::uint64_t done = 0;
    for (std::size_t run = 0; run < options.runs; ++run) {
        const std::uint64_t seed = options.seed * 1000003ULL + run * 7919ULL;
        const HgpModel truth = artificial_generator(config, seed);
        HgpData data;
        data.times = times;
        data.children = sample_hierarchy(truth, times, config.children, seed + 1);
        const std::size_t test = config.children - 1;
        std::mt19937_64 rng(seed + 2);
        const std::vector<bool> mask = random_mask(config.inputs, config.observed, rng);
        const HgpData training = without_child(data, test);
        for (bool hierarchical : {true, false}) {
            const FitResult f = fit_model(training, options, hierarchical);
            ModelRuns& m = hierarchical ? result.mohgp : result.moa;
            m.fit_seconds += f.seconds;
            m.fit_status.push_back(to_string(f.status));
            m.runs.push_back(score_interpolation(f.model, data, test, mask));
            if (options.progress) options.progress(Progress{++done, 2 * options.runs, hierarchical ? "MOHGP" : "MOA"});
        }
    }
    result.mohgp.summarize();
    result.moa.summarize();
    return result;
}

ReplicateInterpolation run_replicate_interpolation(const HgpData& data, std::size_t test_child,
                                                   const std::vector<std::size_t>& observed_counts,
                                                   const ExperimentOptions& options) {
    validate(data);
    if (!data.all_complete()) throw InvalidArgument("run_replicate_interpolation: the children must be complete");
    if (data.child_count() < 2 || test_child >= data.child_count())
        throw InvalidArgument("run_replicate_interpolation: need ≥ 2 children and a valid test child");
    for (std::size_t k : observed_counts)
        if (k + 2 > data.frames())
            throw InvalidArgument("run_replicate_interpolation: " + std::to_string(k) +
                                  " observed frames leave fewer than 2 of " + std::to_string(data.frames()) +
                                  " to predict");
    ReplicateInterpolation out;
    const HgpData training = without_child(data, test_child);
    out.mohgp_fit = fit_model(training, options, true);
    if (options.progress) options.progress(Progress{1, 2, "MOHGP"});
    out.moa_fit = fit_model(training, options, false);
    if (options.progress) options.progress(Progress{2, 2, "MOA"});
    // Every row's masks at once: each model's share of the siblings is computed once.
    std::vector<std::vector<bool>> masks;
    for (std::size_t k : observed_counts)
        for (std::size_t run = 0; run < options.runs; ++run) {
            std::mt19937_64 rng(options.seed * 1000003ULL + k * 131ULL + run);
            masks.push_back(random_mask(data.frames(), k, rng));
        }
    const auto mohgp = score_interpolations(out.mohgp_fit.model, data, test_child, masks);
    const auto moa = score_interpolations(out.moa_fit.model, data, test_child, masks);
    std::size_t next = 0;
    for (std::size_t k : observed_counts) {
        InterpolationRow row;
        row.observed = k;
        for (std::size_t run = 0; run < options.runs; ++run, ++next) {
            row.mohgp.runs.push_back(mohgp[next]);
            row.moa.runs.push_back(moa[next]);
        }
        row.mohgp.fit_seconds = out.mohgp_fit.seconds;
        row.moa.fit_seconds = out.moa_fit.seconds;
        row.mohgp.summarize();
        row.moa.summarize();
        out.rows.push_back(row);
    }
    return out;
}

SynthesisResult run_synthesis(const HgpData& training, const std::vector<MatX>& real, const std::vector<MatX>& control,
                              std::size_t samples, const ExperimentOptions& options) {
    validate(training);
    if (real.empty() || samples == 0) throw InvalidArgument("run_synthesis: need real motions and ≥ 1 sample");
    SynthesisResult out;
    out.mohgp_fit = fit_model(training, options, true);
    out.moa_fit = fit_model(training, options, false);
    SampleOptions so;
    so.seed = options.seed;
    const auto gen_h = sample_children(out.mohgp_fit.model, training, training.times, samples, so);
    const auto gen_m = sample_children(out.moa_fit.model, training, training.times, samples, so);
    out.mohgp = synthesis_scores(gen_h, real);
    out.moa = synthesis_scores(gen_m, real);
    if (!control.empty()) {
        out.control = synthesis_scores(control, real);
    } else {
        // The real motions against each other (each one against the others, not itself).
        if (real.size() < 2)
            throw InvalidArgument("run_synthesis: the real-against-real control needs ≥ 2 real motions");
        for (std::size_t i = 0; i < real.size(); ++i) {
            std::vector<MatX> others;
            for (std::size_t j = 0; j < real.size(); ++j)
                if (j != i) others.push_back(real[j]);
            const SynthesisScores one = synthesis_scores(others, {real[i]});
            out.control.mcc.push_back(one.mcc[0]);
            out.control.mlc.push_back(one.mlc[0]);
        }
    }
    return out;
}

SynthesisResult run_artificial_synthesis(const ArtificialConfig& config, std::size_t samples,
                                         const ExperimentOptions& options) {
    const VecX times = VecX::LinSpaced(static_cast<Eigen::Index>(config.inputs), 0.0, 2.0 * kPi);
    const std::uint64_t seed = options.seed * 1000003ULL + 17;
    const HgpModel truth = artificial_generator(config, seed);
    HgpData training;
    training.times = times;
    std::vector<MatX> all = sample_hierarchy(truth, times, config.children + 5, seed + 1);
    training.children.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(config.children));
    const std::vector<MatX> real(all.begin() + static_cast<std::ptrdiff_t>(config.children), all.end());
    const HgpModel other = artificial_generator(config, seed + 99991);
    const std::vector<MatX> control = sample_hierarchy(other, times, 5, seed + 99992);
    // Control row: the unrelated generator's children scored against the real ones.
    SynthesisResult r = run_synthesis(training, real, control, samples, options);
    return r;
}

}  // namespace mocapdb::gp

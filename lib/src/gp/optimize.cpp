#include "mocapdb/gp/optimize.hpp"

#include <LBFGS.h>

#include <Eigen/Eigenvalues>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

namespace {

constexpr int kLbfgsMemory = 20;

/// −log p / n and its gradient; remembers the best finite point it was asked about.
class Objective {
public:
    Objective(const HgpData& data, HgpModel model, const FitOptions& options, int& evaluations, const std::string& item)
        : data_(data),
          model_(std::move(model)),
          options_(options),
          evaluations_(evaluations),
          item_(item),
          scale_(1.0 / static_cast<double>(data.observed_value_count())) {}

    double operator()(const VecX& x, VecX& grad) {
        ++evaluations_;
        ++own_evaluations;
        if (options_.progress) options_.progress(Progress{static_cast<std::uint64_t>(evaluations_), 0, item_});
        if (!x.allFinite()) {
            grad = VecX::Zero(x.size());
            return std::numeric_limits<double>::infinity();
        }
        model_.set_parameters(x);
        const LikelihoodValue v = log_likelihood(model_, data_, true, options_.path, options_.threads);
        if (!v.ok() || !v.gradient.allFinite()) {
            last_message = v.message.empty() ? "non-finite gradient" : v.message;
            grad = VecX::Zero(x.size());
            return std::numeric_limits<double>::infinity();
        }
        grad = -scale_ * v.gradient;
        const double f = -scale_ * v.log_likelihood;
        if (f < best_f) {
            best_f = f;
            best_x = x;
        }
        return f;
    }

    double best_f = std::numeric_limits<double>::infinity();
    VecX best_x;
    int own_evaluations = 0;
    std::string last_message;

private:
    const HgpData& data_;
    HgpModel model_;
    const FitOptions& options_;
    int& evaluations_;
    std::string item_;
    double scale_;
};

VecX perturbed(const HgpModel& start, double spread, std::uint64_t seed) {
    HgpModel m = start;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    auto shake = [&](Lmc& lmc) {
        for (auto& t : lmc.terms) {
            t.log_lengthscale += spread * normal(rng);
            for (Eigen::Index i = 0; i < t.W.size(); ++i) t.W.data()[i] *= std::exp(spread * normal(rng));
            for (Eigen::Index i = 0; i < t.log_kappa.size(); ++i) t.log_kappa[i] += spread * normal(rng);
        }
    };
    shake(m.child);
    if (m.grouped) shake(m.group);
    if (m.hierarchical) shake(m.parent);
    for (Eigen::Index i = 0; i < m.log_noise.size(); ++i) m.log_noise[i] += spread * normal(rng);
    return m.parameters();
}

}  // namespace

std::string to_string(FitStatus status) {
    switch (status) {
        case FitStatus::Converged: return "converged";
        case FitStatus::MaxIterations: return "max_iterations";
        case FitStatus::LineSearchFailed: return "line_search_failed";
        case FitStatus::NumericalFailure: return "numerical_failure";
    }
    return "unknown";
}

HgpModel initial_model(const HgpData& data, const ModelSpec& spec) {
    validate(data);
    if (spec.child_terms == 0 || (spec.hierarchical && spec.parent_terms == 0) ||
        (spec.grouped && spec.group_terms == 0) || spec.rank == 0)
        throw InvalidArgument("initial_model: need ≥ 1 term per layer and rank ≥ 1");
    if (spec.grouped && (!spec.hierarchical || data.groups.empty()))
        throw InvalidArgument(
            "initial_model: three layers need a hierarchical model and each child's group (HgpData::groups)");
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    // Second-moment matrices (D×D) over the observed frames: of the children's mean per frame (the
    // parent's share) and of the deviations from it (the child's); MOA: of the values themselves.
    MatX mean_m2 = MatX::Zero(d, d), dev_m2 = MatX::Zero(d, d), total_m2 = MatX::Zero(d, d);
    MatX group_m2 = MatX::Zero(d, d), within_m2 = MatX::Zero(d, d);
    double count_m = 0.0, count_dev = 0.0, count_group = 0.0;
    const std::size_t groups = spec.grouped ? data.group_count() : 0;
    for (Eigen::Index f = 0; f < t; ++f) {
        VecX sum = VecX::Zero(d);
        double n = 0.0;
        for (std::size_t r = 0; r < data.child_count(); ++r)
            if (data.is_observed(r, static_cast<std::size_t>(f))) {
                sum += data.children[r].col(f);
                n += 1.0;
            }
        if (n == 0.0) continue;
        const VecX mean = sum / n;
        mean_m2.noalias() += mean * mean.transpose();
        count_m += 1.0;
        for (std::size_t r = 0; r < data.child_count(); ++r)
            if (data.is_observed(r, static_cast<std::size_t>(f))) {
                const VecX dev = data.children[r].col(f) - mean;
                dev_m2.noalias() += dev * dev.transpose();
                total_m2.noalias() += data.children[r].col(f) * data.children[r].col(f).transpose();
                count_dev += 1.0;
            }
        // Three layers: each group's mean about the mean, each child about its group's mean.
        for (std::size_t s = 0; s < groups; ++s) {
            VecX gsum = VecX::Zero(d);
            double gn = 0.0;
            for (std::size_t r = 0; r < data.child_count(); ++r)
                if (data.groups[r] == s && data.is_observed(r, static_cast<std::size_t>(f))) {
                    gsum += data.children[r].col(f);
                    gn += 1.0;
                }
            if (gn == 0.0) continue;
            const VecX gmean = gsum / gn;
            group_m2.noalias() += (gmean - mean) * (gmean - mean).transpose();
            count_group += 1.0;
            for (std::size_t r = 0; r < data.child_count(); ++r)
                if (data.groups[r] == s && data.is_observed(r, static_cast<std::size_t>(f))) {
                    const VecX dev = data.children[r].col(f) - gmean;
                    within_m2.noalias() += dev * dev.transpose();
                }
        }
    }
    mean_m2 /= std::max(count_m, 1.0);
    dev_m2 /= std::max(count_dev, 1.0);
    total_m2 /= std::max(count_dev, 1.0);
    group_m2 /= std::max(count_group, 1.0);
    within_m2 /= std::max(count_dev, 1.0);
    const double floor = 1e-6;
    const MatX& parent_m2 = mean_m2;
    const MatX& child_m2 = spec.grouped ? within_m2 : spec.hierarchical ? dev_m2 : total_m2;
    const double span = std::max(data.times.maxCoeff() - data.times.minCoeff(), 1e-6);

    // Each layer's Q terms share its second moment; term q's W takes the next `rank` principal
    // directions of that moment (80 % of their eigenvalue), κ the rest of the diagonal (at least 5 %).
    auto make = [&](std::size_t terms, const MatX& m2, std::size_t layer) {
        Eigen::SelfAdjointEigenSolver<MatX> es(m2);
        const VecX diag = m2.diagonal().cwiseMax(floor);
        Lmc lmc;
        for (std::size_t q = 0; q < terms; ++q) {
            LmcTerm term;
            term.kernel = spec.kernel;
            const double frac =
                terms == 1 ? 0.2 : 0.05 * std::pow(10.0, static_cast<double>(q) / static_cast<double>(terms - 1));
            term.log_lengthscale = std::log(frac * span);
            const double share = 1.0 / static_cast<double>(terms);
            term.W.resize(d, static_cast<Eigen::Index>(spec.rank));
            for (Eigen::Index j = 0; j < term.W.cols(); ++j) {
                const Eigen::Index which = static_cast<Eigen::Index>(q * spec.rank) + j;
                const Eigen::Index col = d - 1 - (which % d);  // eigenvalues ascending
                const double lambda = std::max(es.eigenvalues()[col], 0.0);
                term.W.col(j) = std::sqrt(0.8 * share * lambda) * es.eigenvectors().col(col);
                // A zero column would be a stationary point of the likelihood: keep it small but non-zero.
                for (Eigen::Index i = 0; i < d; ++i) {
                    const double s = std::sin(1.0 + 1.7 * static_cast<double>(i) + 2.3 * static_cast<double>(j) +
                                              0.9 * static_cast<double>(q) + 0.5 * static_cast<double>(layer));
                    term.W(i, j) += 0.05 * std::sqrt(share * diag[i]) * s;
                }
            }
            const VecX rest = share * diag - term.W.rowwise().squaredNorm();
            term.log_kappa = rest.cwiseMax(0.05 * share * diag).array().log().matrix();
            lmc.terms.push_back(std::move(term));
        }
        return lmc;
    };
    HgpModel m;
    m.hierarchical = spec.hierarchical;
    m.grouped = spec.grouped;
    m.noise_floor = spec.noise_floor;
    m.child = make(spec.child_terms, child_m2, 0);
    if (spec.grouped) m.group = make(spec.group_terms, group_m2, 2);
    if (spec.hierarchical) m.parent = make(spec.parent_terms, parent_m2, 1);
    m.log_noise = (0.01 * child_m2.diagonal().cwiseMax(floor)).array().log().matrix();
    if (!spec.scan_lengthscales) return m;

    // Lengthscales: a coarse scan of one factor per layer (all of a layer's terms scaled together)
    // by the likelihood itself (no gradient), keeping the best usable point.
    const std::vector<double> factors = {0.25, 0.5, 1.0, 2.0, 4.0};
    const HgpModel base = m;
    double best = -std::numeric_limits<double>::infinity();
    for (double fc : factors)
        for (double fp : spec.hierarchical ? factors : std::vector<double>{1.0}) {
            HgpModel trial = base;
            for (auto& term : trial.child.terms) term.log_lengthscale += std::log(fc);
            for (auto& term : trial.parent.terms) term.log_lengthscale += std::log(fp);
            for (auto& term : trial.group.terms) term.log_lengthscale += std::log(fp);
            const LikelihoodValue v = log_likelihood(trial, data, false);
            if (v.ok() && v.log_likelihood > best) {
                best = v.log_likelihood;
                m = trial;
            }
        }
    return m;
}

FitResult fit(const HgpData& data, const HgpModel& start, const FitOptions& options) {
    validate(start);
    validate(data);
    if (start.outputs() != data.outputs()) throw InvalidArgument("fit: model and data have different outputs");
    if (options.restarts < 1 || options.max_iterations < 1)
        throw InvalidArgument("fit: restarts and max_iterations must be ≥ 1");
    const auto t0 = std::chrono::steady_clock::now();
    FitResult result;
    result.model = start;
    result.log_likelihood = -std::numeric_limits<double>::infinity();
    const double scale = static_cast<double>(data.observed_value_count());

    LBFGSpp::LBFGSParam<double> param;
    param.epsilon = options.gradient_tolerance;
    param.epsilon_rel = options.gradient_tolerance;
    param.past = options.past;
    param.delta = options.relative_decrease;
    param.max_iterations = options.max_iterations;
    param.max_linesearch = 40;
    // A longer curvature memory than LBFGSpp's default 6: the LMC's W, κ and noise parameters are
    // strongly coupled (on the 39-output CMU fit: log p after 100 iterations 22 493 with 6, see RESULTS.md).
    param.m = kLbfgsMemory;
    // Strong Wolfe conditions keep the curvature pairs positive (sᵀy > 0); LBFGSpp does not skip bad
    // pairs, and with Armijo alone the next direction can point uphill.
    param.linesearch = LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_STRONG_WOLFE;

    for (int k = 0; k < options.restarts; ++k) {
        const auto tk = std::chrono::steady_clock::now();
        VecX x = k == 0 ? start.parameters()
                        : perturbed(start, options.restart_spread, options.seed + static_cast<std::uint64_t>(k));
        Objective objective(data, start, options, result.evaluations, "restart " + std::to_string(k + 1));
        RestartReport report;
        VecX g(x.size());
        const double f0 = objective(x, g);
        if (!std::isfinite(f0)) {
            report.status = FitStatus::NumericalFailure;
            report.message = "starting point unusable: " + objective.last_message;
        } else {
            // A failed line search ends an L-BFGS run; it is resumed from the best point with a fresh
            // curvature memory while that still makes progress (at most kMaxResumes times).
            constexpr int kMaxResumes = 3;
            int iterations_left = options.max_iterations;
            double last_best = objective.best_f;
            for (int attempt = 0;; ++attempt) {
                LBFGSpp::LBFGSParam<double> p = param;
                p.max_iterations = iterations_left;
                LBFGSpp::LBFGSSolver<double> solver(p);
                double fx = objective.best_f;
                const int evaluations_before = objective.own_evaluations;
                try {
                    const int iterations = solver.minimize(objective, x, fx);
                    report.iterations += iterations;
                    report.status = iterations >= iterations_left ? FitStatus::MaxIterations : FitStatus::Converged;
                    report.message.clear();
                    break;
                } catch (const std::exception& e) {
                    report.status = FitStatus::LineSearchFailed;
                    report.message = e.what();
                    // Iterations of a run ended by an exception are unknown: count its evaluations (≥ them).
                    const int used = std::max(1, objective.own_evaluations - evaluations_before);
                    report.iterations += used;
                    iterations_left -= used;
                }
                const bool progressed = objective.best_f < last_best - 1e-12 * std::max(1.0, std::abs(last_best));
                if (attempt >= kMaxResumes || !progressed || iterations_left <= 0) break;
                last_best = objective.best_f;
                x = objective.best_x;
            }
        }
        report.evaluations = objective.own_evaluations;
        report.log_likelihood =
            std::isfinite(objective.best_f) ? -objective.best_f * scale : -std::numeric_limits<double>::infinity();
        report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tk).count();
        if (std::isfinite(objective.best_f) && report.log_likelihood > result.log_likelihood) {
            result.log_likelihood = report.log_likelihood;
            result.model.set_parameters(objective.best_x);
            result.status = report.status;
        }
        result.restarts.push_back(report);
    }
    if (!std::isfinite(result.log_likelihood)) result.status = FitStatus::NumericalFailure;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace mocapdb::gp

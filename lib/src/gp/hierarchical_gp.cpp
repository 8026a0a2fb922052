#include "mocapdb/gp/hierarchical_gp.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <Eigen/Cholesky>

#include "gp_internal.hpp"
#include "hgp_posteriors.hpp"
#include "structured_likelihood.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

const char* to_string(LikelihoodStatus status) {
    switch (status) {
        case LikelihoodStatus::Ok: return "ok";
        case LikelihoodStatus::NotPositiveDefinite: return "not_positive_definite";
        case LikelihoodStatus::NonFinite: return "non_finite";
    }
    return "unknown";
}

namespace {

using detail::at_queries;
using detail::child_prior_on_grid;
using detail::condition_dense;
using detail::condition_on_own_frames;
using detail::dense_layout;
using detail::dense_likelihood;
using detail::DenseLayout;
using detail::flat_noise;
using detail::Grid;
using detail::grid_prediction;
using detail::GridGaussian;
using detail::group_on_grid;
using detail::make_grid;
using detail::Target;
using detail::trend_on_grid;
using detail::unvec_output_major;
using detail::vec_output_major;

void check_times(const VecX& t_star) {
    if (t_star.size() == 0 || !t_star.allFinite()) throw InvalidArgument("prediction times: expected ≥ 1 finite time");
}

void draw_gaussian(const VecX& mean, const MatX& cov, std::size_t count, std::mt19937_64& rng, Eigen::Index d,
                   Eigen::Index ts, std::vector<MatX>& out) {
    // Cholesky with a small relative jitter (sampling only; the covariance may be numerically singular).
    const double scale = std::max(cov.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    MatX jittered = cov;
    Eigen::LLT<MatX> llt;
    for (double jitter = 1e-10; jitter < 1.0; jitter *= 10.0) {
        jittered = cov;
        jittered.diagonal().array() += jitter * scale;
        llt.compute(jittered);
        if (llt.info() == Eigen::Success) break;
    }
    if (llt.info() != Eigen::Success) throw InvalidArgument("sample_children: covariance cannot be factorized");
    const MatX l = llt.matrixL();
    std::normal_distribution<double> normal(0.0, 1.0);
    for (std::size_t s = 0; s < count; ++s) {
        VecX xi(mean.size());
        for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = normal(rng);
        out.push_back(unvec_output_major(mean + l * xi, d, ts));
    }
}

}  // namespace

namespace {
void check_model_data(const HgpModel& model, const HgpData& data, const char* what) {
    validate(model);
    validate(data);
    if (model.outputs() != data.outputs())
        throw InvalidArgument(std::string(what) + ": model has " + std::to_string(model.outputs()) + " outputs, data " +
                              std::to_string(data.outputs()));
    if (model.grouped && data.groups.empty())
        throw InvalidArgument(std::string(what) + ": a three-layer model needs each child's group (HgpData::groups)");
}

/// Whether the structured and low-rank likelihoods apply: every child complete.
bool structure_applies(const HgpData& data) { return data.all_complete(); }
}  // namespace

LikelihoodValue log_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, LikelihoodPath path,
                               int threads) {
    check_model_data(model, data, "log_likelihood");
    const bool structured = structure_applies(data);
    if ((path == LikelihoodPath::Structured || path == LikelihoodPath::LowRank) && !structured)
        throw InvalidArgument(
            "log_likelihood: the structured and low-rank paths need every child complete (use Dense or Auto)");
    if (path == LikelihoodPath::Dense || (path == LikelihoodPath::Auto && !structured))
        return dense_likelihood(model, data, with_gradient);
    if (path == LikelihoodPath::Structured) return detail::structured_likelihood(model, data, with_gradient, threads);
    const detail::Levels levels = detail::make_levels(model, data);
    if (path == LikelihoodPath::LowRank)
        return detail::low_rank_likelihood(model, data, levels, with_gradient, threads);
    // Auto, every child complete.
    if (detail::low_rank_is_cheaper(model, data, levels)) {
        LikelihoodValue v = detail::low_rank_likelihood(model, data, levels, with_gradient, threads);
        if (v.ok()) return v;
        // P (the κ and noise blocks) may be singular while the full covariance is not.
    }
    return detail::structured_likelihood(model, data, with_gradient, threads);
}

namespace {
void check_prediction_args(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_model_data(model, data, "prediction");
    check_times(t_star);
}

std::vector<std::size_t> all_children(const HgpData& data) {
    std::vector<std::size_t> all(data.child_count());
    for (std::size_t r = 0; r < all.size(); ++r) all[r] = r;
    return all;
}
}  // namespace

GaussianPrediction predict_parent_dense(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    return condition_dense(model, data, t_star, Target{Target::Parent, 0});
}

namespace {
void check_group(const HgpModel& model, const HgpData& data, std::size_t group) {
    if (!model.grouped) throw InvalidArgument("predict_group: the model has no group layer");
    if (group >= data.group_count()) throw InvalidArgument("predict_group: no group " + std::to_string(group));
}
}  // namespace

GaussianPrediction predict_group_dense(const HgpModel& model, const HgpData& data, std::size_t group,
                                       const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    check_group(model, data, group);
    return condition_dense(model, data, t_star, Target{Target::Group, group});
}

GaussianPrediction predict_group(const HgpModel& model, const HgpData& data, std::size_t group, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    check_group(model, data, group);
    if (!data.all_complete()) return condition_dense(model, data, t_star, Target{Target::Group, group});
    const Grid grid = make_grid(data.times, t_star);
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    return grid_prediction(group_on_grid(model, data, group, -1, grid), grid, d, model.noise_variance());
}

GaussianPrediction predict_child_dense(const HgpModel& model, const HgpData& data, std::size_t child,
                                       const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    if (!model.hierarchical) {
        // MOA: the siblings are independent of the child; condition on its own values only.
        HgpData own;
        own.times = data.times;
        own.children = {data.children[child]};
        if (child < data.observed.size()) own.observed = {data.observed[child]};
        bool any = false;
        for (std::size_t f = 0; f < own.frames(); ++f) any = any || own.is_observed(0, f);
        if (!any) {
            GaussianPrediction p;
            p.mean = MatX::Zero(static_cast<Eigen::Index>(data.outputs()), t_star.size());
            p.variance = unvec_output_major(lmc_covariance(model.child, t_star, t_star).diagonal(),
                                            static_cast<Eigen::Index>(data.outputs()), t_star.size());
            p.noise = model.noise_variance();
            return p;
        }
        return condition_dense(model, own, t_star, Target{Target::Child, 0});
    }
    return condition_dense(model, data, t_star, Target{Target::Child, child});
}

GaussianPrediction predict_parent(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    if (!data.all_complete()) return condition_dense(model, data, t_star, Target{Target::Parent, 0});
    const Grid grid = make_grid(data.times, t_star);
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    return grid_prediction(trend_on_grid(model, data, all_children(data), grid), grid, d, model.noise_variance());
}

GaussianPrediction predict_child(const HgpModel& model, const HgpData& data, std::size_t child, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    bool siblings_complete = true;
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != child && !data.is_complete(r)) siblings_complete = false;
    if (model.hierarchical && !siblings_complete)
        return condition_dense(model, data, t_star, Target{Target::Child, child});
    const Grid grid = make_grid(data.times, t_star);
    GridGaussian g = child_prior_on_grid(model, data, child, grid);
    if (g.ok) g.ok = condition_on_own_frames(g, model, data, child, nullptr, grid, false);
    return grid_prediction(g, grid, static_cast<Eigen::Index>(data.outputs()), model.noise_variance());
}

std::vector<GaussianPrediction> predict_child_masks(const HgpModel& model, const HgpData& data, std::size_t child,
                                                    const std::vector<std::vector<bool>>& masks) {
    check_prediction_args(model, data, data.times);
    if (child >= data.child_count()) throw InvalidArgument("predict_child_masks: no child " + std::to_string(child));
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != child && !data.is_complete(r))
            throw InvalidArgument("predict_child_masks: sibling " + std::to_string(r) + " has missing frames");
    for (const auto& m : masks)
        if (m.size() != data.frames())
            throw InvalidArgument("predict_child_masks: a mask has " + std::to_string(m.size()) + " flags, expected " +
                                  std::to_string(data.frames()));
    const Grid grid = make_grid(data.times, data.times);
    const GridGaussian prior = child_prior_on_grid(model, data, child, grid);
    std::vector<GaussianPrediction> out;
    for (const auto& m : masks) {
        GridGaussian g = prior;
        if (g.ok) g.ok = condition_on_own_frames(g, model, data, child, &m, grid, false);
        out.push_back(grid_prediction(g, grid, static_cast<Eigen::Index>(data.outputs()), model.noise_variance()));
    }
    return out;
}

MatX synthesis_trend(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (model.hierarchical) return predict_parent(model, data, t_star).mean;
    // MOA: every observed value of every child is a noisy observation of one function f ~ GP(0, K_f).
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    if (data.all_complete()) {
        // R complete replicates at the same times: their mean ȳ is sufficient, with noise N/R
        // (one (D·T)² factorization instead of (R·D·T)²).
        const double rd = static_cast<double>(data.child_count());
        VecX mean = VecX::Zero(d * t);
        for (const MatX& y : data.children) mean += vec_output_major(y);
        mean /= rd;
        MatX s = lmc_covariance(model.child, data.times, data.times);
        s.diagonal() += flat_noise(model.noise_variance(), t) / rd;
        Eigen::LLT<MatX> llt(s);
        if (llt.info() != Eigen::Success)
            throw NumericalError(
                "GP trend: the children's mean covariance is not positive definite for these parameters");
        return unvec_output_major(lmc_covariance(model.child, t_star, data.times) * llt.solve(mean), d, t_star.size());
    }
    const DenseLayout l = dense_layout(data);
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), t);
    const Eigen::Index n = static_cast<Eigen::Index>(l.flat.size());
    MatX s(n, n);
    for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index i = 0; i < n; ++i) s(i, j) = kf(l.flat[i], l.flat[j]) + (i == j ? noise[l.flat[i]] : 0.0);
    const MatX ks = lmc_covariance(model.child, t_star, data.times);
    MatX cross(d * t_star.size(), n);
    for (Eigen::Index j = 0; j < n; ++j) cross.col(j) = ks.col(l.flat[j]);
    Eigen::LLT<MatX> llt(s);
    if (llt.info() != Eigen::Success)
        throw NumericalError("GP trend: the children's covariance is not positive definite for these parameters");
    return unvec_output_major(cross * llt.solve(l.y), d, t_star.size());
}

std::vector<MatX> sample_children(const HgpModel& model, const HgpData& data, const VecX& t_star, std::size_t count,
                                  const SampleOptions& options) {
    check_prediction_args(model, data, t_star);
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index ts = t_star.size();
    VecX mean;
    MatX cov = lmc_covariance(model.child, t_star, t_star);
    const bool posterior_needed = options.group.has_value() || (model.hierarchical && options.parent_uncertainty);
    if (posterior_needed && !data.all_complete())
        throw InvalidArgument("sample_children: parent_uncertainty and group need every child complete");
    if (options.group) {
        // A new child of an existing group: that group's function's posterior, then K_f.
        check_group(model, data, *options.group);
        const Grid grid = make_grid(data.times, t_star);
        const GridGaussian pg = at_queries(group_on_grid(model, data, *options.group, -1, grid), grid, d);
        if (!pg.ok) throw InvalidArgument("sample_children: the group posterior cannot be computed");
        mean = pg.mean;
        if (options.parent_uncertainty) cov += pg.cov;
    } else {
        // Three layers: a new child of a new group deviates from the trend by h + f.
        if (model.grouped) cov += lmc_covariance(model.group, t_star, t_star);
        if (model.hierarchical && options.parent_uncertainty) {
            const Grid grid = make_grid(data.times, t_star);
            const GridGaussian pp = at_queries(trend_on_grid(model, data, all_children(data), grid), grid, d);
            if (!pp.ok) throw InvalidArgument("sample_children: the parent posterior cannot be computed");
            mean = pp.mean;
            cov += pp.cov;
        } else {
            mean = vec_output_major(synthesis_trend(model, data, t_star));
        }
    }
    if (options.add_noise) cov.diagonal() += flat_noise(model.noise_variance(), ts);
    std::mt19937_64 rng(options.seed);
    std::vector<MatX> out;
    draw_gaussian(mean, cov, count, rng, d, ts, out);
    return out;
}

}  // namespace mocapdb::gp

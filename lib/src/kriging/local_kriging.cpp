#include "mocapdb/kriging/local_kriging.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "gamma_vector.hpp"

namespace mocapdb::kriging {

namespace {
// Columns of the variogram matrix computed at a time (OLS variance precomputation).
constexpr Eigen::Index kGammaBlock = 256;
}  // namespace

LocalKriging LocalKriging::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                                 const KrigingOptions& options, Eigen::Index neighbours) {
    if (neighbours < 1)
        throw InvalidArgument("LocalKriging::build: the neighbourhood must have k >= 1 points, got " +
                              std::to_string(neighbours));
    // Validation, duplicates grouped and the trend basis, exactly as Kriging::build (the local systems
    // then see unique points only).
    Kriging prepared = Kriging::prepare(coords, model, options);
    LocalKriging lk;
    lk.model_ = model;
    lk.options_ = options;
    lk.points_ = std::move(prepared.points_);
    lk.group_ = std::move(prepared.group_);
    lk.group_size_ = std::move(prepared.group_size_);
    lk.basis_ = std::move(prepared.basis_);
    lk.status_ = prepared.status_;
    lk.neighbours_ = std::min(neighbours, lk.points_.rows());
    lk.local_options_ = options;
    lk.ols_ = options.trend_fit == TrendFit::OLS && options.trend == TrendKind::Linear;
    if (lk.ols_) {
        // The residuals of the global trend are kriged locally: ordinary kriging in each neighbourhood.
        lk.local_options_.trend = TrendKind::None;
        lk.u_ = lk.basis_.sample_basis().rightCols(lk.basis_.rank());
        // Gamma U by blocks of Gamma's columns (M by block at a time; Gamma itself is never held).
        const Eigen::Index m = lk.points_.rows();
        lk.gamma_u_ = Eigen::MatrixXd::Zero(m, lk.u_.cols());
        Eigen::MatrixXd block;
        for (Eigen::Index j0 = 0; j0 < m && lk.u_.cols() > 0; j0 += kGammaBlock) {
            const Eigen::Index nb = std::min(kGammaBlock, m - j0);
            block.resize(m, nb);
            detail::gamma_block(lk.points_, model, lk.points_.middleRows(j0, nb), block);
            lk.gamma_u_.noalias() += block * lk.u_.middleRows(j0, nb);
        }
        lk.ut_gamma_u_ = lk.u_.transpose() * lk.gamma_u_;
    }
    return lk;
}

Eigen::VectorXi LocalKriging::neighbourhood(const Eigen::Ref<const Eigen::VectorXd>& c) const {
    if (c.size() != dimension())
        throw InvalidArgument("LocalKriging: c must have P = " + std::to_string(dimension()) + " entries, got " +
                              std::to_string(c.size()));
    if (points_.rows() == 0) throw InvalidArgument("LocalKriging: the object is empty (not built)");
    const Eigen::Index m = points_.rows();
    Eigen::VectorXd d2 = (points_.col(0).array() - c(0)).square().matrix();
    for (Eigen::Index p = 1; p < points_.cols(); ++p) d2.array() += (points_.col(p).array() - c(p)).square();
    std::vector<Eigen::Index> order(static_cast<std::size_t>(m));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    const auto closer = [&d2](Eigen::Index a, Eigen::Index b) { return d2(a) < d2(b) || (d2(a) == d2(b) && a < b); };
    const auto k = static_cast<std::ptrdiff_t>(neighbours_);
    std::nth_element(order.begin(), order.begin() + (k - 1), order.end(), closer);
    std::sort(order.begin(), order.begin() + k, closer);
    Eigen::VectorXi nb(neighbours_);
    for (Eigen::Index j = 0; j < neighbours_; ++j) nb(j) = static_cast<int>(order[static_cast<std::size_t>(j)]);
    return nb;
}

LocalKriging::Solution LocalKriging::solve(const Eigen::Ref<const Eigen::VectorXd>& c, bool with_variance) const {
    const Eigen::VectorXi nb = neighbourhood(c);
    const Eigen::Index k = nb.size();
    const Eigen::Index m = points_.rows();
    Eigen::MatrixXd local(k, points_.cols());
    for (Eigen::Index j = 0; j < k; ++j) local.row(j) = points_.row(nb(j));
    const Kriging system = Kriging::build(local, model_, local_options_);
    // Local weights (== the kernel: GLS, ordinary kriging, and the OLS residuals' ordinary kriging).
    Eigen::VectorXd lw(k);
    Solution s;
    if (with_variance) {
        const KrigingEstimate e = system.estimate(c);
        lw = e.kernel;
        s.variance = e.variance;
        s.paper_variance = e.paper_variance;
    } else {
        QueryWorkspace ws;
        system.weights(c, lw, ws);
    }
    s.kernel = Eigen::VectorXd::Zero(m);
    for (Eigen::Index j = 0; j < k; ++j) s.kernel(nb(j)) = lw(j);
    if (!ols_) {
        s.weights = s.kernel;
        return s;
    }
    // OLS: w = b + U a, a = g_u(c) - U^T b, with the global trend basis (as Kriging's OLS weights).
    const Eigen::Index r = u_.cols();
    Eigen::VectorXd g(basis_.size());
    basis_.evaluate(c, g);
    Eigen::VectorXd a = g.tail(r);
    Eigen::VectorXd ugb = Eigen::VectorXd::Zero(r);  // U^T Gamma b
    for (Eigen::Index j = 0; j < k; ++j) {
        a -= lw(j) * u_.row(nb(j)).transpose();
        ugb += lw(j) * gamma_u_.row(nb(j)).transpose();
    }
    s.weights = s.kernel;
    s.weights.noalias() += u_ * a;
    if (with_variance) {
        // V = 2 w^T gamma(c) - w^T Gamma w (+ the nugget when filtered), as Kriging's OLS variance, with
        // w^T Gamma w = b^T Gamma b + 2 a^T U^T Gamma b + a^T U^T Gamma U a (b nonzero on the neighbours only).
        VariogramModel query_model = model_;
        if (options_.filter_nugget) query_model.nugget = 0.0;
        Eigen::VectorXd gq(m);
        detail::gamma_vector(points_, query_model, c, gq);
        const Eigen::MatrixXd& gnb = system.gamma_matrix();
        const double bgb = lw.dot(gnb * lw);
        const double wgw = bgb + 2.0 * a.dot(ugb) + a.dot(ut_gamma_u_ * a);
        s.variance = std::max(2.0 * s.weights.dot(gq) - wgw + (options_.filter_nugget ? model_.nugget : 0.0), 0.0);
    }
    return s;
}

void LocalKriging::expand(const Eigen::VectorXd& unique, Eigen::Ref<Eigen::VectorXd> out) const {
    for (Eigen::Index i = 0; i < group_.size(); ++i) out(i) = unique(group_(i)) / group_size_(group_(i));
}

double LocalKriging::reliability_of(const Solution& s) const {
    const double v = options_.reliability == ReliabilityVariance::Paper ? s.paper_variance : s.variance;
    return std::clamp(1.0 - v / model_.total_sill(), 0.0, 1.0);
}

void LocalKriging::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                           QueryWorkspace& /*workspace*/) const {
    if (out_weights.size() != num_samples())
        throw InvalidArgument("LocalKriging::weights: out_weights must have N = " + std::to_string(num_samples()) +
                              " entries");
    expand(solve(c, false).weights, out_weights);
}

void LocalKriging::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                 Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != dimension() || out_weights.rows() != num_samples() || out_weights.cols() != queries.rows())
        throw InvalidArgument(
            "LocalKriging::weights_batch: queries must be Q by P (P = " + std::to_string(dimension()) +
            ") and out_weights N by Q (N = " + std::to_string(num_samples()) + ")");
    for (Eigen::Index q = 0; q < queries.rows(); ++q)
        expand(solve(queries.row(q).transpose(), false).weights, out_weights.col(q));
}

KrigingEstimate LocalKriging::estimate(const Eigen::Ref<const Eigen::VectorXd>& c) const {
    const Solution s = solve(c, true);
    KrigingEstimate e;
    e.variance = s.variance;
    e.paper_variance = s.paper_variance;
    e.reliability = reliability_of(s);
    e.weights.resize(num_samples());
    e.kernel.resize(num_samples());
    expand(s.weights, e.weights);
    expand(s.kernel, e.kernel);
    return e;
}

KrigingBatch LocalKriging::estimate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension())
        throw InvalidArgument("LocalKriging::estimate_batch: queries must be Q by P with P = " +
                              std::to_string(dimension()));
    const Eigen::Index nq = queries.rows();
    KrigingBatch out;
    out.weights.resize(num_samples(), nq);
    out.variance.resize(nq);
    out.paper_variance.resize(nq);
    out.reliability.resize(nq);
    for (Eigen::Index q = 0; q < nq; ++q) {
        const Solution s = solve(queries.row(q).transpose(), true);
        expand(s.weights, out.weights.col(q));
        out.variance(q) = s.variance;
        out.paper_variance(q) = s.paper_variance;
        out.reliability(q) = reliability_of(s);
    }
    return out;
}

Eigen::VectorXd LocalKriging::reliability(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension())
        throw InvalidArgument("LocalKriging::reliability: queries must be Q by P with P = " +
                              std::to_string(dimension()));
    Eigen::VectorXd rho(queries.rows());
    for (Eigen::Index q = 0; q < queries.rows(); ++q) rho(q) = reliability_of(solve(queries.row(q).transpose(), true));
    return rho;
}

}  // namespace mocapdb::kriging

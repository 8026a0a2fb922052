#include "mocapdb/kriging/local_kriging.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "prepared_points.hpp"

namespace mocapdb::kriging {

LocalKriging LocalKriging::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                                 const KrigingOptions& options, Eigen::Index neighbours) {
    detail::validate_coords("LocalKriging::build", coords);
    if (neighbours < 1)
        throw InvalidArgument("LocalKriging::build: the neighbourhood must have k >= 1 points, got " +
                              std::to_string(neighbours));
    // The model and options are checked as Kriging::build checks them (a one-point system: no cost).
    (void)Kriging::build(coords.topRows(1), model, options);
    LocalKriging lk;
    lk.model_ = model;
    lk.options_ = options;
    // Duplicates grouped as the exact kriging groups them (the local systems then see unique points only).
    detail::PreparedPoints prepared =
        detail::prepare_points(coords, options.duplicate_tolerance, options.duplicates == DuplicatePolicy::Merge,
                               options.trend, options.trend_rank_tolerance);
    lk.points_ = std::move(prepared.points);
    lk.group_ = std::move(prepared.group);
    lk.group_size_ = std::move(prepared.group_size);
    lk.neighbours_ = std::min(neighbours, lk.points_.rows());
    lk.status_.unique_points = lk.points_.rows();
    lk.status_.duplicates_merged = coords.rows() - lk.points_.rows();
    lk.status_.duplicate_pairs = prepared.duplicate_pairs;
    lk.status_.trend_rank = prepared.basis.rank();
    lk.status_.trend_rank_deficient = prepared.basis.rank_deficient();
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

Kriging LocalKriging::local_system(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::VectorXi& nb) const {
    nb = neighbourhood(c);
    Eigen::MatrixXd local(nb.size(), points_.cols());
    for (Eigen::Index j = 0; j < nb.size(); ++j) local.row(j) = points_.row(nb(j));
    return Kriging::build(local, model_, options_);
}

void LocalKriging::scatter(const Eigen::VectorXi& nb, const Eigen::Ref<const Eigen::VectorXd>& local,
                           Eigen::Ref<Eigen::VectorXd> out) const {
    // position of each unique point in the neighbourhood (-1: outside), then one pass over the samples.
    Eigen::VectorXi slot = Eigen::VectorXi::Constant(points_.rows(), -1);
    for (Eigen::Index j = 0; j < nb.size(); ++j) slot(nb(j)) = static_cast<int>(j);
    for (Eigen::Index i = 0; i < group_.size(); ++i) {
        const int u = group_(i);
        out(i) = slot(u) < 0 ? 0.0 : local(slot(u)) / group_size_(u);
    }
}

void LocalKriging::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                           QueryWorkspace& ws) const {
    if (out_weights.size() != num_samples())
        throw InvalidArgument("LocalKriging::weights: out_weights must have N = " + std::to_string(num_samples()) +
                              " entries");
    Eigen::VectorXi nb;
    const Kriging k = local_system(c, nb);
    Eigen::VectorXd local(nb.size());
    k.weights(c, local, ws);
    scatter(nb, local, out_weights);
}

void LocalKriging::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                 Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != dimension() || out_weights.rows() != num_samples() || out_weights.cols() != queries.rows())
        throw InvalidArgument("LocalKriging::weights_batch: queries must be Q by P (P = " +
                              std::to_string(dimension()) + ") and out_weights N by Q (N = " +
                              std::to_string(num_samples()) + ")");
    QueryWorkspace ws;
    for (Eigen::Index q = 0; q < queries.rows(); ++q) weights(queries.row(q).transpose(), out_weights.col(q), ws);
}

KrigingEstimate LocalKriging::estimate(const Eigen::Ref<const Eigen::VectorXd>& c) const {
    Eigen::VectorXi nb;
    const Kriging k = local_system(c, nb);
    const KrigingEstimate local = k.estimate(c);
    KrigingEstimate e;
    e.variance = local.variance;
    e.paper_variance = local.paper_variance;
    e.reliability = local.reliability;
    e.weights.resize(num_samples());
    e.kernel.resize(num_samples());
    scatter(nb, local.weights, e.weights);
    scatter(nb, local.kernel, e.kernel);
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
        Eigen::VectorXi nb;
        const Kriging k = local_system(queries.row(q).transpose(), nb);
        const KrigingBatch b = k.estimate_batch(queries.row(q));
        scatter(nb, b.weights.col(0), out.weights.col(q));
        out.variance(q) = b.variance(0);
        out.paper_variance(q) = b.paper_variance(0);
        out.reliability(q) = b.reliability(0);
    }
    return out;
}

Eigen::VectorXd LocalKriging::reliability(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension())
        throw InvalidArgument("LocalKriging::reliability: queries must be Q by P with P = " +
                              std::to_string(dimension()));
    Eigen::VectorXd rho(queries.rows());
    for (Eigen::Index q = 0; q < queries.rows(); ++q) {
        Eigen::VectorXi nb;
        rho(q) = local_system(queries.row(q).transpose(), nb).estimate_batch(queries.row(q)).reliability(0);
    }
    return rho;
}

}  // namespace mocapdb::kriging

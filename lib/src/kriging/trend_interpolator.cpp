#include "mocapdb/kriging/trend_interpolator.hpp"

#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

TrendInterpolator TrendInterpolator::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, TrendKind kind,
                                           double rank_tolerance) {
    TrendInterpolator t;
    t.basis_ = TrendBasis::build(coords, kind, rank_tolerance);
    // G's columns are orthogonal (trend.hpp): G^T G = diag(N, 1, ..., 1), so no system is solved.
    t.operator_ = t.basis_.sample_basis();
    t.operator_.col(0) /= static_cast<double>(coords.rows());
    return t;
}

void TrendInterpolator::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                                QueryWorkspace& workspace) const {
    if (c.size() != dimension() || out_weights.size() != num_samples()) {
        throw InvalidArgument("TrendInterpolator::weights: c must have P = " + std::to_string(dimension()) +
                              " entries and the weights N = " + std::to_string(num_samples()));
    }
    workspace.rhs.resize(basis_.size());
    basis_.evaluate(c, workspace.rhs);
    out_weights.noalias() = operator_ * workspace.rhs;
}

void TrendInterpolator::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                      Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != dimension() || out_weights.rows() != num_samples() || out_weights.cols() != queries.rows()) {
        throw InvalidArgument("TrendInterpolator::weights_batch: queries must be Q by P = " +
                              std::to_string(dimension()) + " and the weights N by Q");
    }
    out_weights.noalias() = operator_ * basis_.evaluate_batch(queries);
}

}  // namespace mocapdb::kriging

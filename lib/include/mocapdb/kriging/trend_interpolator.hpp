#pragma once
// The least-squares trend alone as an Interpolator: the prediction is the OLS hyperplane of the samples
// (trend.hpp), s*(c) = sum_i w_i(c) s_i with w(c) = G (G^T G)^-1 g(c). The weights form a partition of
// unity but do not interpolate: a sample's own parameters give the hyperplane there, not the sample.
// The baseline every kernel must beat, and a predictor synthesis may choose (synthesis/predictor_choice.hpp).
// Errors: InvalidArgument for bad coordinates (as TrendBasis::build). Thread safety: immutable.
#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::kriging {

class TrendInterpolator final : public Interpolator {
public:
    TrendInterpolator() = default;

    /// coords: N by P normalized control points (N >= 1, finite).
    static TrendInterpolator build(const Eigen::Ref<const Eigen::MatrixXd>& coords, TrendKind kind = TrendKind::Linear,
                                   double rank_tolerance = 1e-10);

    Eigen::Index num_samples() const override { return operator_.rows(); }
    Eigen::Index dimension() const override { return basis_.dimension(); }
    void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                 QueryWorkspace& workspace) const override;
    void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                       Eigen::Ref<Eigen::MatrixXd> out_weights) const override;
    using Interpolator::weights;
    using Interpolator::weights_batch;

    const TrendBasis& basis() const { return basis_; }

private:
    TrendBasis basis_;
    Eigen::MatrixXd operator_;  // N by K: G (G^T G)^-1
};

}  // namespace mocapdb::kriging

#pragma once
// The interface shared by every scattered-data interpolator of this module (kriging, RBF), so that any
// comparison can swap one for the other.
//
// All of them are linear in the sample values: the prediction at control parameters c is
//     s*(c) = sum_i w_i(c) s_i,
// with weights w(c) that depend on the control points only, form a partition of unity
// (sum_i w_i(c) = 1) and interpolate exactly (w(c_j) = e_j). Vector-valued samples (whole motions,
// pose vectors, tensor coefficients) are blended with the same weights, column by column.
#include <Eigen/Core>

namespace mocapdb::kriging {

/// Scratch buffers for allocation-free single queries. Owned by the caller, one per thread; an
/// interpolator resizes them on first use.
struct QueryWorkspace {
    Eigen::VectorXd rhs;
    Eigen::VectorXd tmp;
    Eigen::VectorXd tmp2;
};

class Interpolator {
public:
    virtual ~Interpolator() = default;

    /// N: number of samples the weights refer to.
    virtual Eigen::Index num_samples() const = 0;
    /// P: dimension of the control space.
    virtual Eigen::Index dimension() const = 0;

    /// Weights at one query. c: P; out_weights: N. Thread-safe (the object is immutable).
    virtual void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                         QueryWorkspace& workspace) const = 0;
    /// Weights at many queries (a matrix product). queries: Q by P; out_weights: N by Q.
    virtual void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                               Eigen::Ref<Eigen::MatrixXd> out_weights) const = 0;

    /// Convenience: allocating single-query weights (N).
    Eigen::VectorXd weights(const Eigen::Ref<const Eigen::VectorXd>& c) const;
    /// Convenience: allocating batch weights (N by Q).
    Eigen::MatrixXd weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;
    /// Predictions: queries Q by P, values N by D (one row per sample); returns Q by D.
    Eigen::MatrixXd predict(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                            const Eigen::Ref<const Eigen::MatrixXd>& values) const;
};

}  // namespace mocapdb::kriging

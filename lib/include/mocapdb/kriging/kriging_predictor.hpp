#pragma once
// Kriging of FIXED sample values with the values folded into the operator ("fold once, then one small
// product per query"). For values V (N by S, one row per sample) the prediction
//     s*(c) = sum_i w_i(c) v_i = V^T w(c)
// is, with the kriging weights of kriging.hpp written as w = E (P Op [gamma(c); g(c)] + G D g(c))
// (Op the M by (M + K) weight operator on the unique points, P = I - G D G^T the constraint projection,
// D = diag(1/M, 1, ..., 1), E the expansion of merged duplicates to the N samples),
//     s*(c) = F [gamma(c); g(c)],   F = (P E^T V)^T Op + [0, (E^T V)^T G D]   (S by M + K),
// computed once here. A query then costs S (M + K) multiply-adds instead of the weights' M (M + K) plus
// the N S of the blend: for the synthesis model's R3 = 24 coefficients of N = 92 samples (P = 4),
// 24 x 97 instead of 92 x 97 + 92 x 24, and F (18 KiB) stays in the L1 cache.
//
// The result equals V^T weights(c) up to rounding (the same products in another order; tested to
// ~1e-12 relative). The constraint projection is folded too, so the unbiasedness constraints hold only
// to the rounding of F (~1e-16 |Op| instead of ~1e-16 |w|): exact weights for ill-conditioned systems
// remain the Kriging object's job. Variances and reliability need the weights: use Kriging.
//
// Immutable after build() and independent of the Kriging object it was built from (it keeps its own
// copy of the unique points, the model and the trend basis); safe to query from several threads (one
// QueryWorkspace or scratch matrix per thread).
#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging {

class KrigingPredictor {
public:
    KrigingPredictor() = default;

    /// values: N by S (N = kriging.num_samples(), S >= 1), finite. Throws InvalidArgument otherwise.
    static KrigingPredictor build(const Kriging& kriging, const Eigen::Ref<const Eigen::MatrixXd>& values);

    Eigen::Index num_samples() const { return num_samples_; }  ///< N
    Eigen::Index dimension() const { return points_.cols(); }  ///< P
    Eigen::Index output_size() const { return folded_.rows(); }  ///< S
    bool empty() const { return folded_.size() == 0; }

    /// s*(c): c P (the kriging's coordinates), out S. No allocation once the workspace has its size.
    void predict(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out,
                 QueryWorkspace& workspace) const;
    /// Q queries (Q by P) into out (S by Q): per block of queries, the gamma block and one matrix product.
    /// scratch: any matrix, resized to (M + K) by min(Q, block) (no allocation when it already has that size).
    void predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out,
                       Eigen::MatrixXd& scratch) const;
    /// Allocating convenience: S by Q.
    Eigen::MatrixXd predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;

    /// F (S by M + K), applied to [gamma(c); g(c)].
    const Eigen::MatrixXd& folded_operator() const { return folded_; }

private:
    VariogramModel model_;
    TrendBasis basis_;
    Eigen::MatrixXd points_;  // M by P unique control points
    Eigen::MatrixXd folded_;  // S by M + K
    Eigen::Index num_samples_ = 0;
};

}  // namespace mocapdb::kriging

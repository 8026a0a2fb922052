#pragma once
// Kriging of FIXED sample values with the values folded into the operator ("fold once, then one small
// product per query"). For values V (N by S, one row per sample) the prediction
//     s*(c) = sum_i w_i(c) v_i = V^T w(c)
// is, with the kriging weights of kriging.hpp written as w = E (P Op [gamma(c); g(c)] + G D g(c))
// (Op the M by (M + K) weight operator on the unique points, P = I - G D G^T the constraint projection,
// D = diag(1/M, 1, ..., 1), E the expansion of merged duplicates to the N samples),
//     s*(c) = F [gamma(c); g(c)],   F = (P E^T V)^T Op + [0, (E^T V)^T G D]   (S by M + K),
// computed once here.
//
// Details: docs/headers/kriging.md (mocapdb/kriging/kriging_predictor.hpp).
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

    Eigen::Index num_samples() const { return num_samples_; }    ///< N
    Eigen::Index dimension() const { return points_.cols(); }    ///< P
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

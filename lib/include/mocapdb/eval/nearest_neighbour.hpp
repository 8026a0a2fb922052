#pragma once
// The nearest-neighbour blend baseline of the evaluation: inverse-distance weights over the k samples
// nearest to the query (Euclidean distance of the control points as given, so pass normalized
// parameters, kriging::ControlScaling),
//     w_i(c) = d_i^-p / sum_{j in kNN(c)} d_j^-p  for i in kNN(c), 0 otherwise,
// exact at a sample (a query at distance 0 from some samples splits the weight evenly among them).
// Partition of unity and exact interpolation, so it implements kriging::Interpolator and blends whole
// motions like the other methods. Ties in the k-th distance are broken by sample index.
#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"

namespace mocapdb::eval {

struct NearestNeighbourOptions {
    Eigen::Index k = 3;  ///< >= 1 (clamped to N)
    double power = 2.0;  ///< > 0
};

class NearestNeighbourBlend final : public kriging::Interpolator {
public:
    /// coords: N by P (N >= 1, finite). InvalidArgument on bad shapes or options.
    NearestNeighbourBlend(const Eigen::Ref<const Eigen::MatrixXd>& coords, const NearestNeighbourOptions& options = {});

    Eigen::Index num_samples() const override { return points_.rows(); }
    Eigen::Index dimension() const override { return points_.cols(); }
    void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                 kriging::QueryWorkspace& workspace) const override;
    void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                       Eigen::Ref<Eigen::MatrixXd> out_weights) const override;
    using Interpolator::weights;
    using Interpolator::weights_batch;

private:
    Eigen::MatrixXd points_;
    NearestNeighbourOptions options_;
};

}  // namespace mocapdb::eval

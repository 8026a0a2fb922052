#pragma once
// Moving-neighbourhood (local) kriging, as gstat's nmax: a query is answered by the kriging system
// (kriging.hpp, same variogram and options) of its k nearest control points only. GLS / ordinary
// kriging: the trend is fitted in that neighbourhood (gstat's local universal kriging). OLS (the
// paper's): the global least-squares trend of all points is kept, its residuals are kriged locally.
// Cost per query: O(M P) for the search, O(k^3) for the local system; memory O(M P) plus O(k^2) per
// query, no M by M matrix (OLS: O(M^2 P) time once at build for the variance). With k >= M it is
// Kriging::build on all points (to rounding). The prediction jumps where the neighbourhood changes.
//
// Immutable after build(); thread-safe (each query builds its own local system).
//
// Details: docs/headers/kriging.md (mocapdb/kriging/local_kriging.hpp).
#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging {

class LocalKriging final : public Interpolator {
public:
    LocalKriging() = default;

    /// coords: N by P control points (as Kriging::build, whose errors it throws); neighbours: k >= 1, the
    /// points of each local system (all of them when k >= the number of unique points).
    static LocalKriging build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                              const KrigingOptions& options, Eigen::Index neighbours);

    Eigen::Index num_samples() const override { return group_.size(); }
    Eigen::Index dimension() const override { return points_.cols(); }
    /// k actually used: min(neighbours, unique points).
    Eigen::Index neighbours() const { return neighbours_; }

    /// The k unique points nearest to c (indices into unique_points(), nearest first; equal distances in
    /// index order).
    Eigen::VectorXi neighbourhood(const Eigen::Ref<const Eigen::VectorXd>& c) const;

    /// w(c): c P, out_weights N (zero outside the neighbourhood).
    void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                 QueryWorkspace& workspace) const override;
    /// queries Q by P, out_weights N by Q.
    void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                       Eigen::Ref<Eigen::MatrixXd> out_weights) const override;
    using Interpolator::weights;
    using Interpolator::weights_batch;

    /// All outputs at one query, from its local system (weights and kernel on the N samples).
    KrigingEstimate estimate(const Eigen::Ref<const Eigen::VectorXd>& c) const;
    /// All outputs at Q queries (queries: Q by P).
    KrigingBatch estimate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;
    /// rho at Q queries (Q by P).
    Eigen::VectorXd reliability(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;

    const VariogramModel& model() const { return model_; }
    const KrigingOptions& options() const { return options_; }
    /// Of the whole set: duplicates and trend rank; factorization Ok (each local system has its own).
    const KrigingStatus& status() const { return status_; }
    const Eigen::MatrixXd& unique_points() const { return points_; }
    const Eigen::VectorXi& unique_index() const { return group_; }

private:
    // One query on the unique points: weights and kernel (M), variances (when asked for).
    struct Solution {
        Eigen::VectorXd weights, kernel;
        double variance = 0.0, paper_variance = 0.0;
    };
    Solution solve(const Eigen::Ref<const Eigen::VectorXd>& c, bool with_variance) const;
    // Unique-point values (M) to the N samples (out: N), a merged point's value split among its samples.
    void expand(const Eigen::VectorXd& unique, Eigen::Ref<Eigen::VectorXd> out) const;
    double reliability_of(const Solution& s) const;

    VariogramModel model_;
    KrigingOptions options_;
    KrigingStatus status_;
    Eigen::MatrixXd points_;      // M by P unique control points
    Eigen::VectorXi group_;       // N -> unique index
    Eigen::VectorXd group_size_;  // M
    Eigen::Index neighbours_ = 0;
    KrigingOptions local_options_;  // of the local systems (OLS: ordinary kriging of the residuals)
    bool ols_ = false;
    TrendBasis basis_;            // global, over the unique points
    Eigen::MatrixXd u_;           // OLS: M by r orthonormal trend columns (basis_ without the constant)
    Eigen::MatrixXd gamma_u_;     // OLS: Gamma U (M by r), Gamma the variogram matrix of the unique points
    Eigen::MatrixXd ut_gamma_u_;  // OLS: U^T Gamma U (r by r)
};

}  // namespace mocapdb::kriging

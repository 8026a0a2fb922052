#pragma once
// Radial-basis-function interpolation baseline (Rose, Cohen & Bodenheimer 1998 "Verbs and adverbs";
// Rose, Sloan & Cohen 2001): a linear least-squares hyperplane in the control parameters plus radial
// basis functions interpolating its residuals,
//     s*(c) = m(c) + sum_j a_j phi_j(|c - c_j|),   Phi a = r  (Phi_ij = phi_j(|c_i - c_j|)).
// Like kriging it is linear in the samples, s*(c) = sum_i w_i(c) s_i with
//     w(c) = h(c) + (I - H) Phi^-T phi(c),
// h(c) the least-squares trend weights and H the hat matrix, so it implements the same Interpolator
// interface (partition of unity, exact at the samples) and can be swapped in for any comparison.
//
// Details: docs/headers/kriging.md (mocapdb/kriging/rbf.hpp).
#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::kriging {

enum class RadialFunction { CubicBSpline, Gaussian, Linear, Cubic, ThinPlate };

const char* to_string(RadialFunction f);

struct RbfOptions {
    RadialFunction function = RadialFunction::CubicBSpline;
    double radius_scale = 2.0;  ///< > 0: CubicBSpline radius factor (times the nearest-neighbour distance).
    double width = 0.0;         ///< >= 0: Gaussian width; 0 = mean nearest-neighbour distance.
    TrendKind trend = TrendKind::Linear;
    double duplicate_tolerance = 0.0;     ///< >= 0, as in KrigingOptions.
    double trend_rank_tolerance = 1e-10;  ///< see TrendBasis::build.
};

struct RbfStatus {
    /// Ok: Phi factorized as is; Jittered: a small ridge made it invertible; Regularized: the heavy
    /// fallback ridge (10 % of Phi's largest entry) was needed, the interpolation is smoothed.
    FactorizationStatus factorization = FactorizationStatus::Ok;
    double ridge = 0.0;  ///< added to the diagonal of Phi when it was singular (0 normally).
    double rcond = 0.0;  ///< reciprocal condition estimate of (the factorized) Phi.
    Eigen::Index unique_points = 0;
    Eigen::Index duplicates_merged = 0;
    Eigen::Index trend_rank = 0;
    bool trend_rank_deficient = false;
};

class RbfInterpolator final : public Interpolator {
public:
    RbfInterpolator() = default;

    /// coords: N by P (N >= 1, finite). Throws InvalidArgument on bad shapes or options.
    static RbfInterpolator build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const RbfOptions& options = {});

    Eigen::Index num_samples() const override { return group_.size(); }
    Eigen::Index dimension() const override { return points_.cols(); }
    void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                 QueryWorkspace& workspace) const override;
    void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                       Eigen::Ref<Eigen::MatrixXd> out_weights) const override;
    using Interpolator::weights;
    using Interpolator::weights_batch;

    const RbfStatus& status() const { return status_; }
    const RbfOptions& options() const { return options_; }
    /// Radius (CubicBSpline) or width (Gaussian) of each unique center: M.
    const Eigen::VectorXd& radii() const { return radii_; }

private:
    void radial_vector(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out) const;

    RbfOptions options_;
    RbfStatus status_;
    TrendBasis basis_;
    Eigen::MatrixXd points_;      // M by P
    Eigen::VectorXi group_;       // N
    Eigen::VectorXd group_size_;  // M
    bool merged_ = false;
    Eigen::VectorXd radii_;     // M
    Eigen::MatrixXd operator_;  // M by (M + K): [(I - H) Phi^-T, G (G^T G)^-1]
};

}  // namespace mocapdb::kriging

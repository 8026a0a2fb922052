#pragma once
// Constraint accuracy (the geostatistical paper, Table 1) and reliability against error (§5.1): on a
// dense grid of control parameters c over the samples' bounding box, each method synthesizes the motion
// (with its timing, as a clip), the same extractors that measured the samples measure the achieved
// parameters c_hat, and the error is ||c - c_hat|| in normalized units (per axis divided by the samples'
// standard deviation, kriging::ControlScaling) so that axes of different units add up. Per method, the
// MAX and RMSE of that error over the grid points whose reliability rho(c) (the naive kriging model's
// coefficient kernel on all samples, paper Appendix B) is >= each threshold, and the Pearson correlation
// of rho and the error over all grid points.
//
// A grid point whose achieved parameter is undefined (e.g. a synthesized jump without a flight phase) is
// a failure: counted per method, excluded from the statistics, never a NaN.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::eval {

struct ConstraintOptions {
    Eigen::Index points_per_axis_2d = 12;  ///< grid points per axis when P = 2 (P > 2: the same per axis)
    Eigen::Index points_1d = 40;           ///< grid points when P = 1
    std::vector<double> thresholds = {0.9, 0.8, 0.7};
};

struct RegionStats {
    double threshold = 0.0;
    Eigen::Index points = 0;  ///< valid grid points with rho >= threshold
    double max = 0.0;         ///< MAX ||c - c_hat|| (normalized)
    double rmse = 0.0;        ///< RMSE ||c - c_hat|| (normalized)
    VecX axis_rmse;           ///< P: RMSE of c_p - c_hat_p in the parameter's own unit
};

struct ConstraintMethodResult {
    std::string method;
    MatX achieved;            ///< Q by P measured parameters (rows of failures hold the requested c)
    VecX error;               ///< Q normalized errors (0 for failures)
    std::vector<bool> valid;  ///< Q
    Eigen::Index failures = 0;
    std::vector<RegionStats> regions;  ///< one per threshold
    RegionStats all;                   ///< over every valid grid point (threshold 0)
    double pearson = 0.0;              ///< corr(rho, error) over valid points (0 when undefined)
    double seconds = 0.0;              ///< build + synthesis + measurement
    /// Q: the rho the regions and pearson use: the method's own (Synthesizer::reliability_batch, its own
    /// kernel) when it has one, else ConstraintResult::reliability.
    VecX reliability;
    bool own_reliability = false;  ///< reliability is the method's own
    /// The largest own rho at the 2P points 3 standard deviations outside the samples' box (from the box's
    /// centre along each axis, both sides: must be <= 0.5); none without an own rho.
    std::optional<double> rho_outside_3sd;
};

struct ConstraintResult {
    MatX grid;                     ///< Q by P requested parameters
    VecX reliability;              ///< Q: rho(c) of the reference kernel (naive kriging on all samples)
    VecX scale;                    ///< P: per-axis normalization (standard deviation of the samples)
    MatX outside_3sd;              ///< 2P by P: the points 3 standard deviations outside the box (see rho_outside_3sd)
    double rho_outside_3sd = 0.0;  ///< the reference kernel's largest rho there
    std::optional<double> loo_mean_z2;  ///< the reference kernel's leave-one-out mean z^2 (synthesis::KernelFit)
    std::vector<ConstraintMethodResult> methods;
};

/// Every method is built on all samples of `set`. Throws InvalidArgument on bad options.
ConstraintResult constraint_accuracy(const EvalSet& set, const std::vector<MethodSpec>& methods,
                                     const ConstraintOptions& options = {}, const ProgressCallback& progress = {});

/// Pearson correlation of two equally long vectors (0 when either is constant or shorter than 2).
double pearson(const Eigen::Ref<const VecX>& a, const Eigen::Ref<const VecX>& b);

}  // namespace mocapdb::eval

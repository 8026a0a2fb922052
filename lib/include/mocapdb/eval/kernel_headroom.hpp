#pragma once
// How much the choice of a stationary kernel could lower kriging's leave-one-out pose error on a set
// (the evaluation's claim "kriging beats RBF and the trend"): every kernel of a fixed grid (model
// exponent, range, nugget share and, with two or more linear parameters, the relative scale of the
// axes after the first) is used in every fold of a naive-kriging leave-one-out, and the best mean
// error over the grid is kept. The best is chosen on the very errors it is scored on, so no choice
// among these kernels made from the training samples alone can beat it: when it does not reach a
// baseline, fitting the variogram better will not either (unless it leaves the grid's families).
//
// Details: docs/headers/eval.md (mocapdb/eval/kernel_headroom.hpp).
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::eval {

struct KernelHeadroomOptions {
    std::vector<double> exponents = {0.0, 1.0, 1.5, 2.0};  ///< paper p (0 = spherical); p = 2 only with a nugget
    std::vector<double> ranges = {0.25, 0.5, 1.0, 2.0, 4.0, 8.0};   ///< in standard deviations of the parameters
    std::vector<double> nugget_shares = {0.0, 0.1, 0.3, 0.6, 0.9};  ///< nugget / (nugget + sill), in [0, 1)
    /// Scale of the parameter axes after the first relative to it (> 0), tried when the set has two or
    /// more parameters and none is periodic.
    std::vector<double> anisotropy = {0.5, 1.0, 2.0};
    std::vector<Eigen::Index> samples;  ///< the left-out samples (empty = all)
};

struct KernelHeadroom {
    Eigen::Index kernels = 0;      ///< grid kernels tried
    kriging::VariogramModel best;  ///< the kernel with the lowest mean pose error (total sill 1)
    double best_anisotropy = 1.0;
    double best_pose_mean_cm = 0.0;    ///< its leave-one-out mean pose error
    double median_pose_mean_cm = 0.0;  ///< the median over the grid
};

/// `progress` counts kernels.
KernelHeadroom kernel_headroom(const EvalSet& set, const KernelHeadroomOptions& options = {},
                               const ProgressCallback& progress = {});

}  // namespace mocapdb::eval

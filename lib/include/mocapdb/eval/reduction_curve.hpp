#pragma once
// Sample reduction (the geostatistical paper §5.2: 69 -> 29 samples at tau = 0.85) as a curve: the
// greedy reliability order of kriging::reduce_samples (run down to the trend size + 1, with the naive
// model's coefficient kernel on all samples, variogram fixed), and at a ladder of kept sizes m the
// joint-position error (cm, aligned time, as loo_prediction.hpp) of predicting every REMOVED sample
// from a naive kriging model built on the m kept ones. The same error for random removal orders (mean
// over `random_orders` seeds) is the baseline that shows whether the reliability order matters.
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/eval_set.hpp"

namespace mocapdb::eval {

struct ReductionCurveOptions {
    double tau = 0.85;
    Eigen::Index checkpoints = 8;  ///< kept sizes measured (spread from N - 1 down to the minimum), >= 1
    int random_orders = 3;         ///< >= 0
    unsigned seed = 7;
};

struct ReductionCurvePoint {
    Eigen::Index kept = 0;
    double max_reliability = 0.0;      ///< max_i rho_{-i}(c_i) over the kept samples at that size (greedy)
    double greedy_mean_cm = 0.0;       ///< mean over removed samples of their mean joint error
    double greedy_max_cm = 0.0;        ///< max joint error over removed samples
    double random_mean_cm = 0.0;       ///< the same for random removal (mean over orders); 0 without
    double greedy_pose_mean_cm = 0.0;  ///< as greedy_mean_cm with the root-relative pose error (loo_prediction.hpp)
    double random_pose_mean_cm = 0.0;  ///< as random_mean_cm, root-relative pose error
};

struct ReductionCurve {
    Eigen::Index samples = 0;
    std::vector<Eigen::Index> removal_order;  ///< greedy, sample indices
    std::vector<double> max_reliability;      ///< before each removal (reduction.hpp)
    Eigen::Index kept_at_tau = 0;             ///< samples left when the greedy loop stops at tau
    std::vector<ReductionCurvePoint> points;  ///< decreasing kept
};

/// Throws InvalidArgument for fewer than 5 samples or bad options.
ReductionCurve reduction_curve(const EvalSet& set, const ReductionCurveOptions& options = {},
                               const ProgressCallback& progress = {});

}  // namespace mocapdb::eval

#pragma once
// Greedy sample reduction by reliability (paper Section 5.2): repeatedly compute, for every remaining
// sample i, the reliability rho(c_i) predicted WITHOUT sample i, remove the sample with the highest
// value, and stop as soon as that highest value falls below the threshold tau.
//
// The variogram model is the one given (estimated once from all samples) and stays fixed during the
// reduction. Each step costs O(M^2): the leave-one-out reliabilities come in closed form from the data
// block of the inverse kriging system, and removing a sample is a rank-one downdate of that block
// (no refactorization). A sample with an exact duplicate among the remaining ones has reliability 1 and
// goes first.
#include <vector>

#include <Eigen/Core>

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging {

struct ReductionOptions {
    double tau = 0.85;             ///< stop when max_i rho_{-i}(c_i) < tau; in [0, 1].
    Eigen::Index min_samples = 0;  ///< never go below this many samples (0 = trend size + 1). >= 0.
    /// Kernel used for the reliabilities (OLS -> the paper's OK kernel). The reliability is always the
    /// paper's (ReliabilityVariance::Paper, whatever `kriging.reliability` says): its rank-one downdates.
    KrigingOptions kriging;
};

struct ReductionResult {
    std::vector<Eigen::Index> removed;        ///< sample indices (0-based, into the input), in removal order.
    std::vector<double> removed_reliability;  ///< rho of each removed sample at its removal.
    /// The curve: max_i rho_{-i}(c_i) before each step, removed.size() + 1 entries when the loop stopped on
    /// tau (the last one is the value that fell below tau), removed.size() when it stopped on min_samples.
    std::vector<double> max_reliability;
    std::vector<Eigen::Index> kept;     ///< remaining sample indices, ascending.
    bool stopped_on_threshold = false;  ///< false: stopped on min_samples.
    KrigingStatus status;               ///< status of the initial factorization.
};

/// coords: N by P. Throws InvalidArgument on bad shapes, an invalid model, or tau outside [0, 1].
ReductionResult reduce_samples(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                               const ReductionOptions& options = {});

}  // namespace mocapdb::kriging

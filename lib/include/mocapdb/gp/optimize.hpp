#pragma once
// Type-II maximum likelihood for HgpModel: L-BFGS (LBFGSpp) on the negative log marginal likelihood
// per observed value, with deterministic restarts. A fit never throws for numerical reasons: a failed
// line search or a non-positive-definite covariance ends that restart with a status, and the best
// parameters seen so far are kept.
#include <cstdint>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/gp/hierarchical_gp.hpp"

namespace mocapdb::gp {

/// Shape of a model to fit.
struct ModelSpec {
    bool hierarchical = true;             ///< false: the MOA baseline
    bool grouped = false;                 ///< three layers (trend → group → child); needs HgpData::groups
    std::size_t parent_terms = 1;         ///< Q of the parent LMC (hierarchical only)
    std::size_t group_terms = 1;          ///< Q of the group LMC (grouped only)
    std::size_t child_terms = 1;          ///< Q of the child LMC
    std::size_t rank = 1;                 ///< columns of every W_q
    KernelType kernel = KernelType::Rbf;  ///< base kernel of every term
    double noise_floor = 1e-6;
    /// initial_model: choose the lengthscales by a coarse likelihood scan (5 factors per layer).
    bool scan_lengthscales = true;
};

/// A deterministic starting point from the data's second moments: per layer, the D×D second-moment
/// matrix of the children's mean (parent) and of the deviations from it (child; MOA: of the values;
/// three layers: the group means' deviations from the mean for the group layer, the children's
/// deviations from their group's mean for the child layer) is shared by the layer's terms; term q's W takes the next `rank` principal directions (80 % of their
/// eigenvalues, plus a small fixed perturbation: a zero W is a stationary point of the likelihood),
/// κ the remaining diagonal (≥ 5 %); the noise starts at 1 % of the child layer's diagonal; lengthscales
/// are spread geometrically between 5 % and 50 % of the time span (20 % for Q = 1) and then, with
/// spec.scan_lengthscales, scaled per layer by the best of 0.25, 0.5, 1, 2, 4 under the likelihood
/// (≤ 25 evaluations without gradient; three layers: the group layer's factor follows the parent's).
HgpModel initial_model(const HgpData& data, const ModelSpec& spec);

enum class FitStatus {
    Converged,         ///< gradient or relative-decrease criterion met
    MaxIterations,     ///< stopped at max_iterations
    LineSearchFailed,  ///< the line search gave up (best point kept)
    NumericalFailure,  ///< the starting point was not usable (covariance not positive definite)
};
std::string to_string(FitStatus status);

struct FitOptions {
    int restarts = 1;                  ///< ≥ 1 runs: the first from the given start, the others perturbed
    std::uint64_t seed = 1;            ///< perturbations of restart k use seed + k
    double restart_spread = 0.5;       ///< std of the perturbation of log-parameters (W: relative)
    int max_iterations = 300;          ///< per restart
    double gradient_tolerance = 1e-5;  ///< on the per-value objective's gradient norm
    double relative_decrease = 1e-7;   ///< stop when the objective improves less over `past` iterations
    int past = 5;
    LikelihoodPath path = LikelihoodPath::Auto;
    int threads = 2;
    ProgressCallback progress;  ///< done = evaluations so far; item = "restart k"
};

struct RestartReport {
    double log_likelihood = 0.0;  ///< best of this restart (−inf when nothing was usable)
    FitStatus status = FitStatus::NumericalFailure;
    std::string message;
    int iterations = 0;
    int evaluations = 0;
    double seconds = 0.0;
};

struct FitResult {
    HgpModel model;  ///< the best parameters over all restarts
    double log_likelihood = 0.0;
    FitStatus status = FitStatus::NumericalFailure;  ///< of the restart that gave the best model
    std::vector<RestartReport> restarts;
    int evaluations = 0;
    double seconds = 0.0;
};

/// Fits `start`'s parameters to `data`. InvalidArgument for inconsistent arguments only.
FitResult fit(const HgpData& data, const HgpModel& start, const FitOptions& options = {});

}  // namespace mocapdb::gp

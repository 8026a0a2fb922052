#pragma once
// Which interpolator blends a set's samples at synthesis time: universal kriging (the papers), RBF (Rose
// et al.), the linear trend alone, or the average of those the cross-validation cannot tell apart, chosen
// by cross-validation on the set itself. The same procedure is
// run by `compress` on the whole set (its choice is stored with the kernel and used by synth and query)
// and by the evaluation inside every outer fold of its nested cross-validation, so that the error the
// evaluation reports for the choice is the error of what synthesis does. Details: docs/synthesis.md.
// Errors: InvalidArgument for bad shapes or options. Thread safety: pure functions.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/rbf.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::synthesis {

/// Average: the mean of the weights of two or three of the others (PredictorChoice::members()); a
/// choice, never a candidate.
enum class Predictor { Kriging, Rbf, Trend, Average };

/// The pose-vector rows the posture metric leaves out: the root's floor position (x, z) and heading (its
/// exponential map's y), as the evaluation's root-relative pose error does.
inline constexpr std::array<Eigen::Index, 3> kRootPathDofs = {0, 2, 4};

/// "kriging", "rbf", "trend", "average".
const char* to_string(Predictor predictor);
/// The predictor of that name; empty for anything else.
std::optional<Predictor> parse_predictor(const std::string& name);
/// Every candidate predictor (not Average), in the order of PredictorChoice::scores.
const std::vector<Predictor>& all_predictors();

struct PredictorScore {
    Predictor predictor = Predictor::Kriging;
    /// Mean over the folds of the held-out sample's root-mean-square value error (the values' units: for
    /// synthesis models the position-weighted pose values of compression/dof_weights.hpp).
    double cv_rms = 0.0;
    /// Paired standard error over the folds of (this candidate's fold error - the lowest one's): SD / sqrt(folds);
    /// 0 for the lowest and with one fold.
    double cv_se = 0.0;
    /// Its share of the weights synthesis uses: 1 for a chosen single predictor, 1 / m for each of m averaged
    /// ones, 0 for the others.
    double weight = 0.0;
};

struct PredictorChoice {
    /// The lowest cv_rms (ties: the earlier in all_predictors()), or Average when other candidates lie within
    /// PredictorChoiceOptions::average_within_se of their paired standard errors of it.
    Predictor chosen = Predictor::Kriging;
    std::vector<PredictorScore> scores;  ///< one per candidate, in all_predictors() order
    std::size_t folds = 0;               ///< held-out samples (each with its twins)
    std::size_t samples = 0;             ///< samples the choice saw (N, or max_samples of them)
    /// The candidates synthesis blends (weight > 0), in scores order: the chosen one, or the averaged ones.
    std::vector<Predictor> members() const;
};

struct PredictorChoiceOptions {
    std::size_t folds = 15;            ///< held-out samples, evenly spread in sample order; >= 1
    std::size_t max_samples = 1000;    ///< larger sets choose on this many, evenly spread (O(n^3) per fold); >= 5
    double elements_per_sample = 1.0;  ///< cv_rms divides a fold's squared error by this (e.g. D x T)
    kriging::RbfOptions rbf;
    /// The predictors to choose among (a subset of all_predictors(), in that order; not empty).
    std::vector<Predictor> candidates = all_predictors();
    /// Candidates whose cv_rms exceeds the lowest by at most this many of their paired standard errors are
    /// averaged with it (a pick among them would follow the folds' noise); 0: the lowest alone. >= 0.
    double average_within_se = 1.0;
};

/// The cross-validated choice for samples at normalized control points xc (N by P) with values (N by S,
/// finite): fold k leaves out sample i_k and its twins (twins: empty or N lists, sample i's twins, the
/// samples that show some of its frames: dataset/sample_twins.hpp SampleTwins::partners), builds every
/// candidate on the remaining samples (kriging with `variogram` and `kriging`, RBF with options.rbf, the
/// trend of kriging.trend) and scores the held-out values (the Euclidean norm: callers pass values whose
/// distances are the metric, e.g. posture_values). Folds with fewer than 3 training rows are skipped;
/// when none remains, folds = 0 and the choice stays kriging. The lowest mean wins, averaged with the
/// candidates within options.average_within_se paired standard errors of it (Average). InvalidArgument
/// when shapes disagree, values are not finite or options are out of range.
PredictorChoice choose_predictor(const Eigen::Ref<const MatX>& xc, const Eigen::Ref<const MatX>& values,
                                 const kriging::VariogramModel& variogram, const kriging::KrigingOptions& kriging,
                                 const std::vector<std::vector<std::size_t>>& twins,
                                 const PredictorChoiceOptions& options = {});

/// "rbf (cv 2.02, kriging 2.1 ± 0.05, trend 2.71 ± 0.2; 15 folds of 45 samples)" or "average of kriging,
/// rbf (cv 2.02 ...)": the choice in one line (± the paired standard error against the lowest).
std::string describe(const PredictorChoice& choice);

/// Rows of `weighted_rows` (N by D T, sample i's position-weighted pose values at column t D + k) with the
/// kRootPathDofs columns set to 0: their distances are the posture metric the choice is scored on.
MatX posture_values(const Eigen::Ref<const MatX>& weighted_rows, Eigen::Index dofs);

}  // namespace mocapdb::synthesis

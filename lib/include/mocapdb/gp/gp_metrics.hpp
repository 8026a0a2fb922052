#pragma once
// Accuracy of interpolation (MSE, SMSE, MSLL) and similarity of synthesized motions (MCC, MLC).
//
// A score undefined for its input (a correlation of a constant sequence, an SMSE without test
// variance) is an empty std::optional, never NaN. Details: docs/headers/gp.md (mocapdb/gp/gp_metrics.hpp).
#include <optional>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb::gp {

struct InterpolationScores {
    double mse = 0.0;
    std::optional<double> smse;  ///< empty when every output's test values are constant (no variance)
    double msll = 0.0;
    std::size_t points = 0;  ///< test values (outputs × test frames)
};

/// Scores predictions of D outputs at test frames. `truth`, `mean`, `variance` (predictive, of y): D by
/// T_test; `train_mean`, `train_variance`: D values of the training data (for MSLL). InvalidArgument on
/// shape mismatch, non-positive variances, or fewer than 2 test frames (SMSE needs a variance).
InterpolationScores interpolation_scores(const MatX& truth, const MatX& mean, const MatX& variance,
                                         const VecX& train_mean, const VecX& train_variance);

/// Each row of `signals` (D by T) mapped to [0, 1] by its own min and max (constant rows become 0).
MatX minmax_rows(const MatX& signals);

/// Max over lags of the full cross-correlation Σ_m a[m]·b[m + lag] of two sequences (any lengths).
double max_cross_correlation(const VecX& a, const VecX& b);
/// Pearson correlation; empty when either sequence is constant. Same length (>= 2) required.
std::optional<double> pearson(const VecX& a, const VecX& b);

/// MCC(generated, real): both D by T (T may differ), normalized with minmax_rows first.
double mean_cross_correlation(const MatX& generated, const MatX& real);
/// MLC(generated, real): both D by T (same T), normalized first; outputs where either is constant are
/// skipped (empty when all are).
std::optional<double> mean_linear_correlation(const MatX& generated, const MatX& real);

struct MeanStd {
    double mean = 0.0;
    double std = 0.0;  ///< population standard deviation
};
MeanStd mean_std(const std::vector<double>& values);
/// mean_std of the values when every one exists; empty when any is missing (one undefined score leaves
/// the summary undefined).
std::optional<MeanStd> mean_std_of_all(const std::vector<std::optional<double>>& values);

struct SynthesisScores {
    std::vector<MeanStd> mcc;                 ///< per real motion: over the generated ones
    std::vector<std::optional<MeanStd>> mlc;  ///< empty where some generated motion's MLC is undefined
};
/// MCC and MLC of every generated motion against every real one, summarized per real motion.
SynthesisScores synthesis_scores(const std::vector<MatX>& generated, const std::vector<MatX>& real);

}  // namespace mocapdb::gp

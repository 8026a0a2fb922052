#pragma once
// Accuracy of interpolation (MSE, SMSE, MSLL) and similarity of synthesized motions (MCC, MLC).
//
// Details: docs/headers/gp.md (mocapdb/gp/gp_metrics.hpp).
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb::gp {

struct InterpolationScores {
    double mse = 0.0;
    double smse = 0.0;
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
/// Pearson correlation; NaN when either sequence is constant. Same length required.
double pearson(const VecX& a, const VecX& b);

/// MCC(generated, real): both D by T (T may differ), normalized with minmax_rows first.
double mean_cross_correlation(const MatX& generated, const MatX& real);
/// MLC(generated, real): both D by T (same T), normalized first; outputs where either is constant are
/// skipped (NaN when all are).
double mean_linear_correlation(const MatX& generated, const MatX& real);

struct MeanStd {
    double mean = 0.0;
    double std = 0.0;  ///< population standard deviation
};
MeanStd mean_std(const std::vector<double>& values);

struct SynthesisScores {
    std::vector<MeanStd> mcc;  ///< per real motion: over the generated ones
    std::vector<MeanStd> mlc;
};
/// MCC and MLC of every generated motion against every real one, summarized per real motion.
SynthesisScores synthesis_scores(const std::vector<MatX>& generated, const std::vector<MatX>& real);

}  // namespace mocapdb::gp

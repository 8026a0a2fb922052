#pragma once
// Choosing the multilinear ranks (R1, R2, R3) of a Tucker model of a D by T by N tensor A.
//
// Details: docs/headers/tensor.md (mocapdb/tensor/rank_selection.hpp).
#include <Eigen/Core>

#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::tensor {

enum class RankCriterion { Explicit, TargetError, TargetCompression, Tolerance };

struct RankSelection {
    Ranks ranks{0, 0, 0};
    RankCriterion criterion = RankCriterion::Explicit;
    double target = 0.0;             ///< the requested error, ratio or tolerance (0 for Explicit)
    double bound_relative = 0.0;     ///< HOSVD bound / ||A||_F at ranks
    double measured_relative = 0.0;  ///< ||A - A_hat||_F / ||A||_F of the HOSVD at ranks, by reconstruction
    Eigen::Index parameters = 0;     ///< tucker_parameter_count
    double compression_ratio = 0.0;
    /// Target error: measured_relative <= target; target ratio: compression_ratio >= target;
    /// explicit, tolerance: true. False means no rank triple met the target (ranks are the closest).
    bool target_met = true;
    TuckerModel model;  ///< the HOSVD at ranks
};

/// Ranks with the fewest parameters whose HOSVD bound is <= target_relative * ||A||_F.
/// spectra: from hosvd_bases(); target_relative >= 0 and finite. Throws InvalidArgument otherwise.
Ranks ranks_for_error_bound(const ModeSpectra& spectra, double target_relative);

/// Ranks with the smallest HOSVD bound whose compression ratio is >= target_ratio; (1, 1, 1) when none
/// is. target_ratio > 0 and finite. Throws InvalidArgument otherwise.
Ranks ranks_for_compression(const ModeSpectra& spectra, double target_ratio);

/// Per-mode numerical rank: #{ i : sigma_i^(n) > tolerance * sigma_1^(n) } (at least 1).
/// tolerance in [0, 1). Throws InvalidArgument otherwise.
Ranks ranks_for_tolerance(const ModeSpectra& spectra, double tolerance);

/// a: D by T by N, non-empty, finite, for every function below.
/// Explicit ranks: 1 <= ranks[n] <= dims[n]. Throws InvalidArgument on bad arguments.
RankSelection select_ranks(const Tensor3& a, const Ranks& ranks);
/// Target relative error (relative RMSE) >= 0. See the header comment.
RankSelection select_ranks_for_error(const Tensor3& a, double target_relative, bool refine_by_measurement = true);
/// Target compression ratio > 0.
RankSelection select_ranks_for_compression(const Tensor3& a, double target_ratio);
/// Singular-value tolerance in [0, 1).
RankSelection select_ranks_for_tolerance(const Tensor3& a, double tolerance);

}  // namespace mocapdb::tensor

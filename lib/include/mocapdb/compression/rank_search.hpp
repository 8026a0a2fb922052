#pragma once
// Choosing Tucker ranks of a set model by a target on the measured error (issue #4): the smallest
// model whose max joint-position error (cm, after forward kinematics) or dof-space RMSE meets the
// target, or the model with the best error at a target compression ratio.
//
// The candidates are the rank triples with the fewest parameters whose HOSVD bound is ≤ e·‖X‖ for a
// relative error e (tensor::ranks_for_error_bound): one triple per e, so the search is a bisection
// over e. The max joint error is not exactly monotone in e; the bisection keeps the best triple it
// has measured that meets the target, so the result always meets it (full ranks reproduce the data;
// they are measured, and returned, only when no probe meets the target).
#include <functional>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::compression {

/// The weighted centred tensor with its HOSVD bases, computed once and shared by every search.
struct PreparedSet {
    Tensor3 x;                 ///< weighted_centred(poses, mean, weight)
    VecX mean;
    VecX weight;
    tensor::HosvdBases bases;  ///< eigenbases and spectra of x's mode Gram matrices (tensor::hosvd_bases)
};

PreparedSet prepare_set(const Tensor3& poses, const VecX& weight);

/// The HOSVD model at ranks, from the prepared bases (no Gram recomputation).
SetModel hosvd_model(const PreparedSet& prepared, const tensor::Ranks& ranks);

struct RankSearchResult {
    SetModel model;                 ///< HOSVD at the chosen ranks
    compression::JointErrorStats stats;    ///< measured for model
    bool target_met = false;
    int evaluations = 0;            ///< models reconstructed and measured
};

/// Smallest-bound ranks whose measured max joint error is ≤ max_cm (> 0). meter's reference must be
/// the poses `prepared` was made from. `progress`: done = bisection steps taken, total = steps + 1
/// (the last unit measures the chosen model).
RankSearchResult search_ranks_for_max_error(const PreparedSet& prepared, const compression::JointErrorMeter& meter,
                                            double max_cm, const ProgressCallback& progress = {});

/// Smallest-bound ranks whose measured RMSE of X (the weighted, centred tensor) is ≤ rmse (≥ 0).
/// `progress` as for search_ranks_for_max_error.
RankSearchResult search_ranks_for_rmse(const PreparedSet& prepared, const compression::JointErrorMeter& meter, double rmse,
                                       const ProgressCallback& progress = {});

/// The ranks with the smallest HOSVD bound among those with compression ratio ≥ ratio (> 0).
RankSearchResult ranks_for_ratio(const PreparedSet& prepared, const compression::JointErrorMeter& meter, double ratio);

}  // namespace mocapdb::compression

#pragma once
// Choosing Tucker ranks of a set model by a target on the measured error: the smallest
// model whose max joint-position error (cm, after forward kinematics) or dof-space RMSE meets the
// target, or the model with the best error at a target compression ratio.
//
// Details: docs/headers/compression.md (mocapdb/compression/rank_search.hpp).
#include <functional>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::compression {

/// The weighted centred tensor with its HOSVD bases, computed once and shared by every search.
struct PreparedSet {
    Tensor3 x;  ///< weighted_centred(poses, mean, weight); empty when in_place is set
    VecX mean;
    VecX weight;
    tensor::HosvdBases bases;           ///< eigenbases and spectra of x's mode Gram matrices (tensor::hosvd_bases)
    const Tensor3* in_place = nullptr;  ///< prepare_set_in_place: the caller's tensor, holding x's values

    /// The weighted, centred tensor, wherever it is held.
    const Tensor3& weighted() const { return in_place ? *in_place : x; }
};

PreparedSet prepare_set(const Tensor3& poses, const VecX& weight);

/// prepare_set with the weighted, centred values (the same, bit for bit) written over `poses`
/// instead of a copy (#16: 0.48 GB at 11 070 windows): the prepared set borrows the tensor, which the
/// caller keeps alive and unchanged while it is used; JointErrorMeter's weighted-reference
/// constructor reads the poses back from it.
PreparedSet prepare_set_in_place(Tensor3& poses, const VecX& weight);

/// The HOSVD model at ranks, from the prepared bases (no Gram recomputation).
SetModel hosvd_model(const PreparedSet& prepared, const tensor::Ranks& ranks);

struct RankSearchResult {
    SetModel model;                      ///< HOSVD at the chosen ranks
    compression::JointErrorStats stats;  ///< measured for model
    bool target_met = false;
    int evaluations = 0;        ///< models reconstructed and checked (on a screen or in full)
    int full_checks = 0;        ///< of them (or the chosen one again), checked on every pose
    int truncation_checks = 0;  ///< screens and full checks decided on the truncation reconstruction
};

/// Samples a probe is screened on by default (see the header comment): about 1/20 of a set of
/// 10 000 windows; sets of up to 4 times as many samples are not screened.
constexpr Eigen::Index kDefaultScreenSamples = 512;

/// Smallest-bound ranks whose measured max joint error is ≤ max_cm (> 0). meter's reference must be
/// the poses `prepared` was made from. `progress`: done = bisection steps taken, total = steps + 1
/// (the last unit measures the chosen model). screen_samples (>= 0; 0: no screening): see the
/// header comment. The result does not depend on the number of mocapdb's worker threads (LAPACK and
/// OpenBLAS, which compute the bases, may change the last digits with their own thread count:
/// OPENBLAS_NUM_THREADS=1 moved the max error by 1e-9 cm at 11 070 windows, same ranks and bytes). Throws InvalidArgument on a
/// bad target or screen_samples.
RankSearchResult search_ranks_for_max_error(const PreparedSet& prepared, const compression::JointErrorMeter& meter,
                                            double max_cm, const ProgressCallback& progress = {},
                                            Eigen::Index screen_samples = kDefaultScreenSamples);

/// The same search, taking the prepared set: the model takes the bases' storage instead of a copy of
/// their leading columns, and prepared.x (when it holds the weighted tensor) is released first (#16:
/// the search's peak memory at 11 070 windows falls by the 0.29 GB sample basis and the 0.1 GB
/// core). prepared is left empty.
RankSearchResult search_ranks_for_max_error(PreparedSet&& prepared, const compression::JointErrorMeter& meter,
                                            double max_cm, const ProgressCallback& progress = {},
                                            Eigen::Index screen_samples = kDefaultScreenSamples);

/// Smallest-bound ranks whose measured RMSE of X (the weighted, centred tensor) is ≤ rmse (≥ 0).
/// `progress` as for search_ranks_for_max_error.
RankSearchResult search_ranks_for_rmse(const PreparedSet& prepared, const compression::JointErrorMeter& meter,
                                       double rmse, const ProgressCallback& progress = {});

/// The ranks with the smallest HOSVD bound among those with compression ratio ≥ ratio (> 0).
RankSearchResult ranks_for_ratio(const PreparedSet& prepared, const compression::JointErrorMeter& meter, double ratio);

}  // namespace mocapdb::compression

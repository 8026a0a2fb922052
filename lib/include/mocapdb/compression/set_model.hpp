#pragma once
// The compressed form of an aligned motion set: a Tucker model of the weighted, centred pose tensor
//     X(d, t, n) = (A(d, t, n) − mean_d) · weight_d,
// A the D × T × N pose vectors (aligned_set.hpp), mean_d the mean of dof d over frames and samples,
// weight_d from dof_weights.hpp (so that |X − X̂| ≤ E everywhere keeps every joint within E cm).
#include <optional>
#include <vector>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/tensor/hooi.hpp"
#include "mocapdb/tensor/sample_decoder.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::compression {

/// Per dof: mean over frames and samples (D entries).
VecX dof_means(const Tensor3& poses);
/// X = (A − mean) · weight, per dof row. Throws InvalidArgument on a length mismatch or weight ≤ 0.
Tensor3 weighted_centred(const Tensor3& poses, const VecX& mean, const VecX& weight);
/// weighted_centred's values written over `poses` (the same arithmetic, so the same values bit for bit).
void weighted_centred_in_place(Tensor3& poses, const VecX& mean, const VecX& weight);
/// The inverse: A = X / weight + mean.
Tensor3 from_weighted_centred(const Tensor3& x, const VecX& mean, const VecX& weight);

struct SetModel {
    tensor::TuckerModel tucker;  ///< of X (fit, error_bound and data_norm are in X's units)
    VecX mean;                   ///< D
    VecX weight;                 ///< D, > 0

    Eigen::Index dofs() const { return mean.size(); }
    /// Reconstructed pose vectors, D × T × N.
    Tensor3 reconstruct() const;
    /// At a level of detail lod (1 ≤ lod[n] ≤ ranks[n]).
    Tensor3 reconstruct(const tensor::Ranks& lod) const;
};

/// A model's pose vectors a few samples at a time (for JointErrorMeter::measure_within): the values
/// SetModel::reconstruct() gives (both decode through tensor::SampleDecoder), without a D x T x N
/// tensor. Sample n is the decoder's sample n, divided by the weights, plus the mean.
/// Keeps a pointer to model: the model must outlive it. Thread-safe (const).
class SampleReconstruction {
public:
    explicit SampleReconstruction(const SetModel& model);
    /// The same for the model with core the block [0, R1) x [0, R2) x [0, R3) of `core` (ranks, each
    /// at most core's dimension), bases the first R1, R2, R3 columns of dof_basis, time_basis and
    /// sample_basis, mean and weight: that model's reconstruct() without copying its N by R3 sample
    /// basis (#16: the rank search's probes, sliced from the full core and bases). Keeps views of the
    /// bases, mean and weight: they must outlive it. Throws InvalidArgument when a rank exceeds the
    /// core's dimension or a basis has fewer columns than the rank, or mean and weight are not D long.
    SampleReconstruction(const Tensor3& core, const tensor::Ranks& ranks, const Eigen::Ref<const MatX>& dof_basis,
                         const Eigen::Ref<const MatX>& time_basis, const MatX& sample_basis, const VecX& mean,
                         const VecX& weight);
    /// Writes samples (each in [0, N)) side by side into out, resized to D by (T samples.size()).
    /// Throws InvalidArgument on a sample out of range.
    void operator()(const std::vector<Eigen::Index>& samples, MatX& out) const;

private:
    tensor::SampleDecoder decoder_;
    const VecX* mean_;
    const VecX* weight_;
};

/// Decomposes the weighted, centred tensor of `poses` at explicit ranks with `method`.
/// Throws InvalidArgument for bad ranks, shapes or non-finite values.
SetModel fit_set_model(const Tensor3& poses, const VecX& weight, const tensor::Ranks& ranks,
                       tensor::TuckerMethod method, const tensor::HooiOptions& hooi = {});
/// The same from x = weighted_centred(poses, mean, weight) (mean = dof_means(poses)): the same model.
SetModel fit_weighted_set_model(const Tensor3& x, const VecX& mean, const VecX& weight, const tensor::Ranks& ranks,
                                tensor::TuckerMethod method, const tensor::HooiOptions& hooi = {});

/// Throws InvalidArgument unless the parts agree: bases D × R1, T × R2, N × R3 with core R1 × R2 × R3,
/// mean and weight of length D, weights > 0, everything finite. `where` names the caller.
void check(const SetModel& model, const char* where);

}  // namespace mocapdb::compression

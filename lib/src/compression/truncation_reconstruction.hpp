#pragma once
// Internal to the compression module: a rank-search probe's pose vectors from what its sample-mode
// truncation leaves out.
//
// For bases whose sample basis spans the projected samples (HosvdBases::spans_projected_samples) the
// HOSVD model's terms over all K sample columns add up to each sample's projection, so the model at
// ranks (R1, R2, R3), R1 <= k0 and R2 <= k1 (HosvdBases::projected_dofs, projected_frames), is
//     X_hat(:, :, n) = P1 X(:, :, n) P2 - sum_{R3 <= k < K} U_sample(n, k) D_k,
// P1 = U_dof U_dof^T and P2 = U_time U_time^T on the leading R1 and R2 columns, D_k = U_dof core_k
// U_time^T the model's term k. Per sample that costs D T (K - R3) plus the two projections instead of
// D T R3 (cheaper_than_direct): at 1 cm on 11 070 windows the chosen R3 is 3 234 of K = 3 719.
// The values equal SampleReconstruction's up to the energy the sample basis leaves out (eigenvalues
// below 1e-14 of the largest) and rounding: 4e-7 cm apart in the max joint error at 11 070 windows.
// So the search decides on them, and measures the model it returns with SampleReconstruction.
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::compression::detail {

class TruncationReconstruction {
public:
    /// Whether the identity above holds for `bases` at `ranks` (factored core, spanning sample basis,
    /// R1 <= k0, R2 <= k1, R3 <= K).
    static bool applies(const tensor::HosvdBases& bases, const tensor::Ranks& ranks);
    /// Whether it applies and costs fewer multiply-adds per sample than SampleReconstruction.
    static bool cheaper_than_direct(const tensor::HosvdBases& bases, const tensor::Ranks& ranks);

    /// x: the weighted centred tensor the bases were computed from (D by T by N); mean and weight as
    /// in SampleReconstruction. Keeps pointers to x, bases, mean and weight: they must outlive it.
    /// Throws InvalidArgument when !applies(bases, ranks) or the shapes disagree.
    TruncationReconstruction(const Tensor3& x, const tensor::HosvdBases& bases, const tensor::Ranks& ranks,
                             const VecX& mean, const VecX& weight);
    /// SampleReconstruction's contract: samples side by side into out (D by T samples.size()).
    /// Thread-safe (const). Throws InvalidArgument on a sample out of range.
    void operator()(const std::vector<Eigen::Index>& samples, MatX& out) const;

private:
    const Tensor3* x_;
    const tensor::HosvdBases* bases_;
    tensor::Ranks ranks_;
    const VecX* mean_;
    const VecX* weight_;
    MatX dropped_terms_;  ///< D_k for R3 <= k < K, unfolded: D T by K - R3
};

}  // namespace mocapdb::compression::detail

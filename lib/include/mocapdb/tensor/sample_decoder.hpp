#pragma once
// Samples of a Tucker model, a few at a time: the values TuckerModel::reconstruct() gives (it decodes
// through this class), without a D x T x N tensor (the rank search measures 10 000
// windows chunk by chunk).
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::tensor {

/// The model with core the block [0, R0) x [0, R1) x [0, R2) of `core` and bases the first R0, R1, R2
/// columns of u0 (D by >= R0), u1 (T by >= R1) and u2 (N by >= R2). Sample n is U0 S U1^T with S
/// (R0 by R1) the core's sample-mode unfolding times u2(n, :)^T: the sample-mode product first, the
/// fewest operations (R0 R1 R2 + D R0 R1 + D T R1 per sample against D T R2 the other way round).
/// Samples are decoded kColumns or more at a time, padded with zero columns to a multiple of 8, so
/// that every product has shapes on which Eigen takes the same kernel path for every column: a
/// sample's values do not depend on which samples are decoded with it, nor on the thread count.
/// Copies the core block (R0 R1 R2 values); keeps views of u0, u1, u2: they must outlive it.
/// Throws InvalidArgument when a rank is < 1 or beyond the core or a basis. Thread-safe (const).
class SampleDecoder {
public:
    SampleDecoder(const Tensor3& core, const Ranks& ranks, const Eigen::Ref<const MatX>& u0,
                  const Eigen::Ref<const MatX>& u1, const Eigen::Ref<const MatX>& u2);
    /// The whole model (ranks = model.ranks).
    explicit SampleDecoder(const TuckerModel& model);

    Eigen::Index dofs() const { return u0_.rows(); }
    Eigen::Index frames() const { return u1_.rows(); }
    Eigen::Index samples() const { return u2_.rows(); }

    /// Writes samples `ids` (each in [0, N)) side by side into out, resized to D by T ids.size().
    /// Throws InvalidArgument on a sample out of range.
    void decode(const std::vector<Eigen::Index>& ids, MatX& out) const;
    /// Every sample, in order, into a D x T x N tensor (chunks on the machine's cores).
    Tensor3 decode_all() const;

private:
    using View = Eigen::Map<const MatX, 0, Eigen::OuterStride<>>;
    static constexpr Eigen::Index kColumns = 32;
    MatX core_;  ///< R0 R1 by R2: the block's sample-mode unfolding
    View u0_, u1_, u2_;
};

}  // namespace mocapdb::tensor

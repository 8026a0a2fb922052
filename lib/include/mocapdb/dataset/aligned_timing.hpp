#pragma once
// The timing and shape of a set's aligned form without its pose values: what a model that keeps its
// own representation of the poses needs from the aligned set (the compressed synthesis model uses only
// the warps and the tensor's D × T × N). Loading it (Database::load_aligned_timing) reads neither the
// tensor nor the per-dof normalization, so it costs what the warps cost, not the D × T × N doubles.
#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/aligned_set.hpp"

namespace mocapdb {

struct AlignedTiming {
    Eigen::Index dof_count = 0;  ///< D of the aligned tensor
    /// T by N, as AlignedSet::warps: warps(t, n) is the (fractional) frame of sample n shown at
    /// aligned frame t, strictly increasing in t.
    MatX warps;

    Eigen::Index dofs() const { return dof_count; }
    Eigen::Index frames() const { return warps.rows(); }
    Eigen::Index samples() const { return warps.cols(); }
    /// T − 1 by N: warps(t + 1, n) − warps(t, n) (as AlignedSet::inverse_warp_increments).
    MatX inverse_warp_increments() const;
};

/// The timing of a whole aligned set (its warps copied; D from its tensor). Does not validate.
AlignedTiming timing_of(const AlignedSet& aligned);

/// Throws InvalidArgument ("aligned set: ...", as validate(AlignedSet)) unless D >= 6, T >= 2, N >= 1
/// and the warps are finite and strictly increasing.
void validate(const AlignedTiming& timing);

}  // namespace mocapdb
